//! The editor's interaction core runs headless under
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
    Drag, DragKind, Handle, HandleId, HandleLayout, HandleSettings, Placed, RefinedHandle,
    Selection,
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
    assert!(handles(&mut app, |q| q.find(h)).is_some());
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
    let mut app = app();
    let settings = HandleSettings::default();
    let project = |p: DVec3| Some(Vec2::new(p.x as f32 * 200.0, -p.z as f32 * 200.0));
    let editable: Vec<Handle> = handles(&mut app, |q| q.editable().collect());
    for a in editable.iter().step_by(7) {
        let (p0, p1) = a.on_screen(project).unwrap();
        let mid = (p0 + p1) * 0.5;
        let got = handles(&mut app, |q| q.pick_on_screen(&settings, mid, project, 8.0));
        // the nearest arrow within 8 px: this one, or one at most as near
        let g = handles(&mut app, |q| {
            q.find(got.expect("an arrow under the pointer"))
        })
        .unwrap();
        let (q0, q1) = g.on_screen(project).unwrap();
        let d = streamline_studio::editor::interaction::segment_distance;
        assert!(d(mid, q0, q1) <= d(mid, p0, p1) + 1e-4);
    }
    let far = Vec2::new(1e6, 1e6);
    let none = handles(&mut app, |q| q.pick_on_screen(&settings, far, project, 8.0));
    assert_eq!(none, None);
    // the sphere: the point of a handle facing the eye
    let a = editable[10];
    let sphere = |d: DVec3| Some(Vec2::new(d.x as f32 * 100.0, d.y as f32 * 100.0));
    let at = sphere(a.dir).unwrap();
    let eye = DVec3::new(a.dir.x, a.dir.y, a.dir.z.abs() + 1.0).normalize();
    let got = handles(&mut app, |q| {
        q.pick_on_sphere(&settings, at, eye, sphere, 10.0)
    });
    assert!(got.is_some_and(|g| (sphere(g.dir).unwrap() - at).length() <= 1e-4));
    // a handle on the far side of the sphere is never picked
    let back = handles(&mut app, |q| {
        q.pick_on_sphere(&settings, at, -a.dir, sphere, 10.0)
    });
    assert!(back.is_none_or(|g| g.dir.dot(-a.dir) >= 0.0));
}

/// The selected handles' entities carry the `Selected` marker, and
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

/// Turning a control tangent moves only its row's handles (a
/// streamline is a running sum along its row), and they are where a full
/// placement of every handle puts them, bit for bit.
#[test]
fn a_turn_moves_only_its_rows_handles() {
    let mut app = app();
    let cols = handles(&mut app, |q| q.shape().1);
    let h = HandleId::tangent(0, 3, 2);
    press(&mut app, Some(h), Some(DragKind::Sphere));
    steer(&mut app, DVec3::new(0.9, 0.35, 0.25).normalize());
    let moved = app.world().resource::<HandleLayout>().moved;
    assert_eq!(moved, cols, "one row of handles moved");
    release(&mut app);
    frame(&mut app);
    let mut fresh = fresh_editor(&app);
    assert!(
        fresh.world().resource::<HandleLayout>().moved > cols,
        "the fresh editor placed all of them"
    );
    assert_eq!(placements(&mut app), placements(&mut fresh));
}

/// A fresh editor on `app`'s scene: it places every handle afresh.
fn fresh_editor(app: &App) -> App {
    let scene = streamline_studio::ecs::patch::scene(app.world());
    let mut fresh = App::new();
    fresh
        .add_plugins(MinimalPlugins)
        .init_resource::<ButtonInput<MouseButton>>()
        .init_resource::<ButtonInput<KeyCode>>()
        .add_plugins(streamline_studio::ecs::ModelPlugin::new(scene))
        .add_plugins(streamline_studio::editor::interaction::InteractionPlugin);
    frame(&mut fresh);
    fresh
}

/// Every handle's id and place, bit for bit: the controls, the edit depth's,
/// the initial curve's and the mirrored copies, in order.
fn placements(app: &mut App) -> Vec<(HandleId, [u64; 7])> {
    let bits = |a: Handle| {
        let v = [a.base, a.dir].map(|v| v.to_array().map(f64::to_bits));
        let [b, d] = v;
        (
            a.id,
            [b[0], b[1], b[2], d[0], d[1], d[2], a.length.to_bits()],
        )
    };
    handles(app, |q| {
        q.controls()
            .chain(q.editable())
            .chain(q.initial())
            .chain(q.mirrored())
            .map(bits)
            .collect()
    })
}

/// A world tick that every later system run is newer than.
fn tick(app: &mut App) -> bevy::ecs::change_detection::Tick {
    let w = app.world_mut();
    let t = w.change_tick();
    w.increment_change_tick();
    t
}

/// The handle entities whose `Placed` changed after `since` (a world tick).
fn changed_since(app: &mut App, since: bevy::ecs::change_detection::Tick) -> Vec<HandleId> {
    let w = app.world_mut();
    let now = w.change_tick();
    let mut q = w.query::<(&HandleId, Ref<Placed>)>();
    let mut v: Vec<HandleId> = q
        .iter(w)
        .filter(|(_, p)| p.last_changed().is_newer_than(since, now))
        .map(|(h, _)| *h)
        .collect();
    v.sort_by_key(|h| (h.is_surface(), h.row, h.col));
    v
}

/// After a drag of one control tangent at edit depth 0,
/// exactly the handle entities whose place differs have `Changed<Placed>`:
/// the turned one among them, all of them in its row, none outside it;
/// and every handle equals a fresh editor's placement bit for bit.
#[test]
fn only_the_moved_handles_are_marked_changed() {
    let mut app = app();
    let (row, col) = (3, 2);
    let h = HandleId::tangent(0, row, col);
    press(&mut app, Some(h), Some(DragKind::Sphere));
    let before = placements(&mut app);
    let since = tick(&mut app);
    steer(&mut app, DVec3::new(0.9, 0.35, 0.25).normalize());
    let changed = changed_since(&mut app, since);
    let after = placements(&mut app);
    // the handles whose bits differ: independent of the change ticks
    let mut differ: Vec<HandleId> = before
        .iter()
        .zip(&after)
        .filter(|(b, a)| b != a)
        .map(|(b, _)| b.0)
        .collect();
    differ.sort_by_key(|h| (h.is_surface(), h.row, h.col));
    differ.dedup();
    assert!(
        changed.contains(&h),
        "the turned handle is marked: {changed:?}"
    );
    assert!(
        changed.iter().all(|c| c.is_surface() && c.row == row),
        "only its row's handles are marked: {changed:?}"
    );
    assert_eq!(changed, differ, "marked exactly the handles that moved");
    // negative control: a frame without an edit marks none
    let since = tick(&mut app);
    frame(&mut app);
    assert!(changed_since(&mut app, since).is_empty());
    release(&mut app);
    frame(&mut app);
    let mut fresh = fresh_editor(&app);
    assert_eq!(placements(&mut app), placements(&mut fresh));
}

/// At an edit depth above 0 each cell of that level is a
/// handle entity (a `RefinedHandle`, child of the patch), placed as a fresh
/// editor places it; picking one and turning it turns that level's tangent;
/// back at depth 0 the refined entities are gone.
#[test]
fn refined_handles_are_entities_at_an_edit_depth_above_0() {
    use streamline_studio::ecs::components::{LevelData, SubdivisionLevel};
    let mut app = app();
    let set_depth = |app: &mut App, d: u32| {
        app.world_mut()
            .write_message(streamline_studio::ecs::EditMessage::from(
                streamline_studio::ecs::Edit::SetEditDepth(d),
            ));
        frame(app);
    };
    let refined = |app: &mut App| {
        let w = app.world_mut();
        let mut q = w.query::<(&RefinedHandle, &HandleId, &ChildOf)>();
        let mut v: Vec<(u32, usize, usize)> = q
            .iter(w)
            .map(|(r, h, _)| {
                assert_eq!(*h, HandleId::tangent(r.level, r.row, r.col));
                (r.level, r.row, r.col)
            })
            .collect();
        v.sort_unstable();
        v
    };
    let level_shape = |app: &mut App, l: u32| {
        let w = app.world_mut();
        let mut q = w.query::<(&SubdivisionLevel, &LevelData)>();
        q.iter(w).find(|(s, _)| s.0 == l).map(|(_, d)| d.0.shape())
    };
    assert!(refined(&mut app).is_empty(), "none at depth 0");
    set_depth(&mut app, 1);
    let (rows, cols) = level_shape(&mut app, 1).expect("level 1");
    let cells = refined(&mut app);
    assert_eq!(cells.len(), rows * cols, "one entity per cell");
    assert!(cells.windows(2).all(|w| w[0] != w[1]));
    assert_eq!(handles(&mut app, |q| q.shape()), (rows, cols));
    assert_eq!(handles(&mut app, |q| q.editable().count()), rows * cols);
    let mut fresh = fresh_editor(&app);
    assert_eq!(placements(&mut app), placements(&mut fresh));
    // pick one on the screen (a projection dropping the depth axis)
    let settings = HandleSettings::default();
    let project = |p: DVec3| Some(Vec2::new(p.x as f32 * 200.0, -p.z as f32 * 200.0));
    let target = HandleId::tangent(1, rows / 2, cols / 2);
    let a = handles(&mut app, |q| q.find(target)).expect("the refined handle");
    let (p0, p1) = a.on_screen(project).unwrap();
    let got = handles(&mut app, |q| {
        q.pick_on_screen(&settings, (p0 + p1) * 0.5, project, 8.0)
    })
    .expect("a refined arrow under the pointer");
    assert_eq!(got.level(), 1, "at depth 1 the refined handles are picked");
    // turn it: the level's tangent at its cell follows, and so does its entity
    let dir = (a.dir + DVec3::new(0.2, -0.1, 0.15)).normalize();
    let steps = undo_steps(&app);
    press(&mut app, Some(target), Some(DragKind::Sphere));
    steer(&mut app, dir);
    release(&mut app);
    frame(&mut app);
    let now = handles(&mut app, |q| q.find(target)).unwrap();
    assert!((now.dir - dir).length() < 1e-9, "{} != {dir}", now.dir);
    let w = app.world_mut();
    let mut q = w.query::<(&SubdivisionLevel, &LevelData)>();
    let level = q.iter(w).find(|(s, _)| s.0 == 1).unwrap().1;
    let t = level.0.tangents.get(target.row, target.col);
    assert!(
        (t - dir).length() < 1e-9,
        "the level's tangent {t} != {dir}"
    );
    assert_eq!(undo_steps(&app), steps + 1, "the drag is one undo step");
    // back at depth 0: no refined entity is left
    set_depth(&mut app, 0);
    frame(&mut app);
    assert!(refined(&mut app).is_empty(), "despawned at depth 0");
    assert_eq!(handles(&mut app, |q| q.find(target)), None);
}
