//! The kernel's axes (z up) and Bevy's (y up): positions are shown as `(x, z, −y)`,
//! a proper rotation (−90° about x), so windings and normals carry over.

use bevy::prelude::*;
use streamline_kernel::DVec3;

/// Kernel coordinates to the view's.
pub fn to_view(p: DVec3) -> Vec3 {
    Vec3::new(p.x as f32, p.z as f32, -p.y as f32)
}

/// The view's coordinates to the kernel's.
pub fn from_view(v: Vec3) -> DVec3 {
    DVec3::new(v.x as f64, -(v.z as f64), v.y as f64)
}

/// The rotation that takes kernel coordinates to the view's (for mesh entities).
pub fn kernel_to_view() -> Quat {
    Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_rotation_agree() {
        let p = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(from_view(to_view(p)), p);
        assert!((kernel_to_view() * p.as_vec3() - to_view(p)).length() < 1e-6);
    }
}
