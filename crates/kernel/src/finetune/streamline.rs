//! Fine tuning one streamline (docs/math.md §6): `p(s) = p(σ) + ∫_σ^s α t ds`.
//!
//! The streamline of Eq. 65 has the constant direction `t_k` on the segment
//! from point `k` to point `k+1`, which spans the arc lengths `[a_k, a_{k+1}]`
//! (`a₀ = s₀`, `a_k = (s_{k−1} + s_k)/2`, `a_{n+1} = s_n`). So the fine-tuned
//! streamline is again a polyline through `n+2` points,
//! `P_{k+1} = P_k + t_k (A(a_{k+1}) − A(a_k))`, with `A = ∫ α` exact
//! (`BSpline::antiderivative`); between its points `p'(s) = α(s) t_k`, exactly
//! `α` times the original derivative. `α` is a function of
//! `u = (s − s₀)/(s_n − s₀)`; beyond `[s₀, s_n]` (an anchor outside, as
//! approximating schemes give) it keeps its end value.

use super::constraint::{Constraint, nearest_meeting};
use crate::finetune::bspline::BSpline;
use crate::streamline::integrate::point_arclength;
use glam::DVec3;

/// What one fine-tuned streamline used.
#[derive(Debug, Clone, PartialEq)]
pub struct FineTuned {
    /// The function actually applied (the designer's, changed by the constraint).
    pub alpha: BSpline,
}

/// The arc-length map of one streamline: `u(s)` and the integral of `α`.
struct Domain {
    s0: f64,
    len: f64,
}

impl Domain {
    fn new(s: &[f64]) -> Self {
        let s0 = s[0];
        Domain {
            s0,
            len: s[s.len() - 1] - s0,
        }
    }

    fn u(&self, x: f64) -> f64 {
        ((x - self.s0) / self.len).clamp(0.0, 1.0)
    }

    /// `∫_{s₀}^{x} f` for `f` given by its antiderivative in `u` (`anti`) and
    /// its end values (`f0`, `f1`), continued beyond the ends.
    fn integral(&self, anti: impl Fn(f64) -> f64, f0: f64, f1: f64, x: f64) -> f64 {
        let end = self.s0 + self.len;
        if x < self.s0 {
            f0 * (x - self.s0)
        } else if x > end {
            anti(1.0) * self.len + f1 * (x - end)
        } else {
            anti(self.u(x)) * self.len
        }
    }
}

/// Points `P_k` from the integral values `big[k] = ∫_{s₀}^{a_k}` (`P₀ = 0`),
/// and the point at `σ` (integral value `at_sigma`).
fn polyline(
    tangents: &[DVec3],
    s: &[f64],
    big: &[f64],
    sigma: f64,
    at_sigma: f64,
    out: &mut Vec<DVec3>,
) -> DVec3 {
    out.clear();
    let n = tangents.len() - 1;
    let mut p = DVec3::ZERO;
    out.push(p);
    for k in 0..=n {
        p += tangents[k] * (big[k + 1] - big[k]);
        out.push(p);
    }
    let k = crate::streamline::integrate::segment_at(s, sigma);
    let (base, dir) = if k > n {
        (n + 1, tangents[n])
    } else {
        (k, tangents[k])
    };
    out[base] + dir * (at_sigma - big[base])
}

/// Integrates and places one fine-tuned streamline so that its point at arc
/// length `sigma` is `origin`, writing `n+2` points into `out`; `alpha` is
/// the designer's function, changed as little as possible (least squares in
/// its control values) to meet `constraint`. Inputs as for
/// [`crate::streamline::integrate::place_into`] (unit tangents, `s` increasing).
pub fn fine_tune_into(
    tangents: &[DVec3],
    s: &[f64],
    sigma: f64,
    origin: DVec3,
    alpha: &BSpline,
    constraint: Constraint,
    out: &mut Vec<DVec3>,
) -> FineTuned {
    let mut alpha = alpha.clone();
    if constraint != Constraint::Free {
        let rows = constraint_rows(tangents, s, sigma, &alpha, constraint);
        // the identity (all ones) gives the original ends
        let ones = vec![1.0; alpha.values().len()];
        let c = nearest_meeting(alpha.values(), &rows, &ones);
        alpha.set_values(&c);
    }
    integrate_tuned(tangents, s, sigma, origin, &alpha, out);
    FineTuned { alpha }
}

/// Integrates one streamline with the function `alpha` as it is (no
/// constraint), placed so that its point at `sigma` is `origin` (Eq. 65 with
/// `p' = α t`, docs/math.md §6).
pub(crate) fn integrate_tuned(
    tangents: &[DVec3],
    s: &[f64],
    sigma: f64,
    origin: DVec3,
    alpha: &BSpline,
    out: &mut Vec<DVec3>,
) {
    let n = tangents.len() - 1;
    let dom = Domain::new(s);
    let anti = alpha.antiderivative();
    let (f0, f1) = (alpha.eval(0.0), alpha.eval(1.0));
    let big: Vec<f64> = (0..n + 2)
        .map(|k| dom.integral(|u| anti.eval(u), f0, f1, point_arclength(s, k)))
        .collect();
    let at_sigma = dom.integral(|u| anti.eval(u), f0, f1, sigma);
    let anchor = polyline(tangents, s, &big, sigma, at_sigma, out);
    let shift = origin - anchor;
    for p in out.iter_mut() {
        *p += shift;
    }
}

/// The point of a fine-tuned polyline (`points`, from [`fine_tune_into`]) at
/// the original arc length `x`, found by its fraction of the segment that
/// holds it (exact for the identity; the editor puts arrows there).
pub fn point_by_fraction(points: &[DVec3], s: &[f64], x: f64) -> DVec3 {
    let n = s.len() - 1;
    let k = crate::streamline::integrate::segment_at(s, x).min(n);
    let (a0, a1) = (point_arclength(s, k), point_arclength(s, k + 1));
    let f = if a1 > a0 {
        ((x - a0) / (a1 - a0)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    points[k].lerp(points[k + 1], f)
}

/// The rows of `A` in `A c = A 1` for one streamline: the far end
/// `p(s_n) − p(σ)` and near end `p(s₀) − p(σ)` (keep ends, 6 rows) or the
/// chord `p(s_n) − p(s₀)` (keep closed, 3 rows), each linear in the values.
pub(crate) fn constraint_rows(
    tangents: &[DVec3],
    s: &[f64],
    sigma: f64,
    alpha: &BSpline,
    constraint: Constraint,
) -> Vec<Vec<f64>> {
    let n = tangents.len() - 1;
    let m = alpha.values().len();
    let dom = Domain::new(s);
    // integrals of each basis function at every node and at σ
    let mut at_nodes = vec![vec![0.0; m]; n + 2];
    let mut buf = vec![0.0; m];
    // on clamped knots only N₀ is nonzero at u = 0 and only N_{m−1} at u = 1
    let end_values: Vec<(f64, f64)> = (0..m)
        .map(|i| (f64::from(i == 0), f64::from(i == m - 1)))
        .collect();
    let mut integral_all = |x: f64, out: &mut [f64]| {
        alpha.basis_integrals(dom.u(x), &mut buf);
        let end = dom.s0 + dom.len;
        for i in 0..m {
            out[i] = if x < dom.s0 {
                end_values[i].0 * (x - dom.s0)
            } else if x > end {
                buf[i] * dom.len + end_values[i].1 * (x - end)
            } else {
                buf[i] * dom.len
            };
        }
    };
    for (k, row) in at_nodes.iter_mut().enumerate() {
        integral_all(point_arclength(s, k), row);
    }
    let mut at_sigma = vec![0.0; m];
    integral_all(sigma, &mut at_sigma);
    let mut far = vec![DVec3::ZERO; m];
    let mut near = vec![DVec3::ZERO; m];
    let mut pts = Vec::with_capacity(n + 2);
    for i in 0..m {
        let big: Vec<f64> = at_nodes.iter().map(|r| r[i]).collect();
        let anchor = polyline(tangents, s, &big, sigma, at_sigma[i], &mut pts);
        far[i] = pts[n + 1] - anchor;
        near[i] = pts[0] - anchor;
    }
    let comp = |v: &[DVec3], axis: usize| v.iter().map(|p| p[axis]).collect::<Vec<f64>>();
    match constraint {
        Constraint::Free => Vec::new(),
        Constraint::KeepEnds => (0..3)
            .map(|a| comp(&far, a))
            .chain((0..3).map(|a| comp(&near, a)))
            .collect(),
        Constraint::KeepClosed => {
            let chord: Vec<DVec3> = far.iter().zip(&near).map(|(f, n)| *f - *n).collect();
            (0..3).map(|a| comp(&chord, a)).collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::streamline::integrate::place_into;

    fn arc(n: usize) -> (Vec<DVec3>, Vec<f64>) {
        let t = (0..n)
            .map(|i| {
                let a = i as f64 * 0.4;
                DVec3::new(a.cos(), a.sin(), 0.2 * (i as f64 * 0.7).sin()).normalize()
            })
            .collect();
        let s = (0..n)
            .map(|i| i as f64 * 0.5 + 0.05 * (i as f64).sin())
            .collect();
        (t, s)
    }

    #[test]
    fn identity_changes_nothing() {
        let (t, s) = arc(9);
        let origin = DVec3::new(0.3, -1.0, 2.0);
        let mut a = Vec::new();
        let mut b = Vec::new();
        for sigma in [
            s[0],
            s[3],
            0.5 * (s[4] + s[5]),
            s[8],
            s[0] - 0.3,
            s[8] + 0.4,
        ] {
            place_into(&t, &s, sigma, origin, &mut a);
            for c in [
                Constraint::Free,
                Constraint::KeepEnds,
                Constraint::KeepClosed,
            ] {
                fine_tune_into(&t, &s, sigma, origin, &BSpline::identity(2), c, &mut b);
                for (p, q) in a.iter().zip(&b) {
                    assert!(
                        (*p - *q).length() < 1e-12,
                        "σ={sigma} {c:?}: {p:?} vs {q:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn keep_ends_holds() {
        let (t, s) = arc(12);
        let origin = DVec3::ZERO;
        let mut a = Vec::new();
        let mut b = Vec::new();
        let f = BSpline::uniform(2, vec![1.0, 1.6, 0.5, 1.3, 0.9, 1.2]).unwrap();
        for sigma in [s[0], s[5], s[11]] {
            place_into(&t, &s, sigma, origin, &mut a);
            let used = fine_tune_into(&t, &s, sigma, origin, &f, Constraint::KeepEnds, &mut b);
            let n = b.len() - 1;
            assert!((b[0] - a[0]).length() < 1e-10, "near end, σ={sigma}");
            assert!((b[n] - a[n]).length() < 1e-10, "far end, σ={sigma}");
            assert!(used.alpha != f, "the constraint changed the values");
            fine_tune_into(&t, &s, sigma, origin, &f, Constraint::KeepClosed, &mut b);
            assert!(
                ((b[n] - b[0]) - (a[n] - a[0])).length() < 1e-10,
                "chord, σ={sigma}"
            );
            fine_tune_into(&t, &s, sigma, origin, &f, Constraint::Free, &mut b);
            let moved = (b[n] - a[n]).length() + (b[0] - a[0]).length();
            assert!(moved > 1e-3, "free fine tuning moves an end, σ={sigma}");
        }
    }
}
