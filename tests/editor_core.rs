//! Issue 19: the editor's interaction core runs headless under
//! `MinimalPlugins` with injected input: presses and drag directions as the
//! views report them, the left button and Esc as the input plugin reads
//! them. The drag state machine (one undo step per drag, Esc restores and
//! forgets it), the selection, and picking on the screen and on the sphere
//! are checked against the model, without a window (the xvfb GUI tests
//! drive the same core through a real pointer).

mod common;

use bevy::prelude::*;
use common::headless_editor::*;
use streamline_kernel::{DVec3, levels::presets};
use streamline_studio::editor::interaction::{
    Drag, DragKind, HandleId, HandleSettings, Handles, Selection,
};
use streamline_studio::scene::Scene;

fn net(app: &App, (r, c): (usize, usize)) -> DVec3 {
    streamline_studio::ecs::patch::scene(app.world())
        .design
        .net()
        .get(r, c)
}

#[test]
fn a_drag_is_one_undo_step_and_esc_restores_it() {
    let mut app = app();
    let cell = (4, 2);
    let h = HandleId::tangent(0, 4, 2);
    let before = net(&app, cell);
    assert!(app.world().resource::<Handles>().find(h).is_some());
    press(&mut app, Some(h), Some(DragKind::Sphere));
    assert_eq!(app.world().resource::<Selection>().primary(), Some(h));
    let d = app.world().resource::<Drag>().0.expect("a drag started");
    assert_eq!((d.handle, d.start_dir, d.sent), (h, before, false));
    // two steps of the drag: the tangent follows, one undo step in all
    let (a, b) = (
        DVec3::new(1.0, 0.3, 0.2).normalize(),
        DVec3::new(0.8, -0.2, 0.5).normalize(),
    );
    steer(&mut app, a);
    assert!(
        (net(&app, cell) - a).length() < 1e-12,
        "{}",
        net(&app, cell)
    );
    steer(&mut app, b);
    assert!((net(&app, cell) - b).length() < 1e-12);
    assert_eq!(undo_steps(&app), 1, "a drag is one undo step");
    // Esc cancels: the direction is back, the step forgotten, the drag over
    key(&mut app, KeyCode::Escape);
    assert_eq!(net(&app, cell), before, "Esc restores the exact direction");
    assert_eq!(undo_steps(&app), 0, "a cancelled drag leaves no undo step");
    assert!(app.world().resource::<Drag>().0.is_none());
    // the selection stays; a second Esc (no drag) clears it
    assert_eq!(app.world().resource::<Selection>().primary(), Some(h));
    key(&mut app, KeyCode::Escape);
    assert_eq!(app.world().resource::<Selection>().primary(), None);
    // directions asked for with no drag change nothing
    release(&mut app);
    steer(&mut app, a);
    assert_eq!(net(&app, cell), before);
}

#[test]
fn release_keeps_the_drag_and_presses_select() {
    let mut app = app();
    let h = HandleId::tangent(0, 1, 3);
    press(&mut app, Some(h), Some(DragKind::Sphere));
    let dir = DVec3::new(0.9, 0.1, -0.3).normalize();
    steer(&mut app, dir);
    release(&mut app);
    assert!(
        app.world().resource::<Drag>().0.is_none(),
        "release ends the drag"
    );
    assert!(
        (net(&app, (1, 3)) - dir).length() < 1e-12,
        "release keeps the direction"
    );
    assert_eq!(undo_steps(&app), 1);
    // a press on empty space clears the selection and starts nothing
    press(&mut app, None, None);
    assert_eq!(app.world().resource::<Selection>().primary(), None);
    assert!(app.world().resource::<Drag>().0.is_none());
    release(&mut app);
    // a press on a handle without a drag kind selects it only
    let g = HandleId::tangent(0, 2, 2);
    press(&mut app, Some(g), None);
    assert_eq!(app.world().resource::<Selection>().primary(), Some(g));
    assert!(app.world().resource::<Drag>().0.is_none());
    release(&mut app);
    // a second drag is a second undo step; undo takes it back
    press(&mut app, Some(g), Some(DragKind::Sphere));
    steer(&mut app, DVec3::Z);
    release(&mut app);
    assert_eq!(undo_steps(&app), 2);
}

#[test]
fn a_selection_follows_the_edit_depth_and_is_dropped_when_gone() {
    let mut app = app();
    let h = HandleId::tangent(0, 8, 5);
    press(&mut app, Some(h), None);
    release(&mut app);
    app.world_mut()
        .write_message(streamline_studio::ecs::EditMessage::from(
            streamline_studio::ecs::Edit::SetEditDepth(1),
        ));
    frame(&mut app);
    // the same cell at the new edit depth
    assert_eq!(
        app.world().resource::<Selection>().primary(),
        Some(HandleId::tangent(1, 8, 5))
    );
    app.world_mut()
        .write_message(streamline_studio::ecs::EditMessage::from(
            streamline_studio::ecs::Edit::Replace(Box::new(Scene::from_design(
                "minimal",
                presets::minimal(),
                1,
            ))),
        ));
    frame(&mut app);
    frame(&mut app);
    assert_eq!(
        app.world().resource::<Selection>().primary(),
        None,
        "(8, 5) is gone"
    );
}

/// Picking on the screen and on the sphere: with a projection that drops
/// the depth axis, the handle whose arrow (or point) is nearest the pointer
/// is picked, within the radius, and hidden handles never are.
#[test]
fn picking_finds_the_nearest_shown_handle() {
    let app = app();
    let handles = app.world().resource::<Handles>();
    let settings = HandleSettings::default();
    let project = |p: DVec3| Some(Vec2::new(p.x as f32 * 200.0, -p.z as f32 * 200.0));
    for a in handles.editable.iter().step_by(7) {
        let (p0, p1) = a.on_screen(project).unwrap();
        let mid = (p0 + p1) * 0.5;
        let got = handles.pick_on_screen(&settings, mid, project, 8.0);
        // the nearest arrow within 8 px: this one, or one at most as near
        let g = handles
            .find(got.expect("an arrow under the pointer"))
            .unwrap();
        let (q0, q1) = g.on_screen(project).unwrap();
        let d = streamline_studio::editor::interaction::segment_distance;
        assert!(d(mid, q0, q1) <= d(mid, p0, p1) + 1e-4);
    }
    let far = Vec2::new(1e6, 1e6);
    assert_eq!(handles.pick_on_screen(&settings, far, project, 8.0), None);
    // the sphere: the point of a handle facing the eye
    let a = handles.editable[10];
    let sphere = |d: DVec3| Some(Vec2::new(d.x as f32 * 100.0, d.y as f32 * 100.0));
    let at = sphere(a.dir).unwrap();
    let eye = DVec3::new(a.dir.x, a.dir.y, a.dir.z.abs() + 1.0).normalize();
    let got = handles.pick_on_sphere(&settings, at, eye, sphere, 10.0);
    assert!(got.is_some_and(|g| (sphere(g.dir).unwrap() - at).length() <= 1e-4));
    // a handle on the far side of the sphere is never picked
    let back = handles.pick_on_sphere(&settings, at, -a.dir, sphere, 10.0);
    assert!(back.is_none_or(|g| g.dir.dot(-a.dir) >= 0.0));
}

/// Issue 26: the selected handles' entities carry the `Selected` marker, and
/// only they.
#[test]
fn the_selected_handle_entity_is_marked() {
    use streamline_studio::ecs::patch::{InitialHandle, SurfaceHandle};
    use streamline_studio::editor::interaction::Selected;
    let mut app = app();
    let marked = |app: &mut App| {
        let w = app.world_mut();
        let mut q =
            w.query_filtered::<(Option<&SurfaceHandle>, Option<&InitialHandle>), With<Selected>>();
        let mut v: Vec<String> = q
            .iter(w)
            .map(|(s, i)| match (s, i) {
                (Some(s), _) => format!("net {} {}", s.row, s.col),
                (_, Some(i)) => format!("initial {}", i.index),
                _ => "other".into(),
            })
            .collect();
        v.sort();
        v
    };
    assert!(marked(&mut app).is_empty());
    press(&mut app, Some(HandleId::tangent(0, 4, 2)), None);
    release(&mut app);
    frame(&mut app);
    assert_eq!(marked(&mut app), ["net 4 2"]);
    app.world_mut()
        .resource_mut::<Selection>()
        .extend([HandleId::initial(1)]);
    frame(&mut app);
    assert_eq!(marked(&mut app), ["initial 1", "net 4 2"]);
    key(&mut app, KeyCode::Escape);
    frame(&mut app);
    assert!(marked(&mut app).is_empty());
}

/// Issue 26: turning a control tangent moves only its row's handles (a
/// streamline is a running sum along its row), and they are where a full
/// placement of every handle puts them, bit for bit.
#[test]
fn a_turn_moves_only_its_rows_handles() {
    let mut app = app();
    let cols = app.world().resource::<Handles>().shape().1;
    let h = HandleId::tangent(0, 3, 2);
    press(&mut app, Some(h), Some(DragKind::Sphere));
    steer(&mut app, DVec3::new(0.9, 0.35, 0.25).normalize());
    let moved = app.world().resource::<Handles>().moved;
    assert_eq!(moved, cols, "one row of handles moved");
    release(&mut app);
    frame(&mut app);
    // a fresh editor on the edited scene places every handle afresh
    let scene = streamline_studio::ecs::patch::scene(app.world());
    let mut fresh = App::new();
    fresh
        .add_plugins(MinimalPlugins)
        .init_resource::<ButtonInput<MouseButton>>()
        .init_resource::<ButtonInput<KeyCode>>()
        .add_plugins(streamline_studio::ecs::ModelPlugin::new(scene))
        .add_plugins(streamline_studio::editor::interaction::InteractionPlugin);
    frame(&mut fresh);
    let (a, b) = (
        app.world().resource::<Handles>(),
        fresh.world().resource::<Handles>(),
    );
    assert!(b.moved > cols, "the fresh editor placed all of them");
    assert_eq!(a.controls, b.controls);
    assert_eq!(a.editable, b.editable);
    assert_eq!(a.initial, b.initial);
}
