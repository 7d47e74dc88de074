//! Exact comparisons: what the incremental paths compare to know that an
//! input did not change at all (the same bits give the same results; `==`
//! would take `-0.0` for `0.0`, and never a NaN for itself).

use glam::DVec3;

/// The bits of a vector.
pub(crate) fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

/// Two runs of vectors bit for bit equal (and of the same length).
pub(crate) fn same(a: &[DVec3], b: &[DVec3]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| bits(*x) == bits(*y))
}
