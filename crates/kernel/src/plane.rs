//! A mirror plane and its reflection (`docs/math.md §9`, Mirror symmetry): the
//! plane `P` of a mirrored design, shared by the initial curve (which is
//! reflected below the seam) and the authoring module (which doubles the net),
//! so it sits below both.

use crate::error::KernelError;
use glam::DVec3;

/// A seam tangent within this angle (radians) of `P` counts as in the plane
/// and is kept bit for bit.
pub const SEAM_IN_PLANE: f64 = 1e-14;

/// A seam tangent within this angle (radians) of `P`'s normal has no usable
/// direction in `P`: refused.
pub const SEAM_MIN_SIN: f64 = 1e-6;

/// A plane `{x : (x − point)·normal = 0}`, `normal` unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MirrorPlane {
    /// A point of the plane.
    pub point: DVec3,
    /// Its unit normal.
    pub normal: DVec3,
}

impl MirrorPlane {
    /// The reflection of a point.
    #[inline]
    pub fn reflect_point(&self, p: DVec3) -> DVec3 {
        p - self.normal * (2.0 * (p - self.point).dot(self.normal))
    }

    /// The reflection of a direction (the linear part of `R`).
    #[inline]
    pub(crate) fn reflect_dir(&self, v: DVec3) -> DVec3 {
        v - self.normal * (2.0 * v.dot(self.normal))
    }

    /// Signed distance of a point from the plane.
    #[inline]
    pub fn distance(&self, p: DVec3) -> f64 {
        (p - self.point).dot(self.normal)
    }

    /// The unit tangent `v` projected into the plane: `v` itself when it is
    /// within [`SEAM_IN_PLANE`] of it, else `v − (v·n) n` normalised; refused
    /// when `v` is within [`SEAM_MIN_SIN`] of the normal (`col` names it).
    pub fn project_dir(&self, v: DVec3, col: usize) -> Result<DVec3, KernelError> {
        let d = v.dot(self.normal);
        if d.abs() <= SEAM_IN_PLANE {
            return Ok(v);
        }
        let w = v - self.normal * d;
        let len = w.length();
        if len.is_nan() || len <= SEAM_MIN_SIN {
            return Err(KernelError::SeamTangentAlongNormal { col });
        }
        Ok(w / len)
    }
}
