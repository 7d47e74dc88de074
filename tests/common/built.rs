//! What the tests of several patches compare (docs/math.md §11): each
//! patch's entity and built stack, and the world against
//! `Document::build` (the scene library's build, an independent path
//! through the same kernel), bit for bit.

use bevy::prelude::*;
use streamline_kernel::DVec3;
use streamline_kernel::joins::{SeamReport, Stack};
use streamline_studio::ecs::joined::{PatchSlot, PatchSurface, SeamState};
use streamline_studio::ecs::patch::Patch;
use streamline_studio::scene::design::document::Document;

/// Each patch's entity, in the document's order.
pub fn patches(app: &mut App) -> Vec<Entity> {
    let w = app.world_mut();
    let mut q = w.query_filtered::<(Entity, &PatchSlot), With<Patch>>();
    let mut v: Vec<_> = q.iter(w).map(|(e, s)| (s.index, e)).collect();
    v.sort();
    v.into_iter().map(|(_, e)| e).collect()
}

pub fn stack(app: &App, e: Entity) -> Stack {
    let s = app
        .world()
        .get::<PatchSurface>(e)
        .expect("a document patch has a surface");
    match &s.built {
        Some(Ok(s)) => s.clone(),
        other => panic!("not built: {other:?}"),
    }
}

pub fn seam(app: &App, e: Entity) -> SeamReport {
    let s = app
        .world()
        .get::<SeamState>(e)
        .expect("a joined patch has a seam");
    s.report.clone().expect("the seam is measured")
}

pub fn bits(g: &streamline_kernel::Grid<DVec3>) -> Vec<[u64; 3]> {
    g.data()
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect()
}

/// The world's patches and seams equal `Document::build`'s, bit for bit.
pub fn assert_as_built(app: &mut App, doc: &Document) {
    let depth = doc.display_depth;
    let built = doc.build(depth).unwrap();
    let ids = patches(app);
    assert_eq!(ids.len(), doc.patches.len());
    for (i, &e) in ids.iter().enumerate() {
        let s = stack(app, e);
        assert_eq!(s.depth(), depth);
        let name = &doc.patches[i].name;
        for (d, (l, w)) in s.levels.iter().zip(&built.patches[i].levels).enumerate() {
            let f = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(&l.tangents),
                bits(&w.tangents),
                "{name} depth {d} tangents"
            );
            assert_eq!(
                f(l.params.s.data()),
                f(w.params.s.data()),
                "{name} depth {d} s"
            );
            assert_eq!(f(&l.params.t), f(&w.params.t), "{name} depth {d} t");
            assert_eq!(f(&l.params.sigma), f(&w.params.sigma), "{name} depth {d} σ");
        }
        for d in 0..=depth as usize {
            assert_eq!(
                bits(&s.points[d]),
                bits(&built.patches[i].points[d]),
                "patch {} depth {d}",
                doc.patches[i].name
            );
        }
    }
    for sm in &built.seams {
        let r = seam(app, ids[sm.b]);
        assert_eq!(r.gap.to_bits(), sm.report.gap.to_bits());
        assert_eq!(r.angle_deg.to_bits(), sm.report.angle_deg.to_bits());
        assert_eq!(r.curvature_dev.to_bits(), sm.report.curvature_dev.to_bits());
    }
}

pub fn changed_ticks(app: &mut App) -> Vec<bevy::ecs::change_detection::Tick> {
    let ids = patches(app);
    let w = app.world();
    ids.iter()
        .map(|&e| {
            w.entity(e)
                .get_ref::<PatchSurface>()
                .unwrap()
                .last_changed()
        })
        .collect()
}

/// The census's totals are the sums of its patches' counts.
pub fn census_adds_up(c: &streamline_studio::ecs::census::Census) {
    assert_eq!(
        c.levels,
        c.per_patch.iter().map(|p| p.levels).sum::<usize>()
    );
    assert_eq!(
        c.streamlines,
        c.per_patch.iter().map(|p| p.streamlines).sum::<usize>()
    );
}
