//! The size of a [`NurbsSurface`] (`docs/math.md §12`): its area by
//! Gauss–Legendre quadrature on every pair of knot spans, the boxes of the
//! surface and of its poles, within [`WORK_BUDGET`] per surface; and the
//! Gauss–Legendre rule itself.

use super::NurbsSurface;
use glam::DVec3;

/// The most work [`NurbsSurface::area`] and [`NurbsSurface::bounds`]
/// spend on one surface, in products of a basis function pair and a pole
/// (`(p + 1)(q + 1)` per evaluation): 64 million, four million evaluations
/// of a bicubic, so that no face a file brings takes more than a second or
/// so to describe.
pub const WORK_BUDGET: usize = 64_000_000;

/// `n`-point Gauss–Legendre nodes and weights on `[−1, 1]` (Newton on the
/// Legendre polynomial from Chebyshev guesses; exact for degree `2n − 1`).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let n = n.max(1);
    let mut out = vec![(0.0, 0.0); n];
    for i in 0..n.div_ceil(2) {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            if n == 1 {
                p1 = x;
                p0 = 1.0;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out[i] = (-x, w);
        out[n - 1 - i] = (x, w);
    }
    if n % 2 == 1 {
        out[n / 2].0 = 0.0;
    }
    out
}

impl NurbsSurface {
    /// Gauss–Legendre nodes per direction and span for [`Self::area`], and
    /// samples per span for [`Self::bounds`], within [`WORK_BUDGET`].
    fn rule_sizes(&self) -> (usize, usize) {
        let (su, sv) = self.spans();
        let spans = (su.len() * sv.len()).max(1);
        let budget = WORK_BUDGET / ((self.degree_u + 1) * (self.degree_v + 1));
        let mut n = (2 * self.degree_u.max(self.degree_v) + 8).min(40);
        while n > 2 && spans * n * n > budget {
            n -= 1;
        }
        let mut k = 8usize;
        while k > 1 && (k * su.len() + 1) * (k * sv.len() + 1) > budget {
            k -= 1;
        }
        (n, k)
    }

    /// The area `∫∫ |S_u × S_v| du dv`, by Gauss–Legendre on every pair of
    /// non-empty knot spans with `2 max(p, q) + 8` points (at most 40) in each
    /// direction: exact for a flat polynomial patch of that degree; for a
    /// rational patch the error falls geometrically with the point count
    /// (tested on a quarter cylinder, one span: relative error below 1e-12).
    /// A surface with so many spans (or so high a degree) that the rule would
    /// pass [`WORK_BUDGET`] gets fewer points per span (two at least).
    pub fn area(&self) -> f64 {
        let (su, sv) = self.spans();
        let g = gauss_legendre(self.rule_sizes().0);
        let mut total = 0.0;
        for a in &sv {
            let (hv, cv) = ((a[1] - a[0]) / 2.0, (a[1] + a[0]) / 2.0);
            for b in &su {
                let (hu, cu) = ((b[1] - b[0]) / 2.0, (b[1] + b[0]) / 2.0);
                let mut acc = 0.0;
                for &(xv, wv) in &g {
                    for &(xu, wu) in &g {
                        let [_, du, dv] = self.derivatives(cu + hu * xu, cv + hv * xv);
                        acc += wu * wv * du.cross(dv).length();
                    }
                }
                total += acc * hu * hv;
            }
        }
        total
    }

    /// The axis-aligned box of the **surface**, sampled at every knot and
    /// seven points inside each span in each direction (fewer within
    /// [`WORK_BUDGET`]): it can be a little smaller than the true box where
    /// the surface bulges between samples (by well under 1 % of a span's
    /// size for smooth faces); [`Self::pole_bounds`] is the box of the
    /// poles, which contains the surface but may be much larger for a
    /// rational face.
    pub fn bounds(&self) -> [DVec3; 2] {
        let (su, sv) = self.spans();
        let k = self.rule_sizes().1;
        let params = |spans: &[[f64; 2]]| -> Vec<f64> {
            let mut t = Vec::with_capacity(spans.len() * k + 1);
            for s in spans {
                for i in 0..k {
                    t.push(s[0] + (s[1] - s[0]) * i as f64 / k as f64);
                }
            }
            if let Some(s) = spans.last() {
                t.push(s[1]);
            }
            t
        };
        let (pu, pv) = (params(&su), params(&sv));
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for &v in &pv {
            for &u in &pu {
                let p = self.point(u, v);
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        [lo, hi]
    }

    /// The axis-aligned box of the poles (contains the surface).
    pub fn pole_bounds(&self) -> [DVec3; 2] {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for p in self.poles.data() {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        [lo, hi]
    }
}
