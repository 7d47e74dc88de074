//! Authoring (docs/math.md §9) on the editor's interaction core, headless under
//! `MinimalPlugins` (as `tests/editor_core.rs`): the initial curve's control
//! tangents are handles of their own kind (a drag moves the curve's tangent,
//! leaves every surface tangent bit for bit, places the streamlines again and
//! re-blends nothing, one undo step, Esc restores), and a selection of
//! several handles (Shift-click) turns together when one of them is dragged
//! (one `RotateMany` per step, one undo step, Esc restores every one).

mod common;

use bevy::prelude::*;
use common::headless_editor::*;
use streamline_kernel::{DQuat, DVec3};
use streamline_studio::ecs::Stats;
use streamline_studio::editor::interaction::{Drag, DragKind, HandleId, Selection};
use streamline_studio::scene::Scene;

fn scene(app: &App) -> Scene {
    streamline_studio::ecs::patch::scene(app.world())
}

fn hold(app: &mut App, k: KeyCode, down: bool) {
    let mut keys = app.world_mut().resource_mut::<ButtonInput<KeyCode>>();
    if down {
        keys.press(k);
    } else {
        keys.release(k);
    }
}

fn esc(app: &mut App) {
    key(app, KeyCode::Escape);
}

#[test]
fn an_initial_tangent_is_a_handle_whose_drag_moves_the_streamlines_rigidly() {
    let mut app = app();
    let n = scene(&app).design.initial().qi().tangents().len();
    let initial = handles(&mut app, |h| h.initial().collect::<Vec<_>>());
    assert_eq!(initial.len(), n, "one handle per initial tangent");
    // each drawn at its curve point, pointing the tangent's way
    for (i, a) in initial.iter().enumerate() {
        assert_eq!(a.id, HandleId::initial(i));
        assert_eq!(a.dir, scene(&app).design.initial().qi().tangents()[i]);
        assert!(a.base.is_finite() && a.length > 0.0);
    }
    let net_before = scene(&app).design.net().clone();
    let initial_before = scene(&app).design.initial().qi().tangents().to_vec();
    let h = HandleId::initial(1);
    press(&mut app, Some(h), Some(DragKind::Sphere));
    assert_eq!(app.world().resource::<Selection>().primary(), Some(h));
    assert!(app.world().resource::<Drag>().0.is_some());
    let start = initial_before[1];
    let targets = [
        (DQuat::from_axis_angle(DVec3::Z, 0.2) * start).normalize(),
        (DQuat::from_axis_angle(DVec3::X, -0.15) * start).normalize(),
    ];
    for t in targets {
        steer(&mut app, t);
        let got = scene(&app).design.initial().qi().tangents()[1];
        assert!((got - t).length() < 1e-12, "{got} != {t}");
        let stats = &app.world().resource::<Stats>().last;
        assert_eq!(
            stats.tangents_reblended, 0,
            "an initial-curve edit re-blends nothing"
        );
        assert!(stats.streamlines_replaced > 0, "{stats:?}");
        // the handle follows the curve's new tangent
        let a = handles(&mut app, |q| q.find(h)).unwrap();
        assert!((a.dir - t).length() < 1e-12);
    }
    assert!(
        *scene(&app).design.net() == net_before,
        "no surface tangent moved"
    );
    assert_eq!(undo_steps(&app), 1, "a drag is one undo step");
    esc(&mut app);
    assert_eq!(
        scene(&app).design.initial().qi().tangents(),
        &initial_before[..],
        "Esc restores the curve exactly"
    );
    assert_eq!(undo_steps(&app), 0);
    // a kept drag, then undo
    press(&mut app, Some(h), Some(DragKind::Sphere));
    steer(&mut app, targets[0]);
    release(&mut app);
    assert_eq!(undo_steps(&app), 1);
    app.world_mut()
        .write_message(streamline_studio::ecs::EditMessage::from(
            streamline_studio::ecs::Edit::Undo,
        ));
    frame(&mut app);
    assert_eq!(
        scene(&app).design.initial().qi().tangents(),
        &initial_before[..]
    );
}

#[test]
fn shift_click_selects_several_and_a_drag_turns_them_all_by_one_rotation() {
    let mut app = app();
    let cells = [(2, 1), (4, 2), (5, 7)];
    let ids: Vec<HandleId> = cells
        .iter()
        .map(|&(r, c)| HandleId::tangent(0, r, c))
        .collect();
    let net_before = scene(&app).design.net().clone();
    let init_before = scene(&app).design.initial().qi().tangents().to_vec();
    // plain click the first, Shift-click the others and an initial tangent
    press(&mut app, Some(ids[0]), None);
    release(&mut app);
    hold(&mut app, KeyCode::ShiftLeft, true);
    for &h in &ids[1..] {
        press(&mut app, Some(h), Some(DragKind::Sphere));
        release(&mut app);
    }
    let init = HandleId::initial(2);
    press(&mut app, Some(init), None);
    release(&mut app);
    // Shift-click again takes it out, and a Shift press on empty space keeps the rest
    press(&mut app, Some(init), None);
    release(&mut app);
    press(&mut app, Some(init), None);
    release(&mut app);
    press(&mut app, None, None);
    release(&mut app);
    hold(&mut app, KeyCode::ShiftLeft, false);
    frame(&mut app);
    let sel: Vec<HandleId> = app.world().resource::<Selection>().iter().collect();
    assert_eq!(sel, [ids[0], ids[1], ids[2], init]);
    assert!(
        app.world().resource::<Drag>().0.is_none(),
        "Shift-click starts no drag"
    );
    // drag the second: it becomes primary, the group stays
    press(&mut app, Some(ids[1]), Some(DragKind::Sphere));
    assert_eq!(app.world().resource::<Selection>().primary(), Some(ids[1]));
    assert_eq!(app.world().resource::<Selection>().len(), 4);
    let start = net_before.get(4, 2);
    let steps = [
        (DQuat::from_axis_angle(DVec3::new(0.3, 0.2, 1.0).normalize(), 0.25) * start).normalize(),
        (DQuat::from_axis_angle(DVec3::new(-1.0, 0.5, 0.1).normalize(), 0.3) * start).normalize(),
    ];
    for &t in &steps {
        steer(&mut app, t);
    }
    // the rotation that took the dragged tangent to its place, applied to all
    let q = DQuat::from_rotation_arc(start, steps[1]);
    let now = scene(&app);
    let net = now.design.net();
    for &(r, c) in &cells {
        let want = q * net_before.get(r, c);
        assert!(
            (net.get(r, c) - want).length() < 1e-9,
            "({r}, {c}): {} != {want}",
            net.get(r, c)
        );
    }
    let got = scene(&app).design.initial().qi().tangents()[2];
    assert!(
        (got - q * init_before[2]).length() < 1e-9,
        "the initial tangent turns too"
    );
    for r in 0..net.rows() {
        for c in 0..net.cols() {
            if !cells.contains(&(r, c)) {
                assert_eq!(net.get(r, c), net_before.get(r, c), "({r}, {c}) moved");
            }
        }
    }
    assert_eq!(undo_steps(&app), 1, "a group drag is one undo step");
    esc(&mut app);
    assert!(
        *scene(&app).design.net() == net_before,
        "Esc restores every tangent"
    );
    assert_eq!(
        scene(&app).design.initial().qi().tangents(),
        &init_before[..]
    );
    assert_eq!(undo_steps(&app), 0);
}
