//! The initial curve `S(s_a, t)` on which every streamline starts (paper 000,
//! Eq. 1; docs/math.md §4): by default a QI curve of its own tangents, of length `L_t`,
//! parameterised by arc length `t ∈ [0, L_t]`.
//!
//! `C(u) = C₀ + L ∫₀ᵘ t(v) dv` with `u = t / L` (the QI tangent is unit, so `u`
//! is proportional to arc length). The integral is evaluated by composite
//! 5-point Gauss–Legendre quadrature on `InitialCurve::PANELS_PER_SPAN` equal
//! panels per knot span (the integrand is smooth inside a span and only
//! `C^{k−2}` across knots, so panels never straddle a knot). A table of the
//! integral at panel ends is built once; a point costs one more 5-point rule.
//! The quadrature error is tested against the closed-form circle of an order-2
//! curve and against a much finer rule ([`InitialCurve::quadrature_error_estimate`]).
//! Outside `[0, L]` the curve continues along its end tangents.

use crate::bits::{bits, same};
use crate::curve::qi::QiCurve;
use crate::error::{KernelError, Place};
use crate::plane::MirrorPlane;
use glam::DVec3;

/// 5-point Gauss–Legendre nodes on [−1, 1].
const GL_X: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683,
    0.0,
    0.538_469_310_105_683,
    0.906_179_845_938_664,
];
/// 5-point Gauss–Legendre weights.
const GL_W: [f64; 5] = [
    0.236_926_885_056_189_1,
    0.478_628_670_499_366_5,
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
];

/// An initial curve: a QI curve of given length placed at an origin.
#[derive(Debug, Clone)]
pub struct InitialCurve {
    qi: QiCurve,
    length: f64,
    origin: DVec3,
    /// Panel ends in `u` and the integral `∫₀ᵘ t` there.
    nodes_u: Vec<f64>,
    nodes_int: Vec<DVec3>,
    /// Mirror symmetry (`docs/math.md §9`): below `t₀` the curve is the
    /// reflection `R(C(2t₀ − t))` of its part above.
    mirror: Option<(f64, MirrorPlane)>,
}

impl InitialCurve {
    /// Panels per knot span.
    pub(crate) const PANELS_PER_SPAN: usize = 16;

    /// A QI initial curve of `order` through `tangents`, of arc length `length`, starting at `origin`.
    pub fn new(
        tangents: &[DVec3],
        order: usize,
        length: f64,
        origin: DVec3,
    ) -> Result<Self, KernelError> {
        if !(length.is_finite() && length > 0.0) {
            return Err(KernelError::NotPositive {
                what: "initial curve length",
                value: length,
            });
        }
        if !origin.is_finite() {
            return Err(KernelError::NonFiniteParameter {
                what: "initial curve origin",
                at: Place::Curve(0),
            });
        }
        if !crate::limits::in_range(length) {
            return Err(KernelError::TooLargeValue {
                what: "initial curve length",
                value: length,
            });
        }
        if let Some(v) = origin
            .to_array()
            .into_iter()
            .find(|v| !crate::limits::in_range(*v))
        {
            return Err(KernelError::TooLargeValue {
                what: "initial curve origin",
                value: v,
            });
        }
        let qi = QiCurve::new(tangents, order)?;
        Ok(Self::from_qi(qi, length, origin, Self::PANELS_PER_SPAN))
    }

    fn from_qi(qi: QiCurve, length: f64, origin: DVec3, per_span: usize) -> Self {
        let mut knots: Vec<f64> = qi.knots().to_vec();
        knots.dedup();
        let mut nodes_u = vec![0.0];
        let mut nodes_int = vec![DVec3::ZERO];
        let mut acc = DVec3::ZERO;
        for w in knots.windows(2) {
            for p in 0..per_span {
                let a = w[0] + (w[1] - w[0]) * p as f64 / per_span as f64;
                let b = w[0] + (w[1] - w[0]) * (p + 1) as f64 / per_span as f64;
                acc += gauss(&qi, a, b);
                nodes_u.push(b);
                nodes_int.push(acc);
            }
        }
        InitialCurve {
            qi,
            length,
            origin,
            nodes_u,
            nodes_int,
            mirror: None,
        }
    }

    /// The curve's QI tangents.
    pub fn qi(&self) -> &QiCurve {
        &self.qi
    }

    /// Its arc length `L_t`.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Its start point.
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// `∫₀ᵘ t(v) dv` for `u ∈ [0, 1]`.
    fn integral(&self, u: f64) -> DVec3 {
        let i = self
            .nodes_u
            .partition_point(|&x| x <= u)
            .saturating_sub(1)
            .min(self.nodes_u.len() - 2);
        self.nodes_int[i] + gauss(&self.qi, self.nodes_u[i], u)
    }

    /// The same curve, reflected in `plane` below `t0`: `R(C(2t₀ − t))` for
    /// `t < t₀` (the initial curve of a mirrored design, `docs/math.md §9`).
    pub(crate) fn mirrored_about(&self, t0: f64, plane: MirrorPlane) -> Self {
        InitialCurve {
            mirror: Some((t0, plane)),
            ..self.clone()
        }
    }

    /// The reflection below `t₀`, when this is a mirrored design's curve.
    pub fn mirror(&self) -> Option<(f64, MirrorPlane)> {
        self.mirror
    }

    /// The point at arc length `t` (extended along the end tangents outside
    /// `[0, L]`; reflected below `t₀` when mirrored).
    pub fn point(&self, t: f64) -> DVec3 {
        match self.mirror {
            Some((t0, plane)) if t < t0 => plane.reflect_point(self.own_point(2.0 * t0 - t)),
            _ => self.own_point(t),
        }
    }

    /// Whether `other` is the same curve bit for bit (control tangents,
    /// order, length, origin and mirror; what every point is computed
    /// from), so that points computed on one are those of the other.
    pub fn same_bits(&self, other: &InitialCurve) -> bool {
        self.qi.order() == other.qi.order()
            && same(self.qi.tangents(), other.qi.tangents())
            && self.length.to_bits() == other.length.to_bits()
            && bits(self.origin) == bits(other.origin)
            && match (self.mirror, other.mirror) {
                (None, None) => true,
                (Some((t, p)), Some((u, q))) => {
                    t.to_bits() == u.to_bits()
                        && bits(p.point) == bits(q.point)
                        && bits(p.normal) == bits(q.normal)
                }
                _ => false,
            }
    }

    fn own_point(&self, t: f64) -> DVec3 {
        let u = t / self.length;
        if u < 0.0 {
            return self.origin + self.qi.tangent(0.0) * t;
        }
        if u > 1.0 {
            return self.origin
                + self.integral(1.0) * self.length
                + self.qi.tangent(1.0) * (t - self.length);
        }
        self.origin + self.integral(u) * self.length
    }

    /// The unit tangent at arc length `t` (of the reflected part below `t₀`
    /// when mirrored: `−R(t(2t₀ − t))`).
    pub fn tangent(&self, t: f64) -> DVec3 {
        match self.mirror {
            Some((t0, plane)) if t < t0 => {
                -plane.reflect_dir(self.qi.tangent((2.0 * t0 - t) / self.length))
            }
            _ => self.qi.tangent(t / self.length),
        }
    }

    /// `m ≥ 2` points at evenly spaced arc lengths, for drawing.
    pub fn polyline(&self, m: usize) -> Vec<DVec3> {
        let m = m.max(2);
        (0..m)
            .map(|j| self.point(self.length * j as f64 / (m - 1) as f64))
            .collect()
    }

    /// Largest distance between the end point from the default rule and from a
    /// rule with 8× as many panels: an estimate of the quadrature error.
    pub fn quadrature_error_estimate(&self) -> f64 {
        let fine = Self::from_qi(
            self.qi.clone(),
            self.length,
            self.origin,
            Self::PANELS_PER_SPAN * 8,
        );
        (fine.point(self.length) - self.point(self.length)).length()
    }
}

fn gauss(qi: &QiCurve, a: f64, b: f64) -> DVec3 {
    if b <= a {
        return DVec3::ZERO;
    }
    let (m, r) = (0.5 * (a + b), 0.5 * (b - a));
    let mut s = DVec3::ZERO;
    for (x, w) in GL_X.iter().zip(GL_W) {
        s += qi.tangent(m + r * x) * w;
    }
    s * r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn initial_curve_order2_is_circle_arc() {
        // Two tangents θ apart, order 2: the tangent turns at a constant rate, so
        // the curve is a circular arc of radius L/θ (closed form).
        for theta in [0.1_f64, 1.0, 2.5] {
            let b = DVec3::new(theta.cos(), theta.sin(), 0.0);
            let len = 3.0;
            let c = InitialCurve::new(&[DVec3::X, b], 2, len, DVec3::ZERO).unwrap();
            let r = len / theta;
            for j in 0..=10 {
                let t = len * j as f64 / 10.0;
                let phi = t / r;
                let exact = DVec3::new(r * phi.sin(), r * (1.0 - phi.cos()), 0.0);
                let err = (c.point(t) - exact).length();
                assert!(err < 1e-13, "θ={theta} t={t}: error {err:e}");
            }
        }
    }

    #[test]
    fn initial_curve_quadrature_error_small() {
        let t = [
            DVec3::new(0.0, 1.0, -0.6),
            DVec3::Y,
            DVec3::new(0.0, 1.0, 0.6),
            DVec3::new(1.0, 0.2, 0.0),
        ];
        for k in 2..=4 {
            let c = InitialCurve::new(&t, k, 2.0, DVec3::ZERO).unwrap();
            let e = c.quadrature_error_estimate();
            assert!(e < 1e-13, "order {k}: quadrature error estimate {e:e}");
        }
    }

    /// `same_bits` tells apart curves whose points differ: a control
    /// tangent turned by 1e-9, another order, the length or the origin one
    /// ulp off, a mirror added; the same inputs give the same curve and
    /// points.
    #[test]
    fn same_bits_is_what_the_points_are_computed_from() {
        let t = [
            DVec3::new(0.0, 1.0, -0.6),
            DVec3::Y,
            DVec3::new(0.0, 1.0, 0.6),
        ];
        let make = |t: &[DVec3], k, len, o| InitialCurve::new(t, k, len, o).unwrap();
        let c = make(&t, 3, 2.0, DVec3::ZERO);
        assert!(c.same_bits(&make(&t, 3, 2.0, DVec3::ZERO)));
        assert_eq!(
            c.point(0.7).to_array().map(f64::to_bits),
            make(&t, 3, 2.0, DVec3::ZERO)
                .point(0.7)
                .to_array()
                .map(f64::to_bits)
        );
        let ulp = |x: f64| f64::from_bits(x.to_bits() + 1);
        let mut t2 = t;
        t2[1].x = 1e-9;
        assert!(!c.same_bits(&make(&t2, 3, 2.0, DVec3::ZERO)));
        assert!(!c.same_bits(&make(&t, 2, 2.0, DVec3::ZERO)));
        assert!(!c.same_bits(&make(&t, 3, ulp(2.0), DVec3::ZERO)));
        assert!(!c.same_bits(&make(&t, 3, 2.0, DVec3::new(0.0, ulp(0.0), 0.0))));
        let plane = MirrorPlane {
            point: DVec3::ZERO,
            normal: DVec3::Y,
        };
        assert!(!c.same_bits(&c.mirrored_about(0.5, plane)));
        assert!(
            c.mirrored_about(0.5, plane)
                .same_bits(&c.mirrored_about(0.5, plane))
        );
    }
}
