//! The planar (scalar) versions of the curve schemes, used to subdivide the
//! parameter grids `s`, `t` and `σ` with the same scheme as the tangents (SPEC §4).
//! Planar rules: Chaikin Eqs. 49–50, cubic B-spline Eqs. 55–56, 4-point Eq. 60
//! with `w = ω/16` and the quadratic end rule `⅜p₀ + ¾p₁ − ⅛p₂`.

use crate::curve::CurveScheme;

/// One step of `scheme` on scalars into `out` (cleared first).
pub fn refine(scheme: CurveScheme, p: &[f64], out: &mut Vec<f64>) {
    out.clear();
    let n = p.len();
    match scheme {
        CurveScheme::Chaikin => {
            for w in p.windows(2) {
                out.push(0.75 * w[0] + 0.25 * w[1]);
                out.push(0.25 * w[0] + 0.75 * w[1]);
            }
        }
        CurveScheme::CubicBSpline => {
            out.push(0.5 * (p[0] + p[1]));
            for i in 1..n - 1 {
                out.push(0.125 * p[i - 1] + 0.75 * p[i] + 0.125 * p[i + 1]);
                out.push(0.5 * (p[i] + p[i + 1]));
            }
        }
        CurveScheme::FourPoint { omega } => {
            if n == 2 {
                out.extend_from_slice(&[p[0], 0.5 * (p[0] + p[1]), p[1]]);
                return;
            }
            let w = omega / 16.0;
            let end = |a: f64, b: f64, c: f64| 0.375 * a + 0.75 * b - 0.125 * c;
            out.push(p[0]);
            out.push(end(p[0], p[1], p[2]));
            for i in 1..n - 2 {
                out.push(p[i]);
                out.push(-w * p[i - 1] + (0.5 + w) * (p[i] + p[i + 1]) - w * p[i + 2]);
            }
            out.push(p[n - 2]);
            out.push(end(p[n - 1], p[n - 2], p[n - 3]));
            out.push(p[n - 1]);
        }
    }
}

/// Output `k` of one step alone, with the same operations as [`refine`].
#[inline]
pub fn at(scheme: CurveScheme, p: &[f64], k: usize) -> f64 {
    let n = p.len();
    match scheme {
        CurveScheme::Chaikin => {
            let i = k / 2;
            if k.is_multiple_of(2) {
                0.75 * p[i] + 0.25 * p[i + 1]
            } else {
                0.25 * p[i] + 0.75 * p[i + 1]
            }
        }
        CurveScheme::CubicBSpline => {
            if k == 0 {
                0.5 * (p[0] + p[1])
            } else if k % 2 == 1 {
                let i = k.div_ceil(2);
                0.125 * p[i - 1] + 0.75 * p[i] + 0.125 * p[i + 1]
            } else {
                0.5 * (p[k / 2] + p[k / 2 + 1])
            }
        }
        CurveScheme::FourPoint { omega } => {
            if k.is_multiple_of(2) {
                return p[k / 2];
            }
            if n == 2 {
                return 0.5 * (p[0] + p[1]);
            }
            let w = omega / 16.0;
            let end = |a: f64, b: f64, c: f64| 0.375 * a + 0.75 * b - 0.125 * c;
            if k == 1 {
                end(p[0], p[1], p[2])
            } else if k == 2 * n - 3 {
                end(p[n - 1], p[n - 2], p[n - 3])
            } else {
                let i = (k - 1) / 2;
                -w * p[i - 1] + (0.5 + w) * (p[i] + p[i + 1]) - w * p[i + 2]
            }
        }
    }
}
