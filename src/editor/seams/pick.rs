//! Clicking a surface selects its patch: a ray from the pointer against
//! each shown patch's triangles, the nearest hit wins, and its name is sent
//! as `Edit::Patch(PatchEdit::SetPatch)`, which sets [`ActivePatch`] (not an
//! undo step).
//!
//! The hook with handle picking (`handles/picking.rs`) is its
//! [`HandlePressed`] message: a left press in the 3D view on no handle is
//! reported as `HandlePressed { handle: None, .. }` (the selection is
//! cleared), and only that press is tried against the surfaces here. So a
//! click that hits a handle picks the handle, as before, and never changes
//! the patch; a Shift press (a box selection) does not either. The sphere
//! inset reports no empty press, and a press over it is ignored.

use super::super::coords::from_view;
use super::super::interaction::{EditorMode, EditorSet, HandlePressed, MainCamera, SphereArea};
use super::super::surface::patches::{PatchMeshes, PickedPatches};
use crate::ecs::SurfaceData;
use crate::ecs::joined::ActivePatch;
use crate::ecs::{Edit, EditMessage};
use crate::scene::edits::patch_edit::PatchEdit;
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_state::prelude::in_state;
use streamline_kernel::DVec3;

pub struct PatchPickPlugin;

impl Plugin for PatchPickPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(
            Update,
            pick.in_set(EditorSet::Drag)
                .run_if(in_state(EditorMode::Streamline)),
        );
    }
}

/// The distance along the ray `origin + λ dir` to triangle `(a, b, c)`
/// (Möller–Trumbore), `None` when it misses or the hit is behind.
pub fn ray_triangle(origin: DVec3, dir: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > 0.0 && t.is_finite()).then_some(t)
}

/// The nearest hit of the ray on a triangle mesh.
pub fn ray_mesh(origin: DVec3, dir: DVec3, positions: &[DVec3], indices: &[u32]) -> Option<f64> {
    indices
        .chunks_exact(3)
        .filter_map(|t| {
            let p = |i: u32| positions.get(i as usize).copied();
            ray_triangle(origin, dir, p(t[0])?, p(t[1])?, p(t[2])?)
        })
        .min_by(f64::total_cmp)
}

/// The patch under a press on empty space, made the active one.
#[allow(clippy::too_many_arguments)]
fn pick(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut presses: MessageReader<HandlePressed>,
    keys: Res<ButtonInput<KeyCode>>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    sphere: Res<SphereArea>,
    (kernel, data): (Res<PatchMeshes>, Res<SurfaceData>),
    patches: PickedPatches,
    active: Res<ActivePatch>,
    mut edits: MessageWriter<EditMessage>,
) {
    let _meter = meter.start();
    let empty = presses.read().any(|p| p.handle.is_none());
    if !empty || keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]) {
        return;
    }
    // a document of one patch has no patch to choose
    if !patches.iter().any(|r| r.2) {
        return;
    }
    let Some(cursor) = window.cursor_position().filter(|p| !sphere.contains(*p)) else {
        return;
    };
    let Ok((camera, gt)) = camera.single() else {
        return;
    };
    let Ok(ray) = camera.viewport_to_world(gt, cursor) else {
        return;
    };
    let (origin, dir) = (from_view(ray.origin), from_view(*ray.direction));
    let mut best: Option<(f64, Entity)> = None;
    for (e, _, joined, hidden, surface) in &patches {
        if hidden {
            continue;
        }
        let hit = (kernel.shown(e, joined, surface, &data))
            .and_then(|(points, triangles)| ray_mesh(origin, dir, points.data(), triangles));
        if let Some(t) = hit
            && best.is_none_or(|(b, _)| t < b)
        {
            best = Some((t, e));
        }
    }
    let Some((_, e)) = best else {
        return;
    };
    let Ok((_, slot, ..)) = patches.get(e) else {
        return;
    };
    // `ActivePatch(None)` is the first patch
    let current = active.0.unwrap_or_else(|| {
        (patches.iter().find(|r| r.1.index == 0)).map_or(Entity::PLACEHOLDER, |r| r.0)
    });
    if current != e {
        edits.write(EditMessage::from(Edit::Patch(PatchEdit::SetPatch(
            slot.name.clone(),
        ))));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square of two triangles in the plane z = 1.
    fn square() -> (Vec<DVec3>, Vec<u32>) {
        let p = vec![
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        (p, vec![0, 1, 2, 0, 2, 3])
    }

    /// Hits are at the plane's distance along the ray (computed by hand),
    /// whatever the ray's slant; misses and hits behind are none.
    #[test]
    fn rays_hit_the_square_where_the_plane_is() {
        let (p, i) = square();
        let o = DVec3::new(0.3, 0.6, -2.0);
        for slant in [0.0, 0.05, -0.05] {
            let dir = DVec3::new(slant, slant, 1.0);
            let t = ray_mesh(o, dir, &p, &i).expect("inside the square");
            // z: −2 + t = 1
            assert!((t - 3.0).abs() < 1e-12, "{t}");
        }
        // outside the square
        assert_eq!(ray_mesh(DVec3::new(1.5, 0.5, -2.0), DVec3::Z, &p, &i), None);
        // the square behind the ray
        assert_eq!(ray_mesh(o, -DVec3::Z, &p, &i), None);
        // parallel to it
        assert_eq!(ray_mesh(o, DVec3::X, &p, &i), None);
        // bad indices are skipped, not a panic
        assert_eq!(ray_mesh(o, DVec3::Z, &p, &[0, 1, 9]), None);
    }

    /// The nearest of two stacked surfaces wins.
    #[test]
    fn the_nearest_hit_wins() {
        let (mut p, mut i) = square();
        p.extend(p.clone().iter().map(|q| *q + DVec3::Z));
        i.extend([4, 5, 6, 4, 6, 7]);
        let t = ray_mesh(DVec3::new(0.5, 0.4, 5.0), -DVec3::Z, &p, &i).unwrap();
        assert!((t - 3.0).abs() < 1e-12, "{t}");
    }
}
