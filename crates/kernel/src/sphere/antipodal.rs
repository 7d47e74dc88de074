//! Which blends of a build take the antipodal branch (docs/math.md §1).
//!
//! Two neighbouring tangents that point in opposite directions have no
//! great circle of their own: [`super::blend::blend`] and [`super::blend::mid`]
//! then turn about a fixed axis perpendicular to the first (`antipodal_axis`),
//! so the surface there depends on that documented choice rather than on
//! the designer's tangents. Every step of the tensor-product schemes
//! (docs/math.md §3) blends neighbours along a row and along a column of the
//! level it refines, and the initial curve's QI curve rotates between
//! consecutive control tangents (docs/math.md §2); this module says which
//! pairs take the antipodal branch ([`is_antipodal`]) and finds them among
//! the initial curve's tangents; `crate::levels::antipodal` finds them in a
//! build's levels, so that a build reports them from its own levels (a
//! process-wide counter cannot say which tangents, nor which build, they
//! belong to).

use super::blend::{DEGENERATE_SIN, MID_MIN_NORM2};
use glam::DVec3;

/// `a·b` above which a pair cannot be antipodal: `|a × b| ≤ 1e-14` with
/// `a·b < 0` means `a·b < −(1 − 1e-28)`, and `|a + b|² ≤ 1e-24` means
/// `a·b ≤ −1 + 5e-25`; a dot product over `−0.5` rules both out, so the scan
/// computes a cross product only for pairs more than 120° apart.
pub(crate) const SCAN_DOT: f64 = -0.5;

/// Whether the blend of the unit vectors `a` and `b` takes the antipodal
/// branch: the predicate of [`super::blend::blend`] (`|a × b| ≤ 1e-14`,
/// `a·b < 0`) or of [`super::blend::mid`] (`|a + b|² ≤ 1e-24`).
#[inline]
pub fn is_antipodal(a: DVec3, b: DVec3) -> bool {
    let c = a.dot(b);
    c < SCAN_DOT
        && ((a + b).length_squared() <= MID_MIN_NORM2 || a.cross(b).length() <= DEGENERATE_SIN)
}

/// The indices `k` of consecutive control tangents `k, k + 1` of a curve
/// (the initial curve's QI curve, docs/math.md §2) that point in opposite
/// directions, where the QI curve's rotation axis is the fixed one.
pub fn antipodal_legs(tangents: &[DVec3]) -> Vec<usize> {
    tangents
        .windows(2)
        .enumerate()
        .filter(|(_, w)| is_antipodal(w[0], w[1]))
        .map(|(k, _)| k)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sphere::blend::{antipodal_events, blend, mid};

    /// The predicate is the blend's own: a pair it flags takes the counted
    /// branch, and a pair a hair away from antipodal does not.
    #[test]
    fn is_antipodal_matches_the_blend_branch() {
        for a in [
            DVec3::X,
            DVec3::new(0.6, 0.8, 0.0),
            DVec3::new(1.0, 2.0, -3.0).normalize(),
        ] {
            assert!(is_antipodal(a, -a), "{a}");
            let before = antipodal_events();
            let _ = blend(a, -a, 0.3);
            let _ = mid(a, -a);
            assert!(antipodal_events() >= before + 2, "{a}: branch taken");
            let off = (-a + a.any_orthonormal_vector() * 1e-6).normalize();
            assert!(!is_antipodal(a, off), "{a}: 1e-6 rad off is a great circle");
            assert!(!is_antipodal(a, a));
        }
    }

    /// The initial curve's consecutive tangents that point apart.
    #[test]
    fn antipodal_legs_names_opposite_neighbours() {
        let x = DVec3::X;
        assert_eq!(antipodal_legs(&[x, -x, DVec3::Y, -DVec3::Y]), vec![0, 2]);
        assert!(antipodal_legs(&[x]).is_empty());
    }
}
