//! What the views share about the main 3D view: its camera's marker and
//! orbit, the area the panels leave it, the inset of the sphere view inside
//! it, the surface's bounds and requests to frame something. The camera
//! plugin moves the orbit; everything else only reads it.

use super::super::coords::to_view;
use crate::scene::files::format::ViewSpec;
use bevy::prelude::*;
use streamline_kernel::DVec3;

/// Marks the main 3D camera.
#[derive(Component)]
pub struct MainCamera;

/// The orbit camera's state, in kernel coordinates (z up): the target, the
/// distance, the angle about the vertical axis and the angle above the horizon.
#[derive(Component, Debug, Clone, Copy)]
pub struct OrbitCamera {
    /// The point looked at.
    pub target: DVec3,
    /// Distance from the target.
    pub distance: f64,
    /// Radians about the vertical axis.
    pub yaw: f64,
    /// Radians above the horizon.
    pub pitch: f64,
}

impl OrbitCamera {
    /// The eye's direction from the target (unit, kernel coordinates).
    pub fn eye_dir(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        DVec3::new(cp * cy, cp * sy, sp)
    }

    /// The camera transform (view coordinates).
    pub fn transform(&self) -> Transform {
        let eye = to_view(self.target + self.eye_dir() * self.distance);
        Transform::from_translation(eye).looking_at(to_view(self.target), Vec3::Y)
    }

    /// From a scene's view.
    pub fn from_view(v: &ViewSpec) -> Self {
        OrbitCamera {
            target: v.target.vec(),
            distance: v.distance.0.abs().max(1e-3),
            yaw: v.yaw.0.to_radians(),
            pitch: v.pitch.0.to_radians().clamp(-1.55, 1.55),
        }
    }

    /// Looks at a ball of radius `radius` about `center`, keeping the angles.
    pub fn frame(&mut self, center: DVec3, radius: f64) {
        self.target = center;
        // vertical field of view π/4; a margin for the viewport's narrow side
        self.distance = (radius.max(1e-3) / (std::f64::consts::FRAC_PI_8).sin()) * 1.15;
    }
}

/// The surface's bounding box (kernel coordinates).
#[derive(Resource, Debug, Clone, Copy)]
pub struct SceneBounds {
    /// Smallest corner.
    pub min: DVec3,
    /// Largest corner.
    pub max: DVec3,
}

impl Default for SceneBounds {
    fn default() -> Self {
        SceneBounds {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        }
    }
}

impl SceneBounds {
    /// The box's centre.
    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// The box's diagonal.
    pub fn size(&self) -> f64 {
        (self.max - self.min).length()
    }

    /// What "frame all" looks at: the box's centre and half its diagonal.
    pub fn all(&self) -> (DVec3, f64) {
        (self.center(), 0.5 * self.size())
    }
}

/// The area of the window left to the 3D view by the panels (logical pixels),
/// set by the panel system each frame.
#[derive(Resource, Debug, Clone, Copy, Default)]
pub struct ViewArea(pub Option<Rect>);

/// A request to frame something, from the panels or keys.
#[derive(Resource, Debug, Default)]
pub struct FrameRequest(pub Option<(DVec3, f64)>);

/// The sphere view's inset on the window (logical px), `None` when hidden.
#[derive(Resource, Debug, Default, Clone, Copy)]
pub struct SphereArea(pub Option<Rect>);

impl SphereArea {
    /// Whether `p` is inside the inset.
    pub fn contains(&self, p: Vec2) -> bool {
        self.0.is_some_and(|r| r.contains(p))
    }
}
