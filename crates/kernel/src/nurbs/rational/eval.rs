//! Evaluating a [`NurbsSurface`] (`docs/math.md §12`): the knot span of a
//! parameter and the `p + 1` nonzero basis functions there with their first
//! derivatives (Piegl & Tiller, *The NURBS Book*, A2.1, A2.2 and Eq. 2.7),
//! the point and its first derivatives by the rational quotient rule
//! `S = A/W`, `S_u = (A_u − W_u S)/W` (Eq. 4.8), and whether the surface
//! closes on itself in `u` or in `v`.

use super::{MAX_DEGREE, NurbsSurface};
use glam::DVec3;

/// Basis values and first derivatives at one parameter: the first nonzero
/// function's index, then `p + 1` values and `p + 1` derivatives.
struct BasisDers {
    first: usize,
    n: [f64; MAX_DEGREE + 1],
    d: [f64; MAX_DEGREE + 1],
}

/// The knot span index `k` (`p ≤ k < count`) with `knots[k] ≤ u < knots[k+1]`,
/// the last non-empty span closed at the domain's end (Piegl & Tiller A2.1);
/// `u` is clamped to the domain, a NaN is read as its start.
#[inline]
fn find_span(knots: &[f64], p: usize, count: usize, u: f64) -> (usize, f64) {
    let (a, b) = (knots[p], knots[count]);
    let u = if u.is_nan() { a } else { u.clamp(a, b) };
    if u >= b {
        // the last non-empty span
        let mut k = count - 1;
        while k > p && knots[k] >= b {
            k -= 1;
        }
        return (k, u);
    }
    // first index in p..=count whose knot is > u, minus one
    let idx = knots[p..=count].partition_point(|k| *k <= u) + p;
    (idx.saturating_sub(1).max(p), u)
}

/// The `p + 1` nonzero basis functions at `u` in span `span` and their first
/// derivatives (Piegl & Tiller A2.2, then `N'_{i,p} = p (N_{i,p−1}/(k_{i+p} −
/// k_i) − N_{i+1,p−1}/(k_{i+p+1} − k_{i+1}))`, Eq. 2.7).
#[inline]
fn basis_ders(knots: &[f64], p: usize, span: usize, u: f64) -> BasisDers {
    let mut n = [0.0; MAX_DEGREE + 1];
    let mut d = [0.0; MAX_DEGREE + 1];
    let mut left = [0.0; MAX_DEGREE + 1];
    let mut right = [0.0; MAX_DEGREE + 1];
    n[0] = 1.0;
    for j in 1..=p {
        left[j] = u - knots[span + 1 - j];
        right[j] = knots[span + j] - u;
        if j == p {
            // n holds the degree p − 1 functions N_{span−p+1 .. span, p−1}
            for r in 0..=p {
                // derivative of N_{span−p+r, p}
                let mut v = 0.0;
                if r >= 1 {
                    let i = span - p + r; // N_{i, p-1} = n[r-1]
                    let den = knots[i + p] - knots[i];
                    if den > 0.0 {
                        v += n[r - 1] / den;
                    }
                }
                if r < p {
                    let i1 = span - p + r + 1; // N_{i1, p-1} = n[r]
                    let den = knots[i1 + p] - knots[i1];
                    if den > 0.0 {
                        v -= n[r] / den;
                    }
                }
                d[r] = p as f64 * v;
            }
        }
        let mut saved = 0.0;
        for r in 0..j {
            let den = right[r + 1] + left[j - r];
            let temp = if den != 0.0 { n[r] / den } else { 0.0 };
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
    }
    BasisDers {
        first: span - p,
        n,
        d,
    }
}

impl NurbsSurface {
    /// The homogeneous sums `(A, W, A_u, W_u, A_v, W_v)` at `(u, v)`,
    /// parameters clamped to the domain.
    #[inline]
    fn sums(&self, u: f64, v: f64, ders: bool) -> [[f64; 4]; 3] {
        let (p, q) = (self.degree_u, self.degree_v);
        let (nu, nv) = self.pole_counts();
        let (su, u) = find_span(&self.knots_u, p, nu, u);
        let (sv, v) = find_span(&self.knots_v, q, nv, v);
        let bu = basis_ders(&self.knots_u, p, su, u);
        let bv = basis_ders(&self.knots_v, q, sv, v);
        let mut s = [[0.0; 4]; 3];
        for l in 0..=q {
            let row = (bv.first + l) * nu + bu.first;
            let mut c = [0.0; 4];
            let mut cu = [0.0; 4];
            for k in 0..=p {
                let h = &self.hom[row + k];
                let (a, da) = (bu.n[k], bu.d[k]);
                for x in 0..4 {
                    c[x] += a * h[x];
                    cu[x] += da * h[x];
                }
            }
            let (b, db) = (bv.n[l], bv.d[l]);
            for x in 0..4 {
                s[0][x] += b * c[x];
                if ders {
                    s[1][x] += b * cu[x];
                    s[2][x] += db * c[x];
                }
            }
        }
        s
    }

    /// `S(u, v)`, the parameters clamped to the domain (a NaN reads as its
    /// start).
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let [a, _, _] = self.sums(u, v, false);
        DVec3::new(a[0], a[1], a[2]) / a[3]
    }

    /// `S`, `∂S/∂u`, `∂S/∂v` at `(u, v)` (rational quotient rule
    /// `S_u = (A_u − W_u S)/W`), parameters clamped to the domain. At a
    /// parameter on a knot the derivative is the one of the span that
    /// starts there (of the last span at the domain's end).
    pub fn derivatives(&self, u: f64, v: f64) -> [DVec3; 3] {
        let [a, au, av] = self.sums(u, v, true);
        let w = a[3];
        let s = DVec3::new(a[0], a[1], a[2]) / w;
        let su = (DVec3::new(au[0], au[1], au[2]) - s * au[3]) / w;
        let sv = (DVec3::new(av[0], av[1], av[2]) - s * av[3]) / w;
        [s, su, sv]
    }

    /// Boundary parameters at which closedness is checked: every distinct
    /// knot of the domain and 3 points inside each span.
    fn check_params(spans: &[[f64; 2]]) -> Vec<f64> {
        let mut t = Vec::with_capacity(spans.len() * 4 + 1);
        for s in spans {
            for i in 0..4 {
                t.push(s[0] + (s[1] - s[0]) * i as f64 / 4.0);
            }
        }
        if let Some(s) = spans.last() {
            t.push(s[1]);
        }
        t
    }

    /// Whether the boundary curves `S(u0, ·)` and `S(u1, ·)` coincide within
    /// `tol` (checked at every knot and three points inside each `v` span).
    pub fn closed_u(&self, tol: f64) -> bool {
        let ([u0, u1], _) = self.domain();
        let (_, sv) = self.spans();
        Self::check_params(&sv)
            .iter()
            .all(|&v| self.point(u0, v).distance(self.point(u1, v)) <= tol)
    }

    /// Whether the boundary curves `S(·, v0)` and `S(·, v1)` coincide within
    /// `tol` (checked at every knot and three points inside each `u` span).
    pub fn closed_v(&self, tol: f64) -> bool {
        let (_, [v0, v1]) = self.domain();
        let (su, _) = self.spans();
        Self::check_params(&su)
            .iter()
            .all(|&u| self.point(u, v0).distance(self.point(u, v1)) <= tol)
    }
}
