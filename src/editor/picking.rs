//! Picking and dragging tangent arrows. The pointer picks the nearest arrow
//! shaft on screen (within 8 px); a left drag turns that tangent on a virtual
//! trackball about the arrow's base (Bell's trackball: a sphere near the centre,
//! a hyperbolic sheet outside, so the rotation never jumps). Every step is a
//! `SetDirection` edit of one group, so the drag is one undo step and the
//! surface follows in the same frame; Esc sends `CancelGroup`, which restores
//! the direction and forgets the step.

use super::camera::MainCamera;
use super::coords::{from_view, to_view};
use super::handles::{HandleArrows, HandleSettings};
use super::sphere_view::SphereArea;
use crate::ecs::{Edit, EditMessage, ModelSet};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::input::egui_wants_any_pointer_input;
use streamline_kernel::DVec3;

/// The selected and the hovered handle, `(row, col)` at the edit depth.
#[derive(Resource, Debug, Default, Clone, Copy, PartialEq)]
pub struct Selection {
    /// Selected (the Selection panel edits it).
    pub handle: Option<(usize, usize)>,
    /// Under the pointer.
    pub hover: Option<(usize, usize)>,
}

/// How a drag turns its tangent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DragKind {
    /// A trackball about the arrow's base in the 3D view.
    Trackball {
        /// The base on screen (logical px).
        center: Vec2,
        /// The trackball's radius on screen (px).
        radius: f32,
        /// Where the drag started.
        start: Vec2,
        /// The camera's rotation when it started.
        camera: Quat,
    },
    /// The point follows the pointer on the Gaussian sphere view.
    Sphere,
}

/// A drag in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActiveDrag {
    /// Handle row at the edit depth.
    pub row: usize,
    /// Handle column.
    pub col: usize,
    /// Undo group of its edits.
    pub group: u64,
    /// The direction when it started (Esc restores it).
    pub start_dir: DVec3,
    /// The last direction sent.
    pub last: DVec3,
    /// Whether any edit was sent.
    pub sent: bool,
    /// Trackball or sphere.
    pub kind: DragKind,
}

impl ActiveDrag {
    /// Points the dragged tangent at `dir`: one `SetDirection` of the drag's
    /// undo group, unless it barely moved.
    pub fn steer(&mut self, dir: DVec3, edits: &mut MessageWriter<EditMessage>) {
        if (dir - self.last).length() < 1e-7 {
            return;
        }
        self.last = dir;
        self.sent = true;
        edits.write(EditMessage {
            edit: Edit::SetDirection {
                row: self.row,
                col: self.col,
                dir,
            },
            group: Some(self.group),
        });
    }
}

/// The drag in progress, if any.
#[derive(Resource, Debug, Default)]
pub struct Drag(pub Option<ActiveDrag>);

/// Hands out undo groups for drags.
#[derive(Resource, Debug, Default)]
pub struct DragGroups(u64);

impl DragGroups {
    /// A group no earlier drag used.
    pub fn next(&mut self) -> u64 {
        self.0 += 1;
        // keep clear of groups other tools might pick (small numbers)
        (1 << 40) + self.0
    }
}

pub struct PickingPlugin;

impl Plugin for PickingPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<Selection>()
            .init_resource::<Drag>()
            .init_resource::<DragGroups>()
            .add_systems(
                Update,
                (
                    hover.run_if(
                        not(egui_wants_any_pointer_input)
                            .and_then(super::mesh_mode::streamline_mode),
                    ),
                    press.run_if(
                        not(egui_wants_any_pointer_input)
                            .and_then(super::mesh_mode::streamline_mode),
                    ),
                    drag_move,
                    release_or_cancel,
                    keep_selection_valid,
                )
                    .chain()
                    .before(ModelSet::Edit),
            );
    }
}

/// Distance from `p` to the segment `a`–`b` (screen px).
fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-9)).clamp(0.0, 1.0);
    (a + ab * t).distance(p)
}

/// The pickable handle nearest the cursor, within `max_px`.
fn pick(
    cursor: Vec2,
    camera: &Camera,
    gt: &GlobalTransform,
    arrows: &HandleArrows,
    settings: &HandleSettings,
    max_px: f32,
) -> Option<(usize, usize)> {
    let mut best: Option<((usize, usize), f32)> = None;
    let refined_hidden = arrows.edit_depth > 0 && !settings.refined;
    for a in &arrows.handles {
        if refined_hidden || !settings.shows(a.level, a.row, a.col) {
            continue;
        }
        let (Ok(p0), Ok(p1)) = (
            camera.world_to_viewport(gt, to_view(a.base)),
            camera.world_to_viewport(gt, to_view(a.tip())),
        ) else {
            continue;
        };
        let d = segment_distance(cursor, p0, p1);
        if d <= max_px && best.is_none_or(|(_, bd)| d < bd) {
            best = Some(((a.row, a.col), d));
        }
    }
    best.map(|(h, _)| h)
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
    arrows: Res<HandleArrows>,
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
            .and_then(|c| pick(c, camera, gt, &arrows, &settings, 8.0))
    };
    if selection.hover != hovered {
        selection.hover = hovered;
    }
}

#[allow(clippy::too_many_arguments)]
fn press(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    arrows: Res<HandleArrows>,
    sphere: Res<SphereArea>,
    mut selection: ResMut<Selection>,
    mut drag: ResMut<Drag>,
    mut groups: ResMut<DragGroups>,
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
        selection.handle = None;
        return;
    };
    selection.handle = Some(h);
    let Some(a) = arrows.find(h) else {
        return;
    };
    let (Ok(center), Ok(tip)) = (
        camera.world_to_viewport(gt, to_view(a.base)),
        camera.world_to_viewport(gt, to_view(a.tip())),
    ) else {
        return;
    };
    drag.0 = Some(ActiveDrag {
        row: h.0,
        col: h.1,
        group: groups.next(),
        start_dir: a.dir,
        last: a.dir,
        sent: false,
        kind: DragKind::Trackball {
            center,
            radius: center.distance(tip).max(90.0),
            start: cursor,
            camera: gt.compute_transform().rotation,
        },
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

fn drag_move(
    meter: Res<crate::ecs::meter::CpuMeter>,
    window: Single<&Window, With<PrimaryWindow>>,
    mut drag: ResMut<Drag>,
    mut edits: MessageWriter<EditMessage>,
) {
    let _meter = meter.start();
    let Some(d) = drag.0.as_mut() else {
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
    let dir = trackball_rotate(d.start_dir, start, p, center, radius, camera);
    d.steer(dir, &mut edits);
}

fn release_or_cancel(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    mut drag: ResMut<Drag>,
    mut selection: ResMut<Selection>,
    mut edits: MessageWriter<EditMessage>,
) {
    let _meter = meter.start();
    if keys.just_pressed(KeyCode::Escape) {
        match drag.0.take() {
            Some(d) if d.sent => {
                edits.write(EditMessage::from(Edit::CancelGroup(d.group)));
            }
            Some(_) => {}
            None => selection.handle = None,
        }
        return;
    }
    if drag.0.is_some() && !buttons.pressed(MouseButton::Left) {
        drag.0 = None;
    }
}

/// Drops a selection that no longer exists (after a depth change or a load).
fn keep_selection_valid(
    meter: Res<crate::ecs::meter::CpuMeter>,
    arrows: Res<HandleArrows>,
    mut selection: ResMut<Selection>,
) {
    let _meter = meter.start();
    if !arrows.is_changed() || arrows.handles.is_empty() {
        return;
    }
    if let Some(h) = selection.handle
        && arrows.find(h).is_none()
    {
        selection.handle = None;
    }
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

    #[test]
    fn segment_distance_is_euclidean() {
        let (a, b) = (Vec2::ZERO, Vec2::new(10.0, 0.0));
        assert_eq!(segment_distance(Vec2::new(5.0, 3.0), a, b), 3.0);
        assert_eq!(segment_distance(Vec2::new(-4.0, 3.0), a, b), 5.0);
    }
}
