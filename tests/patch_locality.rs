//! docs/math.md §5 and §11: an edit of any patch of a design re-blends only
//! its window and, downstream, only what its moved edge reaches, and the
//! world still equals `Document::build` bit for bit. Three G1-chained cars
//! (the bench's `ecs/patches/car-x3`), an edit in each position: the
//! patches before it keep their stacks (not even marked changed); the
//! edited one (through its kept levels, `ecs::joined::KeptPatch`, when it is
//! not the first) re-blends no more tangents than the first car's own
//! incremental pipeline does for the same edit, less than a whole build,
//! and places again only the rows of its window; the ones after it keep their
//! levels and place again the rows whose start moved. Negative control: a
//! structure change (a column added) builds the patch whole, counting every
//! tangent.

mod common;

use bevy::prelude::*;
use common::built::{assert_as_built, changed_ticks, patches};
use streamline_kernel::{DQuat, DVec3};
use streamline_studio::cli::bench::patches::chained_cars;
use streamline_studio::ecs::joined::{PatchSurface, PatchWork};
use streamline_studio::ecs::{self, Edit, ModelConfig, Stats};
use streamline_studio::scene::edits::patch_edit::PatchEdit;

const DEPTH: u32 = 4;

fn work(app: &App, e: Entity) -> PatchWork {
    app.world()
        .get::<PatchWork>(e)
        .cloned()
        .expect("a patch built through its kept levels reports its work")
}

/// Tangents of levels `1 ..= d` of patch `e` (a whole build's count).
fn whole_count(app: &App, e: Entity) -> usize {
    let s = app.world().get::<PatchSurface>(e).unwrap();
    let stack = s.stack().expect("built");
    stack.levels[1..]
        .iter()
        .map(|l| l.tangents.data().len())
        .sum()
}

#[test]
fn an_edit_of_any_of_three_chained_cars_is_local_and_equals_the_whole_build() {
    // what the first car's own pipeline re-blends for the edit
    let (mut first, mut first_rows) = (0, 0);
    for p in 0..3 {
        let mut doc = chained_cars(3, DEPTH);
        let mut app = ecs::headless_document_app(&doc, None, ModelConfig::default());
        let ids = patches(&mut app);
        if p > 0 {
            let name = doc.patches[p].name.clone();
            ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch(name))).unwrap();
        }
        let before = changed_ticks(&mut app);
        let dir = DQuat::from_rotation_y(0.05) * doc.patches[p].design.net().get(2, 4);
        ecs::apply(
            &mut app,
            Edit::SetDirection {
                row: 2,
                col: 4,
                dir,
            },
        )
        .unwrap();
        doc.patches[p].design.set_tangent(2, 4, dir).unwrap();
        assert_as_built(&mut app, &doc);
        let after = changed_ticks(&mut app);
        for k in 0..p {
            assert_eq!(
                after[k], before[k],
                "edit of car {p}: car {k} before it kept"
            );
        }
        assert_ne!(after[p], before[p], "edit of car {p}: rebuilt");
        let rows = app
            .world()
            .get::<PatchSurface>(ids[p])
            .unwrap()
            .stack()
            .unwrap()
            .finest()
            .tangents
            .rows();
        let all = whole_count(&app, ids[p]);
        if p == 0 {
            let stats = &app.world().resource::<Stats>().last;
            (first, first_rows) = (stats.tangents_reblended, stats.streamlines_reintegrated);
            assert!(
                first > 0 && first < all,
                "the pipeline re-blended {first} of {all}"
            );
        } else {
            let w = work(&app, ids[p]);
            assert!(!w.whole, "edit of car {p}: updated in place, {w:?}");
            assert!(
                w.reblended > 0 && w.reblended <= first,
                "edit of car {p}: re-blended {} of {all}, the first car's pipeline {first}",
                w.reblended
            );
            let span = w.rows.expect("rows placed again");
            assert!(
                span.hi - span.lo < first_rows && first_rows < rows,
                "edit of car {p}: rows {span:?} of {rows}, the first car's pipeline {first_rows}"
            );
        }
        for k in p + 1..3 {
            assert_ne!(
                after[k], before[k],
                "edit of car {p}: car {k} on its moved end"
            );
            let w = work(&app, ids[k]);
            assert_eq!(
                (w.whole, w.reblended),
                (false, 0),
                "edit of car {p}: car {k} keeps its levels"
            );
        }
    }
}

/// A drag of the last car: every frame is an update in place, equal to the
/// whole build after the last; then another display depth builds every
/// kept patch whole (the negative control of the counts above).
#[test]
fn a_drag_of_the_last_car_stays_in_place_and_another_depth_builds_it_whole() {
    let mut doc = chained_cars(3, DEPTH);
    let mut app = ecs::headless_document_app(&doc, None, ModelConfig::default());
    let ids = patches(&mut app);
    let name = doc.patches[2].name.clone();
    ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch(name))).unwrap();
    let mut dir = doc.patches[2].design.net().get(3, 5);
    for k in 0..6 {
        dir = DQuat::from_axis_angle(
            DVec3::new(0.3, 1.0, 0.2).normalize(),
            0.02 * (k as f64 - 2.5),
        ) * dir;
        ecs::apply(
            &mut app,
            Edit::SetDirection {
                row: 3,
                col: 5,
                dir,
            },
        )
        .unwrap();
        let w = work(&app, ids[2]);
        assert!(!w.whole && w.reblended > 0, "frame {k}: {w:?}");
    }
    doc.patches[2].design.set_tangent(3, 5, dir).unwrap();
    assert_as_built(&mut app, &doc);
    // control: another display depth builds every kept patch whole
    ecs::apply(&mut app, Edit::SetDisplayDepth(DEPTH - 1)).unwrap();
    for &e in &ids[1..] {
        let w = work(&app, e);
        assert!(w.whole, "{w:?}");
        assert_eq!(w.reblended, whole_count(&app, e));
    }
    doc.display_depth = DEPTH - 1;
    assert_as_built(&mut app, &doc);
}
