//! The planar (scalar) versions of the curve schemes, used to subdivide the
//! parameter grids `s`, `t` and `σ` with the same scheme as the tangents (docs/math.md §4).
//! Planar rules: Chaikin Eqs. 49–50, cubic B-spline Eqs. 55–56, 4-point Eq. 60
//! with `w = ω/16` and the quadratic end rule `⅜p₀ + ¾p₁ − ⅛p₂`.
//!
//! [`CurveScheme::refine_scalars`] is defined here (not in `scheme.rs`), so
//! that this file imports `scheme.rs` and not the other way round.

use crate::curve::scheme::{CurveScheme, Stencil};

impl CurveScheme {
    /// One refinement step of planar scalars (the parameter grids: docs/math.md §4), the
    /// same scheme with the ordinary affine combinations (Eqs. 49–50, 55–56, 60).
    pub fn refine_scalars(self, input: &[f64], out: &mut Vec<f64>) {
        refine(self, input, out);
    }
}

/// One step of `scheme` on scalars into `out` (cleared first).
pub fn refine(scheme: CurveScheme, p: &[f64], out: &mut Vec<f64>) {
    out.clear();
    let n = p.len();
    let m = scheme.refined_len(n);
    out.extend((0..m).map(|k| apply(scheme, scheme.stencil(n, k), |j| p[j])));
}

/// Output `k` of one step alone, with the same operations as [`refine`].
#[inline]
pub fn at(scheme: CurveScheme, p: &[f64], k: usize) -> f64 {
    apply(scheme, scheme.stencil(p.len(), k), |j| p[j])
}

/// `w = ω/16` of the planar 4-point rule (Eq. 60).
#[inline(always)]
pub(crate) fn insert_weight(scheme: CurveScheme) -> f64 {
    match scheme {
        CurveScheme::FourPoint { omega } => omega / 16.0,
        _ => 1.0 / 16.0,
    }
}

/// The planar 4-point insert between `b` and `c` (Eq. 60).
#[inline(always)]
pub fn insert(w: f64, a: f64, b: f64, c: f64, d: f64) -> f64 {
    -w * a + (0.5 + w) * (b + c) - w * d
}

/// The planar rule of stencil `st`, reading input `j` as `f(j)`.
#[inline(always)]
pub fn apply(scheme: CurveScheme, st: Stencil, f: impl Fn(usize) -> f64) -> f64 {
    match st {
        Stencil::Copy(i) => f(i),
        Stencil::Mid(i) => 0.5 * (f(i) + f(i + 1)),
        Stencil::Quarter(i) => 0.75 * f(i) + 0.25 * f(i + 1),
        Stencil::ThreeQuarters(i) => 0.25 * f(i) + 0.75 * f(i + 1),
        Stencil::Vertex(i) => 0.125 * f(i - 1) + 0.75 * f(i) + 0.125 * f(i + 1),
        Stencil::Insert(i) => insert(insert_weight(scheme), f(i - 1), f(i), f(i + 1), f(i + 2)),
        Stencil::End(a, b, c) => 0.375 * f(a) + 0.75 * f(b) - 0.125 * f(c),
    }
}
