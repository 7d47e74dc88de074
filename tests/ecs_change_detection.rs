//! The entity model (docs/architecture.md, "Entities"): a patch entity
//! owns its tangent handles, levels and streamlines; the edit stage writes
//! components only; change detection alone decides what is re-blended.
//! Each test checks a consequence against an independent measure: the
//! counts of what was redone, which level entities were marked changed
//! (seen by a system of the test's own), and the surface against a fresh
//! build.

mod common;

use bevy::prelude::*;
use common::{max_diff, points, scene};
use streamline_kernel::levels::presets;
use streamline_kernel::{DVec3, Grid};
use streamline_studio::ecs::census::census;
use streamline_studio::ecs::components::{LevelData, Streamline, SubdivisionLevel};
use streamline_studio::ecs::patch::{
    ArcParam, DetailHandle, DetailRotation, Direction, InitialHandle, Patch, PatchIndex,
    SurfaceHandle,
};
use streamline_studio::ecs::{self, Edit, EditStats, Stats};
use streamline_studio::scene::Scene;

/// The levels whose `LevelData` was marked changed in the last update, as a
/// system sees them (`Ref::is_changed`).
#[derive(Resource, Default, Debug, Clone, PartialEq)]
struct ChangedLevels(Vec<u32>);

fn record_changed_levels(
    levels: Query<(&SubdivisionLevel, Ref<LevelData>)>,
    mut out: ResMut<ChangedLevels>,
) {
    let mut v: Vec<u32> = levels
        .iter()
        .filter(|(_, d)| d.is_changed())
        .map(|(l, _)| l.0)
        .collect();
    v.sort();
    out.0 = v;
}

fn app_of(scene: Scene) -> App {
    let mut app = ecs::headless_app(scene);
    app.init_resource::<ChangedLevels>()
        .add_systems(Last, record_changed_levels);
    app.update();
    app
}

fn car(edit_depth: u32, display: u32) -> App {
    let mut s = Scene::from_design("car1", presets::car1(), display);
    s.edit_depth = edit_depth;
    app_of(s)
}

fn last(app: &App) -> EditStats {
    app.world().resource::<Stats>().last.clone()
}

fn changed_levels(app: &App) -> Vec<u32> {
    app.world().resource::<ChangedLevels>().0.clone()
}

fn bits(g: &Grid<DVec3>) -> Vec<[u64; 3]> {
    g.data()
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect()
}

fn turn(app: &mut App, row: usize, col: usize, radians: f64) {
    ecs::apply(
        app,
        Edit::Rotate {
            row,
            col,
            axis: DVec3::new(0.2, 1.0, 0.3),
            radians,
        },
    )
    .unwrap();
}

#[test]
fn the_patch_owns_one_entity_per_handle_level_and_streamline() {
    let mut app = car(0, 3);
    let s = scene(&app);
    let (rows, cols) = (s.design.net().rows(), s.design.net().cols());
    let w = app.world_mut();
    let c = census(w);
    assert_eq!(c.patches, 1);
    assert_eq!(c.handles.surface, rows * cols);
    assert_eq!(c.handles.initial, s.initial.tangents.len());
    assert_eq!(c.handles.detail, 0);
    assert_eq!(c.levels, 4, "levels 0..=3");
    assert_eq!(c.streamlines, points(&app).rows());
    // every handle, level and streamline is a child of the patch
    let w = app.world_mut();
    let patch = w.query_filtered::<Entity, With<Patch>>().single(w).unwrap();
    let mut kids = w.query_filtered::<&ChildOf, Or<(
        With<SurfaceHandle>,
        With<InitialHandle>,
        With<SubdivisionLevel>,
        With<Streamline>,
    )>>();
    let parents: Vec<Entity> = kids.iter(w).map(|c| c.parent()).collect();
    assert_eq!(
        parents.len(),
        rows * cols + s.initial.tangents.len() + 4 + c.streamlines
    );
    assert!(parents.iter().all(|&p| p == patch));
    // the handles hold the scene's values, bit for bit
    let index = w.get::<PatchIndex>(patch).unwrap().clone();
    for r in 0..rows {
        for k in 0..cols {
            let e = index.surface.get(r, k);
            let h = w.get::<SurfaceHandle>(e).unwrap();
            assert_eq!((h.row, h.col), (r, k));
            assert_eq!(w.get::<Direction>(e).unwrap().0, s.design.net().get(r, k));
            assert_eq!(
                w.get::<ArcParam>(e).unwrap().0,
                s.design.params().s.get(r, k)
            );
        }
    }
}

#[test]
fn setting_a_direction_to_the_value_it_has_reblends_nothing() {
    let mut app = car(0, 4);
    let before = points(&app);
    let dir = scene(&app).design.net().get(4, 3);
    ecs::apply(
        &mut app,
        Edit::SetDirection {
            row: 4,
            col: 3,
            dir,
        },
    )
    .unwrap();
    let s = last(&app);
    assert!(!s.full_rebuild);
    assert_eq!(s.tangents_reblended, 0, "{s:?}");
    assert_eq!(s.streamlines_reintegrated, 0, "{s:?}");
    assert_eq!(
        changed_levels(&app),
        Vec::<u32>::new(),
        "no level entity marked changed"
    );
    assert_eq!(bits(&points(&app)), bits(&before));
    // a real change of the same handle does re-blend (the control)
    turn(&mut app, 4, 3, 0.2);
    assert!(last(&app).tangents_reblended > 0);
}

#[test]
fn undoing_an_edit_reblends_exactly_the_window_the_edit_did() {
    let mut app = car(0, 4);
    let before = points(&app);
    turn(&mut app, 4, 3, 0.25);
    let edit = last(&app);
    let edit_levels = changed_levels(&app);
    assert!(
        !edit.full_rebuild && edit.tangents_reblended > 0,
        "{edit:?}"
    );
    ecs::apply(&mut app, Edit::Undo).unwrap();
    let undo = last(&app);
    assert!(!undo.full_rebuild, "{undo:?}");
    assert_eq!(undo.tangents_reblended, edit.tangents_reblended);
    assert_eq!(undo.streamlines_reintegrated, edit.streamlines_reintegrated);
    assert_eq!(changed_levels(&app), edit_levels);
    assert_eq!(
        bits(&points(&app)),
        bits(&before),
        "undo restores the surface bit for bit"
    );
    ecs::apply(&mut app, Edit::Redo).unwrap();
    assert_eq!(last(&app).tangents_reblended, edit.tangents_reblended);
}

#[test]
fn loading_a_scene_that_differs_in_one_tangent_reblends_its_window_only() {
    let mut app = car(0, 4);
    // the same edit made as an edit, for its window
    let mut probe = car(0, 4);
    turn(&mut probe, 2, 5, -0.3);
    let edit = last(&probe);
    let dir = tempdir("load-one");
    let path = dir.join("one-tangent.ron");
    streamline_studio::scene::design::document_io::save_scene(&scene(&probe), &path).unwrap();
    ecs::apply(&mut app, Edit::Load(path.clone())).unwrap();
    let load = last(&app);
    assert!(!load.full_rebuild, "{load:?}");
    assert_eq!(load.tangents_reblended, edit.tangents_reblended);
    assert_eq!(load.streamlines_reintegrated, edit.streamlines_reintegrated);
    assert_eq!(bits(&points(&app)), bits(&points(&probe)));
    // and against a fresh build of the file
    let fresh = app_of(streamline_studio::scene::design::document_io::load_scene(&path).unwrap());
    assert_eq!(max_diff(&points(&fresh), &points(&app)), 0.0);
    // a scene of another shape is a structural change: a full build
    let grid = Scene::from_design("grid", presets::wavy(7, 7), 3);
    let other = dir.join("grid.ron");
    streamline_studio::scene::design::document_io::save_scene(&grid, &other).unwrap();
    ecs::apply(&mut app, Edit::Load(other)).unwrap();
    assert!(last(&app).full_rebuild);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_level_is_marked_changed_only_where_its_window_was_recomputed() {
    // a detail at level 2 re-blends levels 2.. only
    let mut app = car(2, 4);
    turn(&mut app, 9, 8, 0.3);
    assert_eq!(changed_levels(&app), vec![2, 3, 4]);
    assert_eq!(scene(&app).details.len(), 1);
    // its handle is an entity of its own, under the patch
    let w = app.world_mut();
    let mut q = w.query::<(&DetailHandle, &DetailRotation)>();
    let d: Vec<_> = q.iter(w).map(|(h, r)| (h.key(), r.0)).collect();
    assert_eq!(d.len(), 1);
    assert_eq!(d[0].0, (2, 9, 8));
    // clearing it removes the entity and re-blends the same levels
    ecs::apply(&mut app, Edit::ClearDetail { row: 9, col: 8 }).unwrap();
    assert_eq!(changed_levels(&app), vec![2, 3, 4]);
    assert_eq!(census(app.world_mut()).handles.detail, 0);
    // an edit of level 0 changes every level; an edit with no effect, none
    let mut app = car(0, 3);
    turn(&mut app, 1, 1, 0.1);
    assert_eq!(changed_levels(&app), vec![0, 1, 2, 3]);
    app.update();
    assert_eq!(changed_levels(&app), Vec::<u32>::new());
}

#[test]
fn writing_a_handle_component_directly_rebuilds_like_an_edit() {
    // the pipeline follows the components, whoever writes them
    let mut by_edit = car(0, 4);
    let mut by_component = car(0, 4);
    turn(&mut by_edit, 5, 2, 0.4);
    let want = scene(&by_edit).design.net().get(5, 2);
    let w = by_component.world_mut();
    let patch = w.query_filtered::<Entity, With<Patch>>().single(w).unwrap();
    let e = w.get::<PatchIndex>(patch).unwrap().surface.get(5, 2);
    w.get_mut::<Direction>(e).unwrap().0 = want;
    by_component.world_mut().resource_mut::<Stats>().last = Default::default();
    by_component.update();
    let s = last(&by_component);
    assert!(!s.full_rebuild);
    assert_eq!(s.tangents_reblended, last(&by_edit).tangents_reblended);
    assert_eq!(bits(&points(&by_component)), bits(&points(&by_edit)));
}

fn tempdir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("streamline-cd-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
