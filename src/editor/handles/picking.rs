//! Picking handles in the 3D view and turning them on a trackball. The
//! pointer picks the nearest arrow shaft on screen (within 8 px); a left
//! press reports it to the interaction core's drag state machine, and while
//! the drag lasts the pointer asks for a direction on a virtual trackball
//! about the arrow's base (Bell's trackball: a sphere near the centre, a
//! hyperbolic sheet outside, so the rotation never jumps). The core turns
//! each step into an edit of the drag's undo group (one undo step, the
//! surface following in the same frame) and Esc into `CancelGroup`.

use super::super::coords::{from_view, to_view};
use super::super::interaction::{
    Drag, DragKind, DragTo, EditorMode, EditorSet, HandlePressed, HandleQuery, HandleSettings,
    MainCamera, Selection, SphereArea,
};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::input::egui_wants_any_pointer_input;
use bevy_state::prelude::in_state;
use streamline_kernel::DVec3;

pub struct PickingPlugin;

impl Plugin for PickingPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(
            Update,
            (
                (hover, press).chain().run_if(
                    not(egui_wants_any_pointer_input).and_then(in_state(EditorMode::Streamline)),
                ),
                drag_move,
            )
                .chain()
                .in_set(EditorSet::Input),
        );
    }
}

/// Projects kernel points of the 3D view to the window (logical px).
fn projector<'a>(
    camera: &'a Camera,
    gt: &'a GlobalTransform,
) -> impl Fn(DVec3) -> Option<Vec2> + 'a {
    move |p| camera.world_to_viewport(gt, to_view(p)).ok()
}

/// The cursor if it is over the main 3D view (not the sphere inset).
fn view_cursor(window: &Window, camera: &Camera, sphere: &SphereArea) -> Option<Vec2> {
    let p = window.cursor_position()?;
    let r = camera.logical_viewport_rect()?;
    (r.contains(p) && !sphere.contains(p)).then_some(p)
}

#[allow(clippy::too_many_arguments)]
fn hover(
    meter: Res<crate::ecs::meter::CpuMeter>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    handles: HandleQuery,
    settings: Res<HandleSettings>,
    sphere: Res<SphereArea>,
    drag: Res<Drag>,
    mut selection: ResMut<Selection>,
) {
    let _meter = meter.start();
    let Ok((camera, gt)) = camera.single() else {
        return;
    };
    let hovered = if drag.0.is_some() {
        None
    } else {
        view_cursor(&window, camera, &sphere)
            .and_then(|c| handles.pick_on_screen(&settings, c, projector(camera, gt), 8.0))
    };
    if selection.hover != hovered {
        selection.hover = hovered;
    }
}

/// A left press in the 3D view: on the hovered handle (a trackball drag) or
/// on empty space.
#[allow(clippy::too_many_arguments)]
fn press(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    handles: HandleQuery,
    sphere: Res<SphereArea>,
    selection: Res<Selection>,
    drag: Res<Drag>,
    mut presses: MessageWriter<HandlePressed>,
) {
    let _meter = meter.start();
    if !buttons.just_pressed(MouseButton::Left) || drag.0.is_some() {
        return;
    }
    let Ok((camera, gt)) = camera.single() else {
        return;
    };
    let Some(cursor) = view_cursor(&window, camera, &sphere) else {
        return;
    };
    let Some(h) = selection.hover else {
        presses.write(HandlePressed {
            handle: None,
            drag: None,
        });
        return;
    };
    let trackball = handles
        .find(h)
        .and_then(|a| a.on_screen(projector(camera, gt)))
        .map(|(center, tip)| DragKind::Trackball {
            center,
            radius: center.distance(tip).max(90.0),
            start: cursor,
            camera: gt.compute_transform().rotation,
        });
    presses.write(HandlePressed {
        handle: Some(h),
        drag: trackball,
    });
}

/// A screen point on Bell's trackball, in camera coordinates (x right, y up, z to the viewer).
pub fn trackball_point(p: Vec2, center: Vec2, radius: f32) -> Vec3 {
    let x = (p.x - center.x) / radius;
    let y = -(p.y - center.y) / radius;
    let d2 = x * x + y * y;
    let z = if d2 <= 0.5 {
        (1.0 - d2).sqrt()
    } else {
        0.5 / d2.sqrt()
    };
    Vec3::new(x, y, z).normalize()
}

/// The direction a trackball drag from `start` to `now` gives `dir`.
pub fn trackball_rotate(
    dir: DVec3,
    start: Vec2,
    now: Vec2,
    center: Vec2,
    radius: f32,
    camera: Quat,
) -> DVec3 {
    let q = Quat::from_rotation_arc(
        trackball_point(start, center, radius),
        trackball_point(now, center, radius),
    );
    let world = camera * q * camera.inverse();
    let turned = world.as_dquat() * to_view(dir).as_dvec3();
    from_view(turned.as_vec3()).try_normalize().unwrap_or(dir)
}

/// The direction a trackball drag asks for at the pointer.
fn drag_move(
    meter: Res<crate::ecs::meter::CpuMeter>,
    window: Single<&Window, With<PrimaryWindow>>,
    drag: Res<Drag>,
    mut to: MessageWriter<DragTo>,
) {
    let _meter = meter.start();
    let Some(d) = drag.0.as_ref() else {
        return;
    };
    let DragKind::Trackball {
        center,
        radius,
        start,
        camera,
    } = d.kind
    else {
        return;
    };
    let Some(p) = window.cursor_position() else {
        return;
    };
    to.write(DragTo(trackball_rotate(
        d.start_dir,
        start,
        p,
        center,
        radius,
        camera,
    )));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trackball_keeps_unit_length_and_follows_the_pointer() {
        let dir = DVec3::new(1.0, 0.0, 0.0);
        let c = Vec2::new(400.0, 300.0);
        // no motion: no turn
        let same = trackball_rotate(dir, c, c, c, 100.0, Quat::IDENTITY);
        assert!((same - dir).length() < 1e-6);
        // camera looking down −z (view): dragging right turns +x (view) ... a turn about view y
        for p in [
            Vec2::new(450.0, 300.0),
            Vec2::new(900.0, 50.0),
            Vec2::new(-500.0, 900.0),
        ] {
            let d = trackball_rotate(dir, c, p, c, 100.0, Quat::IDENTITY);
            assert!((d.length() - 1.0).abs() < 1e-6 && d.is_finite());
        }
        // dragging straight up from the centre tilts a view-x arrow about view x: it stays
        let d = trackball_rotate(dir, c, Vec2::new(400.0, 250.0), c, 100.0, Quat::IDENTITY);
        assert!((d - dir).length() < 1e-5, "{d}");
        // a tangent along view z (kernel −y) dragged right turns towards view x (kernel x)
        let toward_viewer = DVec3::new(0.0, -1.0, 0.0);
        let d = trackball_rotate(
            toward_viewer,
            c,
            Vec2::new(450.0, 300.0),
            c,
            100.0,
            Quat::IDENTITY,
        );
        assert!(d.x > 0.3, "{d}");
    }
}
