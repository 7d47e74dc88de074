//! Analysis ▸ to reference without a window: the map's distances under
//! `MinimalPlugins` (the model, the interaction core and the reference map's
//! plugin; no renderer). On the fitted hood the largest distance is the
//! closest-point distance of the shown points and within the tolerance; a
//! turned tangent takes the surface off the reference, and undo brings it
//! back. A design without a reference has the mode disabled.

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
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.ron");
    let doc = streamline_studio::scene::document_io::load(&path).unwrap();
    editor(doc.patch_scene(0))
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
    let doc = streamline_studio::scene::document_io::load(&path).unwrap();
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
