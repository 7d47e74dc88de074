//! The validated unit vector at the kernel's boundary.

use crate::error::{KernelError, Place};
use glam::DVec3;

/// A unit vector: a point of the Gaussian sphere. Built only through [`Tangent::new`],
/// so loops inside the kernel never re-check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangent(DVec3);

/// Why a vector is not a direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum TangentFault {
    /// All components are zero.
    Zero,
    /// A component is NaN or infinite.
    NonFinite,
}

impl Tangent {
    /// Normalises `v`. Works for any finite non-zero input, from subnormal to
    /// `f64::MAX` components: the vector is first divided by its largest
    /// absolute component so that squaring can neither overflow nor underflow.
    ///
    /// A vector already unit to within [`Tangent::UNIT_TOLERANCE`] is kept
    /// bit for bit, so normalising is idempotent (a saved scene loads back identical).
    pub fn new(v: DVec3) -> Result<Self, TangentFault> {
        if !v.is_finite() {
            return Err(TangentFault::NonFinite);
        }
        if (v.length_squared() - 1.0).abs() <= Self::UNIT_TOLERANCE {
            return Ok(Tangent(v));
        }
        let m = v.abs().max_element();
        if m == 0.0 {
            return Err(TangentFault::Zero);
        }
        let w = v / m;
        Ok(Tangent(w / w.length()))
    }

    /// `| |v|² − 1 |` below which a vector counts as unit already (4 ulp of 1).
    pub const UNIT_TOLERANCE: f64 = 4.0 * f64::EPSILON;

    /// The unit vector.
    #[inline]
    pub fn get(self) -> DVec3 {
        self.0
    }
}

impl From<Tangent> for DVec3 {
    fn from(t: Tangent) -> DVec3 {
        t.0
    }
}

/// Normalises one vector, reporting a fault at `at`.
pub(crate) fn normalize_at(v: DVec3, at: Place) -> Result<DVec3, KernelError> {
    Tangent::new(v)
        .map(Tangent::get)
        .map_err(|fault| match fault {
            TangentFault::Zero => KernelError::ZeroTangent { at },
            TangentFault::NonFinite => KernelError::NonFiniteTangent { at },
        })
}

/// Normalises a curve's tangents; the first bad one is reported by index.
pub fn normalize_all(vs: &[DVec3]) -> Result<Vec<DVec3>, KernelError> {
    vs.iter()
        .enumerate()
        .map(|(i, &v)| normalize_at(v, Place::Curve(i)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_normalises_extremes() {
        for v in [
            DVec3::new(1e-320, 0.0, 0.0),
            DVec3::new(f64::MAX, f64::MAX, -f64::MAX),
            DVec3::new(3.0, 4.0, 0.0),
        ] {
            let t = Tangent::new(v).unwrap().get();
            assert!((t.length() - 1.0).abs() < 1e-15, "{v:?} -> {t:?}");
        }
    }

    #[test]
    fn tangent_rejects_zero_and_nan() {
        assert_eq!(Tangent::new(DVec3::ZERO), Err(TangentFault::Zero));
        assert_eq!(
            Tangent::new(DVec3::new(f64::NAN, 0.0, 1.0)),
            Err(TangentFault::NonFinite)
        );
        assert_eq!(
            Tangent::new(DVec3::new(f64::INFINITY, 0.0, 1.0)),
            Err(TangentFault::NonFinite)
        );
    }
}
