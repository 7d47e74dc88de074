//! Analysis ▸ to reference without a window: the map's distances under
//! `MinimalPlugins` (the model, the interaction core and the reference map's
//! plugin; no renderer). On the fitted hood the largest distance is the
//! closest-point distance of the shown points and within the tolerance; a
//! turned tangent takes the surface off the reference, and undo brings it
//! back. An edit is measured again only where it moved the surface, and
//! the map is then bit for bit the full measure (plain and mirrored). A
//! design without a reference has the mode disabled.

mod common;

use bevy::prelude::*;
use common::headless_editor::frame;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_kernel::fit::ClosestPoints;
use streamline_studio::ecs::{Edit, ModelPlugin, SurfaceData, apply};
use streamline_studio::editor::interaction::InteractionPlugin;
use streamline_studio::editor::{ReferenceField, ReferenceMapPlugin};

/// The headless editor on `scene` with the map to the reference shown.
fn editor(scene: streamline_studio::scene::Scene) -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .init_resource::<ButtonInput<MouseButton>>()
        .init_resource::<ButtonInput<KeyCode>>()
        .add_plugins(ModelPlugin::new(scene))
        .add_plugins(InteractionPlugin)
        .add_plugins(ReferenceMapPlugin);
    // what the Analysis section's "to reference" does
    app.world_mut().resource_mut::<ReferenceField>().shown = true;
    frame(&mut app);
    frame(&mut app);
    app
}

fn hood() -> App {
    editor(hood_scene())
}

fn hood_scene() -> streamline_studio::scene::Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.ron");
    let doc = streamline_studio::scene::design::document_io::load(&path).unwrap();
    doc.patch_scene(0)
}

/// The shown points of the first patch.
fn shown(app: &App) -> Vec<DVec3> {
    app.world().resource::<SurfaceData>().points.data().to_vec()
}

/// The largest distance of the map, checked against `ClosestPoints` on the
/// shown points (each within 1e-12), and the map's tolerance.
fn largest(app: &App) -> (f64, f64) {
    let field = app.world().resource::<ReferenceField>();
    assert!(field.has_reference);
    assert_eq!(field.error, None);
    let values = field.values.as_ref().expect("the map measured the points");
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.step");
    let file = streamline_reference::read(&path).unwrap();
    let surface = file.surface(0).unwrap();
    let points = shown(app);
    let want = ClosestPoints::new(surface).unwrap().distances(&points);
    assert_eq!(values.len(), want.len(), "a distance for each shown point");
    for (a, b) in values.iter().zip(&want) {
        assert!((a - b).abs() <= 1e-12, "{a} against {b}");
    }
    let max = want.iter().copied().fold(0.0, f64::max);
    assert!((field.distances.max - max).abs() <= 1e-12);
    assert!(field.tolerance > 0.0 && field.tolerance.is_finite());
    (field.distances.max, field.tolerance)
}

#[test]
fn the_map_follows_an_edit_and_its_undo() {
    let mut app = hood();
    let (max, tolerance) = largest(&app);
    assert!(max < tolerance, "fitted: {max} within {tolerance}");
    let generation = app.world().resource::<ReferenceField>().generation;
    apply(
        &mut app,
        Edit::Rotate {
            row: 4,
            col: 3,
            axis: DVec3::Z,
            radians: 8f64.to_radians(),
        },
    )
    .unwrap();
    frame(&mut app);
    let (turned, _) = largest(&app);
    assert!(
        turned > 5e-4,
        "a turned tangent leaves the reference: {turned}"
    );
    eprintln!("largest distance: fitted {max:.3e}, turned {turned:.3e}, tolerance {tolerance:.3e}");
    assert!(app.world().resource::<ReferenceField>().generation > generation);
    apply(&mut app, Edit::Undo).unwrap();
    frame(&mut app);
    let (back, _) = largest(&app);
    assert!(back < tolerance, "undone: {back} within {tolerance}");
}

#[test]
fn a_design_without_reference_has_the_mode_disabled() {
    let mut app = editor(streamline_studio::scene::Scene::from_design(
        "car1",
        streamline_kernel::levels::presets::car1(),
        2,
    ));
    for _ in 0..3 {
        frame(&mut app);
    }
    let field = app.world().resource::<ReferenceField>();
    assert!(!field.has_reference, "the panel greys the mode out");
    assert_eq!(field.values, None);
    assert_eq!(field.error, None);
}

#[test]
fn a_missing_reference_file_is_an_error_not_a_panic() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.ron");
    let doc = streamline_studio::scene::design::document_io::load(&path).unwrap();
    let mut scene = doc.patch_scene(0);
    if let Some(link) = scene.reference.as_mut() {
        link.path = link.path.with_file_name("no-such-hood.step");
    }
    let mut app = editor(scene);
    frame(&mut app);
    let field = app.world().resource::<ReferenceField>();
    assert!(field.has_reference);
    assert_eq!(field.values, None);
    let e = field.error.as_deref().expect("the read error is kept");
    assert!(e.contains("no-such-hood"), "{e}");
}

/// The map's distances and largest and mean distance, as bits.
fn bits(app: &App) -> (Vec<u64>, u64, u64) {
    let field = app.world().resource::<ReferenceField>();
    let v = field.values.as_ref().expect("measured");
    (
        v.iter().map(|d| d.to_bits()).collect(),
        field.distances.max.to_bits(),
        field.distances.mean.to_bits(),
    )
}

/// An edit is measured again in the window of points it moved, and the
/// map is then the full measure bit for bit: each value, the largest and
/// the mean. The values from before the edit are not (the negative
/// control: a map that kept them would fail the comparison).
fn incremental_equals_full(mirror: bool) {
    let mut scene = hood_scene();
    scene.mirror = mirror;
    let mut app = editor(scene);
    let (before, _, _) = bits(&app);
    let total = shown(&app).len();
    // the last as a frame of the bench's drag (`reference-deviation/hood/d5/drag-row`)
    let turns = [
        (4, 3, DVec3::Z, 8.0),
        (1, 6, DVec3::Z, -5.0),
        (7, 1, DVec3::Z, 3.0),
        (4, 3, DVec3::Y, f64::to_degrees(-0.01)),
    ];
    for (row, col, axis, degrees) in turns {
        apply(
            &mut app,
            Edit::Rotate {
                row,
                col,
                axis,
                radians: f64::to_radians(degrees),
            },
        )
        .unwrap();
        frame(&mut app);
        let field = app.world().resource::<ReferenceField>();
        let window = field
            .window
            .expect("a tangent's edit is measured in its window");
        let measured = field.measured;
        assert!(measured < total, "{measured} of {total} points measured");
        eprintln!(
            "mirror {mirror}: tangent ({row}, {col}): rows {}..={} × cols {}..={} measured, {measured} of {total} points",
            window.rows.lo, window.rows.hi, window.cols.lo, window.cols.hi
        );
        let incremental = bits(&app);
        app.world_mut()
            .resource_mut::<ReferenceField>()
            .remeasure_all();
        frame(&mut app);
        let field = app.world().resource::<ReferenceField>();
        assert_eq!(field.window, None, "measured whole");
        assert!(field.measured >= measured, "every measured point");
        let full = bits(&app);
        assert!(incremental.0 == full.0, "each value as the full measure's");
        assert_eq!(incremental.1, full.1, "the largest distance");
        assert_eq!(incremental.2, full.2, "the mean distance");
        // negative control: the values from before the edits are not the map
        let moved = before.iter().zip(&full.0).filter(|(a, b)| a != b).count();
        assert!(moved > 0, "the edit moved the surface");
        eprintln!("  {moved} of {total} values differ from before the edits");
    }
}

#[test]
fn an_edit_is_measured_where_it_moved_the_surface_and_equals_a_full_measure() {
    incremental_equals_full(false);
}

#[test]
fn a_mirrored_edit_is_measured_where_it_moved_the_surface_and_equals_a_full_measure() {
    incremental_equals_full(true);
}
