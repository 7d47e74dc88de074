//! Fine tuning a closed Chaikin curve (paper 003, §4.1, Eqs. 9–12).
//!
//! Chaikin's rule (Eqs. 9–10) refines a closed polygon `P₀ … P_{n−1}` towards
//! the uniform periodic quadratic B-spline; its segment `i` (`u ∈ [0, 1]`)
//! is `p(u) = B₀(u) Pᵢ + B₁(u) P_{i+1} + B₂(u) P_{i+2}` (indices mod n), from
//! `(Pᵢ + P_{i+1})/2` to `(P_{i+1} + P_{i+2})/2`, with the linear derivative
//! `p' = (1 − u) Dᵢ + u D_{i+1}`, `Dᵢ = P_{i+1} − Pᵢ`.
//!
//! The scalar function is linear and periodic, with one control value `aᵢ`
//! at each joint between segments (the paper's *virtual vertices*): on segment
//! `i`, `α = (1 − u) aᵢ + u a_{i+1}`. The product `α p'` is quadratic, so the
//! fine-tuned curve `q = q₀ + ∫ α p'` is a C¹ piecewise cubic: a cubic
//! B-spline with double knots. Its Bézier points on segment `i` are
//! `Q₀`, `Q₁ = Q₀ + aᵢDᵢ/3`, `Q₂ = Q₁ + (aᵢD_{i+1} + a_{i+1}Dᵢ)/6`,
//! `Q₃ = Q₂ + a_{i+1}D_{i+1}/3`, and its B-spline control polygon is the
//! inner points `Q₁, Q₂` of every segment. With every `aᵢ = 1` these are
//! `⅙Pᵢ + ⅚P_{i+1}` and `⅚P_{i+1} + ⅙P_{i+2}`: Eqs. 11–12, the degree
//! elevation of the quadratic curve. The curve starts at `(P₀ + P₁)/2`.
//!
//! Closedness: the curve closes when `Σᵢ aᵢ Wᵢ = 0`, `Wᵢ = (D_{i−1} + 4Dᵢ + D_{i+1})/6`;
//! [`Constraint::KeepClosed`] meets it with the least-squares change of the `aᵢ`.

use super::constraint::{Constraint, nearest_meeting};
use crate::error::KernelError;
use glam::DVec3;

/// A closed C¹ cubic (double knots) made of one Bézier segment per Chaikin segment.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedCubic {
    /// Bézier points `Q₀ … Q₃` of each segment.
    pub segments: Vec<[DVec3; 4]>,
    /// The scalar values used (after the constraint).
    pub alpha: Vec<f64>,
}

impl ClosedCubic {
    /// The B-spline control polygon: `Q₁, Q₂` of every segment (`2n` points; Eqs. 11–12).
    pub fn control_polygon(&self) -> Vec<DVec3> {
        self.segments.iter().flat_map(|q| [q[1], q[2]]).collect()
    }

    /// The point at `u ∈ [0, n]` (segment `⌊u⌋`, de Casteljau).
    pub fn eval(&self, u: f64) -> DVec3 {
        let n = self.segments.len();
        let u = u.clamp(0.0, n as f64);
        let i = (u.floor() as usize).min(n - 1);
        let t = u - i as f64;
        let q = &self.segments[i];
        let l1 = [q[0].lerp(q[1], t), q[1].lerp(q[2], t), q[2].lerp(q[3], t)];
        let l2 = [l1[0].lerp(l1[1], t), l1[1].lerp(l1[2], t)];
        l2[0].lerp(l2[1], t)
    }

    /// How far the end is from the start (zero for a closed curve).
    pub fn gap(&self) -> f64 {
        let n = self.segments.len();
        (self.segments[n - 1][3] - self.segments[0][0]).length()
    }
}

/// The closed Chaikin (quadratic B-spline) curve of `points` fine-tuned by
/// the linear periodic function with values `alpha` (one per joint, joint
/// `i` at the start of segment `i`). `points.len() ≥ 3`, finite; `alpha`
/// finite, same count.
pub fn fine_tune_closed(
    points: &[DVec3],
    alpha: &[f64],
    constraint: Constraint,
) -> Result<ClosedCubic, KernelError> {
    let n = points.len();
    if n < 3 {
        return Err(KernelError::TooFewTangents {
            what: "a closed Chaikin curve (points)",
            got: n,
            need: 3,
        });
    }
    if alpha.len() != n {
        return Err(KernelError::LengthMismatch {
            what: "fine-tuning values (one per joint)",
            got: alpha.len(),
            expected: n,
        });
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(KernelError::NonFiniteParameter {
            what: "control point",
            at: crate::error::Place::Curve(i),
        });
    }
    if let Some(i) = alpha.iter().position(|a| !a.is_finite()) {
        return Err(KernelError::NonFiniteParameter {
            what: "fine-tuning value",
            at: crate::error::Place::Curve(i),
        });
    }
    let d: Vec<DVec3> = (0..n).map(|i| points[(i + 1) % n] - points[i]).collect();
    let mut a = alpha.to_vec();
    if constraint != Constraint::Free {
        // Σ aᵢ Wᵢ = 0 (both KeepClosed and KeepEnds mean "the end meets the start" here)
        let w: Vec<DVec3> = (0..n)
            .map(|i| (d[(i + n - 1) % n] + d[i] * 4.0 + d[(i + 1) % n]) / 6.0)
            .collect();
        let rows: Vec<Vec<f64>> = (0..3).map(|ax| w.iter().map(|v| v[ax]).collect()).collect();
        a = nearest_meeting(&a, &rows, &vec![0.0; n]);
    }
    let mut q0 = (points[0] + points[1]) * 0.5;
    let mut segments = Vec::with_capacity(n);
    for i in 0..n {
        let j = (i + 1) % n;
        let q1 = q0 + d[i] * (a[i] / 3.0);
        let q2 = q1 + (d[j] * a[i] + d[i] * a[j]) / 6.0;
        let q3 = q2 + d[j] * (a[j] / 3.0);
        segments.push([q0, q1, q2, q3]);
        q0 = q3;
    }
    Ok(ClosedCubic { segments, alpha: a })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygon() -> Vec<DVec3> {
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, -0.3, 0.1),
            DVec3::new(3.0, 1.5, 0.0),
            DVec3::new(1.2, 2.6, -0.2),
            DVec3::new(-0.8, 1.4, 0.3),
        ]
    }

    /// The closed quadratic B-spline's derivative on segment `i` (from its definition).
    fn deriv(p: &[DVec3], u: f64) -> DVec3 {
        let n = p.len();
        let i = (u.floor() as usize).min(n - 1);
        let t = u - i as f64;
        let (a, b, c) = (p[i], p[(i + 1) % n], p[(i + 2) % n]);
        (b - a) * (1.0 - t) + (c - b) * t
    }

    #[test]
    fn chaikin_identity_is_eqs_11_12() {
        let p = polygon();
        let c = fine_tune_closed(&p, &[1.0; 5], Constraint::Free).unwrap();
        let q = c.control_polygon();
        let n = p.len();
        for i in 0..n {
            // leg (P_{i+1}, P_{i+2}) of segment i: Q₂ᵢ = ⅚P_{i+1} + ⅙P_{i+2} (Eq. 11)
            let e11 = p[(i + 1) % n] * (5.0 / 6.0) + p[(i + 2) % n] * (1.0 / 6.0);
            let e12 = p[(i + 1) % n] * (1.0 / 6.0) + p[(i + 2) % n] * (5.0 / 6.0);
            assert!((q[2 * i + 1] - e11).length() < 1e-14, "Eq. 11 at leg {i}");
            assert!(
                (q[(2 * i + 2) % (2 * n)] - e12).length() < 1e-14,
                "Eq. 12 at leg {i}"
            );
        }
        assert!(
            c.gap() < 1e-14,
            "identity keeps the curve closed: gap {}",
            c.gap()
        );
    }

    #[test]
    fn chaikin_product_matches_dense_integration() {
        let p = polygon();
        let a = [1.0, 1.8, 0.6, 1.2, 0.9];
        let c = fine_tune_closed(&p, &a, Constraint::Free).unwrap();
        let n = p.len();
        let alpha = |u: f64| {
            let i = (u.floor() as usize).min(n - 1);
            let t = u - i as f64;
            a[i] * (1.0 - t) + a[(i + 1) % n] * t
        };
        // composite Simpson of α p' from 0, 200 panels per segment
        let mut x = (p[0] + p[1]) * 0.5;
        let h = 1.0 / 200.0;
        for k in 0..200 * n {
            let u0 = k as f64 * h;
            let f = |u: f64| deriv(&p, u.min(n as f64 - 1e-12)) * alpha(u.min(n as f64 - 1e-12));
            x += (f(u0) + f(u0 + 0.5 * h) * 4.0 + f(u0 + h)) * (h / 6.0);
            let u1 = u0 + h;
            if (k + 1) % 50 == 0 {
                assert!(
                    (c.eval(u1) - x).length() < 1e-12,
                    "u={u1}: {:?} vs {x:?}",
                    c.eval(u1)
                );
            }
        }
        assert!(c.gap() > 1e-3, "free fine tuning opens the curve");
        let closed = fine_tune_closed(&p, &a, Constraint::KeepClosed).unwrap();
        assert!(closed.gap() < 1e-10, "gap {}", closed.gap());
    }
}
