//! Several patches in the ECS world (docs/math.md §11): a
//! document's patches are entities; the joined ones are built through the
//! kernel's joins into `PatchSurface`, with a `SeamState` per join, and
//! rebuilt by change detection. Checked against `Document::build` (the
//! scene library's build, an independent path through the same kernel).

mod common;

use common::built::{assert_as_built, bits, changed_ticks, patches, stack};

use bevy::prelude::*;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_studio::ecs::census::census;
use streamline_studio::ecs::joined::PatchSurface;
use streamline_studio::ecs::patch::{Direction, PatchIndex};
use streamline_studio::ecs::{self, Edit, ModelConfig};
use streamline_studio::scene::design::document::Document;
use streamline_studio::scene::design::document_io::load;

fn hood() -> Document {
    load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron")).unwrap()
}

fn app(doc: &Document) -> App {
    ecs::headless_document_app(doc, None, ModelConfig::default())
}

/// Sets tangent (`row`, `col`) of the first patch to `dir` through the
/// edit stage, and in `doc`, the design the world must equal.
fn set_first(app: &mut App, doc: &mut Document, row: usize, col: usize, dir: DVec3) {
    ecs::apply(app, Edit::SetDirection { row, col, dir }).unwrap();
    doc.patches[0].design.set_tangent(row, col, dir).unwrap();
}

#[test]
fn a_document_is_one_patch_entity_per_patch_built_as_the_scene_library_builds_it() {
    let doc = hood();
    let mut app = app(&doc);
    let c = census(app.world_mut());
    assert_eq!(c.patches, 3);
    let handles: usize = doc
        .patches
        .iter()
        .map(|p| p.design.net().data().len())
        .sum();
    assert_eq!(c.handles.surface, handles);
    assert_as_built(&mut app, &doc);
    // the first patch keeps the incremental pipeline: its mesh is a one-patch scene's
    let one = ecs::headless_app(doc.patch_scene(0));
    assert_eq!(bits(&common::points(&app)), bits(&common::points(&one)));
}

#[test]
fn a_one_patch_document_is_todays_world() {
    let doc =
        Document::from_scene(streamline_studio::scene::design::builtin::scene("car1").unwrap());
    let mut a = app(&doc);
    let mut b = ecs::headless_app(doc.patch_scene(0));
    assert_eq!(census(a.world_mut()), census(b.world_mut()));
    let w = a.world_mut();
    assert_eq!(w.query::<&PatchSurface>().iter(w).count(), 0);
    assert_eq!(bits(&common::points(&a)), bits(&common::points(&b)));
}

#[test]
fn an_edit_of_the_first_patch_rebuilds_every_patch_that_starts_on_it() {
    let mut doc = hood();
    let mut app = app(&doc);
    // row 4 is the wing's edge (`Last`): its edge curve moves
    let before = changed_ticks(&mut app);
    let dir = DVec3::new(0.9, 0.2, 0.3).normalize();
    set_first(&mut app, &mut doc, 4, 2, dir);
    let after = changed_ticks(&mut app);
    assert!(
        before.iter().zip(&after).all(|(a, b)| a != b),
        "all three rebuilt"
    );
    assert_as_built(&mut app, &doc);
    // row 1 is out of the reach of the wing's edge curve (Kobbelt's stencil
    // spans two rows): the G2 run is rebuilt, the wing is left as it is
    // (`joins::rejoin`), and every patch still equals the whole build
    let before = changed_ticks(&mut app);
    let dir = DVec3::new(0.9, 0.2, 0.3).normalize();
    set_first(&mut app, &mut doc, 1, 2, dir);
    let after = changed_ticks(&mut app);
    assert_ne!(after[0], before[0], "the hood rebuilt");
    assert_ne!(after[1], before[1], "the screen rebuilt");
    assert_eq!(after[2], before[2], "the wing kept");
    assert_as_built(&mut app, &doc);
    // the G2 run moved the screen: a negative control against the old build
    let old = hood().build(doc.display_depth).unwrap();
    let ids = patches(&mut app);
    let d = doc.display_depth as usize;
    assert_ne!(
        bits(&stack(&app, ids[1]).points[d]),
        bits(&old.patches[1].points[d])
    );
}

#[test]
fn an_edit_of_a_joined_patch_rebuilds_it_alone_and_setting_a_value_it_has_rebuilds_nothing() {
    let mut doc = hood();
    let mut app = app(&doc);
    let ids = patches(&mut app);
    let wing = ids[2];
    let h = app
        .world()
        .get::<PatchIndex>(wing)
        .unwrap()
        .surface
        .get(1, 2);
    // the same value: nothing rebuilt
    let before = changed_ticks(&mut app);
    let same = app.world().get::<Direction>(h).unwrap().0;
    app.world_mut()
        .get_mut::<Direction>(h)
        .unwrap()
        .set_if_neq(Direction(same));
    app.update();
    assert_eq!(changed_ticks(&mut app), before);
    // a new value: the wing alone
    let dir = DVec3::new(0.2, 0.9, 0.4).normalize();
    app.world_mut()
        .get_mut::<Direction>(h)
        .unwrap()
        .set_if_neq(Direction(dir));
    app.update();
    let after = changed_ticks(&mut app);
    assert_eq!(&after[..2], &before[..2], "hood and screen not rebuilt");
    assert_ne!(after[2], before[2], "the wing rebuilt");
    doc.patches[2].design.set_tangent(1, 2, dir).unwrap();
    assert_as_built(&mut app, &doc);
}

#[test]
fn the_bench_s_three_chained_cars_build_as_the_library_builds_them_and_follow_an_edit() {
    use streamline_studio::cli::bench::patches::chained_cars;
    let mut doc = chained_cars(3, 3);
    let mut app = app(&doc);
    assert_as_built(&mut app, &doc);
    let dir = DVec3::new(0.8, 0.1, 0.5).normalize();
    set_first(&mut app, &mut doc, 2, 4, dir);
    assert_as_built(&mut app, &doc);
    // the seam column is one handle of both cars (G1): turning the first's
    // last column turns the second's first
    let last = doc.patches[0].design.net().cols() - 1;
    ecs::apply(
        &mut app,
        Edit::SetDirection {
            row: 2,
            col: last,
            dir,
        },
    )
    .unwrap();
    let v = common::scene(&app).design.net().get(2, last);
    doc.patches[0].design.set_tangent(2, last, v).unwrap();
    doc.patches[1].design.set_tangent(2, 0, v).unwrap();
    assert_as_built(&mut app, &doc);
}

/// The G2 run (hood and screen) is kept between edits
/// (`ecs::joined::g2::G2RunState` on the hood, `joins::g2_state`): an edit
/// of the screen's far column re-blends the merged net there only, so the
/// hood's stack keeps its bits and is not marked changed (nor is the wing on
/// it), and after each edit every patch equals the whole build.
#[test]
fn a_g2_run_is_updated_in_place_and_an_edit_of_its_far_end_leaves_its_head() {
    use streamline_studio::ecs::joined::g2::G2RunState;
    let mut doc = hood();
    let mut app = app(&doc);
    let ids = patches(&mut app);
    let has_state = |app: &App| {
        app.world()
            .get::<G2RunState>(ids[0])
            .is_some_and(|s| s.0.is_some())
    };
    assert!(has_state(&app), "the hood keeps the run's merged levels");
    assert!(app.world().get::<G2RunState>(ids[1]).is_none());
    let screen = ids[1];
    let index = app
        .world()
        .get::<PatchIndex>(screen)
        .unwrap()
        .surface
        .clone();
    let far = index.cols() - 1;
    for (k, row) in [1usize, 3, 2].into_iter().enumerate() {
        let before = changed_ticks(&mut app);
        let h = index.get(row, far);
        let old = app.world().get::<Direction>(h).unwrap().0;
        let dir = (old + DVec3::new(0.0, 0.05 * (k as f64 + 1.0), -0.03)).normalize();
        app.world_mut()
            .get_mut::<Direction>(h)
            .unwrap()
            .set_if_neq(Direction(dir));
        app.update();
        let after = changed_ticks(&mut app);
        assert_eq!(after[0], before[0], "the hood kept (edit {k})");
        assert_ne!(after[1], before[1], "the screen rebuilt (edit {k})");
        assert_eq!(after[2], before[2], "the wing kept (edit {k})");
        assert!(has_state(&app));
        doc.patches[1].design.set_tangent(row, far, dir).unwrap();
        assert_as_built(&mut app, &doc);
    }
    // an edit of the hood moves both, still as the whole build
    let dir = DVec3::new(0.9, 0.2, 0.3).normalize();
    set_first(&mut app, &mut doc, 1, 2, dir);
    assert_as_built(&mut app, &doc);
    // a new depth builds the run whole, as the whole build
    ecs::apply(&mut app, Edit::SetDisplayDepth(doc.display_depth - 1)).unwrap();
    doc.display_depth -= 1;
    assert_as_built(&mut app, &doc);
}

/// The first patch's stack is kept between edits and brought up to date in
/// place from its pipeline (`ecs::joined::first`: the blend stage's level
/// windows, the mesh stage's surface window, the coarser rows that read a
/// change): after each step of a drag, an edit of an edge row and of the
/// seam column, an `s` edit, two initial-curve edits, a depth change and an
/// undo, every patch (levels and points at every depth, and the seam)
/// equals `Document::build` of the world's designs, bit for bit.
/// Negative control: the stack before the drag is not the one after it.
#[test]
fn the_first_patch_s_stack_follows_a_drag_and_other_edits_in_place_bit_for_bit() {
    use streamline_studio::cli::bench::patches::chained_cars;
    use streamline_studio::ecs::joined::document;
    use streamline_studio::scene::edits::edit::AuthorEdit;
    let doc = chained_cars(2, 3);
    let mut app = app(&doc);
    assert_as_built(&mut app, &doc);
    let first = patches(&mut app)[0];
    let before = stack(&app, first);
    let last = doc.patches[0].design.net().cols() - 1;
    let turn = |row, col, radians| Edit::Rotate {
        row,
        col,
        axis: DVec3::new(0.2, 1.0, 0.1).normalize(),
        radians,
    };
    let mut edits: Vec<Edit> = (0..6).map(|k| turn(2, 4, 0.01 * (k + 1) as f64)).collect();
    edits.extend([
        turn(0, 1, 0.05),
        turn(5, 7, -0.04),
        turn(3, last, 0.03),
        Edit::SetLength {
            row: 1,
            col: 3,
            coefficient: 1.1,
        },
        Edit::Author(AuthorEdit::RotateInitial {
            index: 1,
            axis: DVec3::X,
            radians: 0.05,
        }),
        Edit::Author(AuthorEdit::SetInitialOrigin(DVec3::new(0.1, -0.2, 0.05))),
        turn(2, 4, 0.02),
        Edit::SetDisplayDepth(2),
        turn(2, 4, 0.02),
        Edit::SetDisplayDepth(3),
        turn(1, 5, -0.03),
        Edit::Undo,
        turn(4, 2, 0.02),
    ]);
    for (k, e) in edits.into_iter().enumerate() {
        let label = format!("{e:?}");
        ecs::apply(&mut app, e).unwrap_or_else(|err| panic!("step {k} {label}: {err}"));
        let now = document(app.world()).unwrap();
        assert_as_built(&mut app, &now);
        if k == 0 {
            let d = doc.display_depth as usize;
            assert_ne!(bits(&stack(&app, first).points[d]), bits(&before.points[d]));
        }
    }
}

/// A G2 run's head is drawn as the run's cut (docs/math.md §11.1), so its
/// own one-patch pipeline waits while it heads a built run: an edit of the
/// hood re-blends and re-integrates none of the pipeline's levels and
/// streamlines (the run's state does the work) and every patch still
/// equals `Document::build`; once nothing continues it with G2 (the screen
/// removed), the pipeline is built afresh and equals a one-patch scene of
/// the hood as it is now, bit for bit. Negative control: while it waits,
/// the pipeline's surface is not that one-patch surface.
#[test]
fn a_g2_head_s_own_pipeline_waits_and_is_built_afresh_when_the_run_ends() {
    use streamline_studio::scene::edits::patch_edit::PatchEdit;
    let mut doc = hood();
    let mut app = app(&doc);
    for (k, (row, col)) in [(1usize, 2usize), (2, 3), (3, 1)].into_iter().enumerate() {
        let dir = DVec3::new(0.9, 0.1 * k as f64 + 0.1, 0.3).normalize();
        set_first(&mut app, &mut doc, row, col, dir);
        let last = app.world().resource::<ecs::Stats>().last.clone();
        assert_eq!(
            (last.tangents_reblended, last.streamlines_reintegrated),
            (0, 0),
            "edit {k}: {last:?}"
        );
        assert_as_built(&mut app, &doc);
    }
    let one = ecs::headless_app(doc.patch_scene(0));
    assert_ne!(bits(&common::points(&app)), bits(&common::points(&one)));
    ecs::apply(
        &mut app,
        Edit::Patch(PatchEdit::RemovePatch("screen".into())),
    )
    .unwrap();
    assert!(app.world().resource::<ecs::Stats>().last.full_rebuild);
    assert_eq!(bits(&common::points(&app)), bits(&common::points(&one)));
    let dir = DVec3::new(0.8, -0.2, 0.4).normalize();
    ecs::apply(
        &mut app,
        Edit::SetDirection {
            row: 2,
            col: 1,
            dir,
        },
    )
    .unwrap();
    let last = app.world().resource::<ecs::Stats>().last.clone();
    assert!(
        !last.full_rebuild && last.tangents_reblended > 0,
        "{last:?}"
    );
}

/// A drag of the hood's seam handle (2, 4), which heads the G2 run with the
/// screen and carries the wing on its last edge, at depth 5: after each
/// step every patch's mesh normals (`PatchSurface::normals`, made again in
/// the moved rows ± 1 and, in a run's member, from one column before the
/// first point placed again; the wing's levels re-blended in its stack's
/// own grids) are the whole mesh's normals of its finest points
/// (`SurfaceMesh::from_points`, docs/math.md §4), bit for bit, and every
/// stack and seam is the whole build's. Control: the hood's normals were
/// written in place (`PatchSurface::rows`), so the windows were taken.
#[test]
fn a_drag_of_the_g2_head_keeps_every_normal_the_whole_mesh_s() {
    use streamline_kernel::streamline::surface_mesh::SurfaceMesh;
    let mut doc = hood();
    doc.display_depth = 5;
    let mut app = app(&doc);
    let ids = patches(&mut app);
    let mut dir = doc.patches[0].design.net().get(2, 4);
    for step in 0..4 {
        dir = (dir + DVec3::new(0.0, 0.01, 0.015 * (step as f64 - 1.5))).normalize();
        set_first(&mut app, &mut doc, 2, 4, dir);
        // the seam column is one handle of the hood and the screen
        doc.patches[1].design.set_tangent(2, 0, dir).unwrap();
        app.update();
        assert_as_built(&mut app, &doc);
        for (k, &p) in ids.iter().enumerate() {
            let surface = app.world().get::<PatchSurface>(p).unwrap();
            let points = surface.stack().unwrap().finest_points();
            let whole = SurfaceMesh::from_points(points);
            let f = |v: &[DVec3]| {
                v.iter()
                    .map(|n| n.to_array().map(f64::to_bits))
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                f(&surface.normals),
                f(&whole.normals),
                "patch {k}, step {step}"
            );
            if k == 0 && step > 0 {
                assert!(surface.rows.is_some(), "the hood written in place");
            }
        }
    }
}
