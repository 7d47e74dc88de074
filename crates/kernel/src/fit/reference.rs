//! A reference surface and the arc-length tables the fit reads from it
//! (`docs/math.md §12`).
//!
//! The fit works in the frame of the streamlines: its `u` is the reference's
//! parameter along them and its `v` the one across (the reference's own `u`
//! and `v`, or exchanged when they run along `v`). In that frame:
//!
//! * a **row** is the iso-curve `v = const`; its arc length
//!   `ℓ(v) = ∫ |∂R/∂u| du` is summed by 8-point Gauss–Legendre on panels
//!   that never straddle a knot (eq. 12.1), and a fraction `f` of it is
//!   found again by inverting the cubic Hermite interpolant of the
//!   cumulative length through the panel ends (a first guess) and Newton on
//!   the quadrature itself (to rounding);
//! * the **anchor curve** is the curve through the point at the fraction
//!   `φ_a` of every row (the iso-curve `u = u_min` when `φ_a = 0`),
//!   parametrised by its own arc length `t` the same way.

use super::error::ReferenceFitError;
use crate::nurbs::rational::{NurbsSurface, gauss_legendre};
use glam::DVec3;

/// A surface a design can be fitted to: a parameter rectangle, points and
/// first derivatives. Evaluation outside the domain may clamp.
pub trait ReferenceSurface: Sync {
    /// `([u0, u1], [v0, v1])`.
    fn domain(&self) -> ([f64; 2], [f64; 2]);
    /// `R(u, v)`.
    fn point(&self, u: f64, v: f64) -> DVec3;
    /// `R`, `∂R/∂u`, `∂R/∂v`.
    fn derivatives(&self, u: f64, v: f64) -> [DVec3; 3];
    /// Parameters inside the `u` range where the surface may be less smooth
    /// (the knots); quadrature panels never straddle them. None by default.
    fn breaks_u(&self) -> Vec<f64> {
        Vec::new()
    }
    /// As [`Self::breaks_u`], in `v`.
    fn breaks_v(&self) -> Vec<f64> {
        Vec::new()
    }
}

fn inner_knots(knots: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    let mut k: Vec<f64> = knots
        .iter()
        .copied()
        .filter(|&x| x > lo && x < hi)
        .collect();
    k.dedup();
    k
}

impl ReferenceSurface for NurbsSurface {
    fn domain(&self) -> ([f64; 2], [f64; 2]) {
        NurbsSurface::domain(self)
    }
    fn point(&self, u: f64, v: f64) -> DVec3 {
        NurbsSurface::point(self, u, v)
    }
    fn derivatives(&self, u: f64, v: f64) -> [DVec3; 3] {
        NurbsSurface::derivatives(self, u, v)
    }
    fn breaks_u(&self) -> Vec<f64> {
        let (du, _) = NurbsSurface::domain(self);
        inner_knots(self.knots_u(), du[0], du[1])
    }
    fn breaks_v(&self) -> Vec<f64> {
        let (_, dv) = NurbsSurface::domain(self);
        inner_knots(self.knots_v(), dv[0], dv[1])
    }
}

/// A reference with `u` and `v` exchanged (streamlines along `v`).
pub(crate) struct Swapped<'a>(pub &'a dyn ReferenceSurface);

impl ReferenceSurface for Swapped<'_> {
    fn domain(&self) -> ([f64; 2], [f64; 2]) {
        let (u, v) = self.0.domain();
        (v, u)
    }
    fn point(&self, u: f64, v: f64) -> DVec3 {
        self.0.point(v, u)
    }
    fn derivatives(&self, u: f64, v: f64) -> [DVec3; 3] {
        let [p, a, b] = self.0.derivatives(v, u);
        [p, b, a]
    }
    fn breaks_u(&self) -> Vec<f64> {
        self.0.breaks_v()
    }
    fn breaks_v(&self) -> Vec<f64> {
        self.0.breaks_u()
    }
}

/// Quadrature panels over `[a, b]`: the breaks inside split it into spans,
/// each cut into equal panels so that there are at least `min_total`.
pub(crate) fn panels(range: [f64; 2], breaks: &[f64], min_total: usize) -> Vec<f64> {
    let mut ends = vec![range[0]];
    let mut b: Vec<f64> = breaks
        .iter()
        .copied()
        .filter(|x| x.is_finite() && *x > range[0] && *x < range[1])
        .collect();
    b.sort_by(f64::total_cmp);
    b.dedup();
    ends.extend(b);
    ends.push(range[1]);
    let spans = ends.len() - 1;
    let per = min_total.div_ceil(spans).max(1);
    let mut out = Vec::with_capacity(spans * per + 1);
    for w in ends.windows(2) {
        for i in 0..per {
            out.push(w[0] + (w[1] - w[0]) * i as f64 / per as f64);
        }
    }
    out.push(range[1]);
    out
}

/// The fit's frame: the reference with `u` along the streamlines, its
/// panels, quadrature and scale.
pub(crate) struct Frame<'a> {
    pub r: &'a dyn ReferenceSurface,
    pub du: [f64; 2],
    pub dv: [f64; 2],
    pub panels_u: Vec<f64>,
    pub panels_v: Vec<f64>,
    pub gl: Vec<(f64, f64)>,
    /// Whether the frame's `u` is the reference's `v`.
    pub swapped: bool,
    /// The reference's sampled bounding-box diagonal.
    pub diag: f64,
    /// Below this speed `|∂R/∂u|` a point is a pole.
    pub min_speed: f64,
}

/// Gauss–Legendre points per panel.
pub(crate) const GL_POINTS: usize = 8;

/// The fewest quadrature panels over a row or the anchor curve.
pub(crate) const MIN_PANELS: usize = 16;

impl<'a> Frame<'a> {
    pub fn new(r: &'a dyn ReferenceSurface, swapped: bool) -> Result<Self, ReferenceFitError> {
        let (du, dv) = r.domain();
        for (dir, d) in [('u', du), ('v', dv)] {
            if !(d[0].is_finite() && d[1].is_finite() && d[1] > d[0]) {
                let direction = match (dir, swapped) {
                    ('u', false) | ('v', true) => 'u',
                    _ => 'v',
                };
                return Err(ReferenceFitError::EmptyDomain { direction });
            }
        }
        let panels_u = panels(du, &r.breaks_u(), MIN_PANELS);
        let panels_v = panels(dv, &r.breaks_v(), MIN_PANELS);
        // the bounding box of a sample at the panel ends and midpoints
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        let mids = |p: &[f64]| -> Vec<f64> {
            let mut out = Vec::with_capacity(p.len() * 2);
            for w in p.windows(2) {
                out.push(w[0]);
                out.push(0.5 * (w[0] + w[1]));
            }
            out.extend(p.last());
            out
        };
        for &v in &mids(&panels_v) {
            for &u in &mids(&panels_u) {
                let p = r.point(u, v);
                if !p.is_finite() {
                    return Err(ReferenceFitError::NonFinite { what: "point" });
                }
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        let diag = (hi - lo).length();
        if !diag.is_finite() {
            return Err(ReferenceFitError::NonFinite { what: "point" });
        }
        let min_speed = 1e-9 * diag / (du[1] - du[0]);
        Ok(Frame {
            r,
            du,
            dv,
            panels_u,
            panels_v,
            gl: gauss_legendre(GL_POINTS),
            swapped,
            diag,
            min_speed,
        })
    }

    /// The streamlines' direction, named in the reference's parameters.
    pub fn along(&self) -> char {
        if self.swapped { 'v' } else { 'u' }
    }

    /// A pole at the frame's `(u, v)`, named in the reference's parameters.
    pub fn pole(&self, u: f64, v: f64) -> ReferenceFitError {
        let (ru, rv) = if self.swapped { (v, u) } else { (u, v) };
        ReferenceFitError::Pole {
            u: ru,
            v: rv,
            along: self.along(),
        }
    }

    /// The name of the frame's iso-curve `v = value` in the reference's terms.
    pub fn row_name(&self, v: f64) -> String {
        let across = if self.swapped { 'u' } else { 'v' };
        format!("{across} = {v}")
    }

    /// The name of the frame's iso-curve `u = value`.
    pub fn column_name(&self, u: f64) -> String {
        format!("{} = {u}", self.along())
    }

    /// The unit tangent `∂R/∂u / |∂R/∂u|` at `(u, v)`.
    pub fn tangent(&self, u: f64, v: f64) -> Result<DVec3, ReferenceFitError> {
        let d = self.r.derivatives(u, v)[1];
        let l = d.length();
        if l.is_nan() || l < self.min_speed || !l.is_finite() {
            return Err(self.pole(u, v));
        }
        Ok(d / l)
    }

    /// Whether the reference closes on itself along `u`: its edges
    /// `u = u0` and `u = u1` coincide (within `1e-7` of the diagonal) at
    /// every panel end in `v`.
    pub fn closed_along(&self) -> bool {
        let tol = 1e-7 * self.diag;
        self.panels_v.iter().all(|&v| {
            self.r
                .point(self.du[0], v)
                .distance(self.r.point(self.du[1], v))
                <= tol
        })
    }
}

/// A monotone table `x ↦ s(x)` with slopes, inverted by its cubic Hermite
/// interpolant.
#[derive(Debug, Clone)]
pub(crate) struct Hermite {
    pub x: Vec<f64>,
    pub s: Vec<f64>,
    pub d: Vec<f64>,
}

impl Hermite {
    /// The total `s`.
    pub fn total(&self) -> f64 {
        self.s.last().copied().unwrap_or(0.0)
    }

    /// The panel holding `target` and the Hermite estimate of its `x`.
    pub fn inverse(&self, target: f64) -> (usize, f64) {
        let n = self.x.len();
        if n < 2 {
            return (0, self.x.first().copied().unwrap_or(0.0));
        }
        let target = if target.is_nan() { 0.0 } else { target };
        let i = self
            .s
            .partition_point(|&s| s <= target)
            .saturating_sub(1)
            .min(n - 2);
        let (xa, xb) = (self.x[i], self.x[i + 1]);
        let (sa, sb) = (self.s[i], self.s[i + 1]);
        let h = xb - xa;
        let (ma, mb) = (self.d[i] * h, self.d[i + 1] * h);
        if target <= sa {
            return (i, xa);
        }
        if target >= sb {
            return (i, xb);
        }
        let mut x = if sb > sa {
            (target - sa) / (sb - sa)
        } else {
            0.5
        };
        for _ in 0..8 {
            let (x2, x3) = (x * x, x * x * x);
            let val = (2.0 * x3 - 3.0 * x2 + 1.0) * sa
                + (x3 - 2.0 * x2 + x) * ma
                + (-2.0 * x3 + 3.0 * x2) * sb
                + (x3 - x2) * mb;
            let der = (6.0 * x2 - 6.0 * x) * sa
                + (3.0 * x2 - 4.0 * x + 1.0) * ma
                + (-6.0 * x2 + 6.0 * x) * sb
                + (3.0 * x2 - 2.0 * x) * mb;
            if der.is_nan() || der <= 0.0 {
                break;
            }
            let step = (val - target) / der;
            x = (x - step).clamp(0.0, 1.0);
            if step.abs() < 1e-15 {
                break;
            }
        }
        (i, xa + x * h)
    }
}

/// One row `v = const`: cumulative arc length at the panel ends.
#[derive(Debug, Clone)]
pub(crate) struct RowTable {
    pub v: f64,
    pub table: Hermite,
}

impl RowTable {
    /// The table of row `v` (eq. 12.1); a pole (speed below the frame's
    /// minimum) at a panel end or quadrature point is an error.
    pub fn new(f: &Frame<'_>, v: f64) -> Result<Self, ReferenceFitError> {
        let pu = &f.panels_u;
        let mut s = Vec::with_capacity(pu.len());
        let mut d = Vec::with_capacity(pu.len());
        let mut acc = 0.0;
        for (i, &u) in pu.iter().enumerate() {
            let sp = f.r.derivatives(u, v)[1].length();
            if sp.is_nan() || sp < f.min_speed {
                return Err(f.pole(u, v));
            }
            if i > 0 {
                let (a, b) = (pu[i - 1], u);
                let (m, h) = (0.5 * (a + b), 0.5 * (b - a));
                let mut part = 0.0;
                for &(x, w) in &f.gl {
                    let uu = m + h * x;
                    let q = f.r.derivatives(uu, v)[1].length();
                    if q.is_nan() || q < f.min_speed {
                        return Err(f.pole(uu, v));
                    }
                    part += w * q;
                }
                acc += part * h;
            }
            s.push(acc);
            d.push(sp);
        }
        if !acc.is_finite() {
            return Err(ReferenceFitError::NonFinite { what: "derivative" });
        }
        Ok(RowTable {
            v,
            table: Hermite {
                x: pu.clone(),
                s,
                d,
            },
        })
    }

    /// The row's arc length `ℓ(v)`.
    pub fn length(&self) -> f64 {
        self.table.total()
    }

    /// The `u` at the fraction `frac` of the row's length, from the Hermite
    /// table alone (relative error about `1e-8` of a panel; a first guess).
    pub fn u_at(&self, frac: f64) -> f64 {
        self.table.inverse(frac.clamp(0.0, 1.0) * self.length()).1
    }

    /// The `u` at the fraction `frac`, to rounding: Newton on the
    /// quadrature of the panel from the Hermite guess.
    pub fn u_exact(&self, f: &Frame<'_>, frac: f64) -> f64 {
        let target = frac.clamp(0.0, 1.0) * self.length();
        let (i, mut u) = self.table.inverse(target);
        let (ua, sa) = (self.table.x[i], self.table.s[i]);
        let ub = self.table.x[(i + 1).min(self.table.x.len() - 1)];
        for _ in 0..3 {
            let (m, h) = (0.5 * (ua + u), 0.5 * (u - ua));
            let mut part = 0.0;
            for &(x, w) in &f.gl {
                part += w * f.r.derivatives(m + h * x, self.v)[1].length();
            }
            let val = sa + part * h - target;
            let sp = f.r.derivatives(u, self.v)[1].length();
            if sp.is_nan() || sp <= 0.0 || !val.is_finite() {
                break;
            }
            let step = val / sp;
            u = (u - step).clamp(ua, ub);
            if step.abs() <= 1e-15 * (ub - ua).abs().max(f64::MIN_POSITIVE) {
                break;
            }
        }
        u
    }
}

/// The anchor curve `C(v)`: the point at the fraction `φ_a` of each row,
/// with its cumulative arc length `t(v)` at the panel ends in `v`.
#[derive(Debug, Clone)]
pub(crate) struct AnchorCurve {
    pub fraction: f64,
    pub table: Hermite,
}

impl AnchorCurve {
    /// `C(v)`.
    pub fn point(f: &Frame<'_>, fraction: f64, v: f64) -> Result<DVec3, ReferenceFitError> {
        if fraction <= 0.0 {
            return Ok(f.r.point(f.du[0], v));
        }
        let row = RowTable::new(f, v)?;
        Ok(f.r.point(row.u_exact(f, fraction), v))
    }

    /// `dC/dv` (exact on the boundary iso-curve; central differences of
    /// step `1e-6` of the range otherwise).
    pub fn derivative(f: &Frame<'_>, fraction: f64, v: f64) -> Result<DVec3, ReferenceFitError> {
        if fraction <= 0.0 {
            return Ok(f.r.derivatives(f.du[0], v)[2]);
        }
        let h = 1e-6 * (f.dv[1] - f.dv[0]);
        let a = (v - h).max(f.dv[0]);
        let b = (v + h).min(f.dv[1]);
        Ok((Self::point(f, fraction, b)? - Self::point(f, fraction, a)?) / (b - a))
    }

    /// The curve's table (eq. 12.2), on the rows' panels cut in four (its
    /// ends are where the initial curve is checked).
    pub fn new(f: &Frame<'_>, fraction: f64) -> Result<Self, ReferenceFitError> {
        let mut pv = Vec::with_capacity(4 * f.panels_v.len());
        for w in f.panels_v.windows(2) {
            for i in 0..4 {
                pv.push(w[0] + (w[1] - w[0]) * i as f64 / 4.0);
            }
        }
        pv.extend(f.panels_v.last());
        let pv = &pv;
        let mut s = Vec::with_capacity(pv.len());
        let mut d = Vec::with_capacity(pv.len());
        let mut acc = 0.0;
        for (i, &v) in pv.iter().enumerate() {
            let sp = Self::derivative(f, fraction, v)?.length();
            if i > 0 {
                let (a, b) = (pv[i - 1], v);
                let (m, h) = (0.5 * (a + b), 0.5 * (b - a));
                let mut part = 0.0;
                for &(x, w) in &f.gl {
                    part += w * Self::derivative(f, fraction, m + h * x)?.length();
                }
                acc += part * h;
            }
            s.push(acc);
            d.push(sp);
        }
        if !acc.is_finite() {
            return Err(ReferenceFitError::NonFinite { what: "derivative" });
        }
        if acc.is_nan() || acc <= 1e-9 * f.diag {
            let edge = if fraction <= 0.0 {
                f.column_name(f.du[0])
            } else {
                format!("through the rows' points at {fraction} of their length")
            };
            return Err(ReferenceFitError::ZeroLengthInitial { edge });
        }
        Ok(AnchorCurve {
            fraction,
            table: Hermite {
                x: pv.clone(),
                s,
                d,
            },
        })
    }

    /// Its arc length `L_t`.
    pub fn length(&self) -> f64 {
        self.table.total()
    }

    /// The `v` at arc length `t` (clamped to the curve), Hermite estimate.
    pub fn v_at(&self, t: f64) -> f64 {
        self.table.inverse(t.clamp(0.0, self.length())).1
    }

    /// The `v` at arc length `t`, to rounding (Newton on the quadrature).
    pub fn v_exact(&self, f: &Frame<'_>, t: f64) -> Result<f64, ReferenceFitError> {
        let target = t.clamp(0.0, self.length());
        let (i, mut v) = self.table.inverse(target);
        let (va, sa) = (self.table.x[i], self.table.s[i]);
        let vb = self.table.x[(i + 1).min(self.table.x.len() - 1)];
        for _ in 0..3 {
            let (m, h) = (0.5 * (va + v), 0.5 * (v - va));
            let mut part = 0.0;
            for &(x, w) in &f.gl {
                part += w * Self::derivative(f, self.fraction, m + h * x)?.length();
            }
            let val = sa + part * h - target;
            let sp = Self::derivative(f, self.fraction, v)?.length();
            if sp.is_nan() || sp <= 0.0 || !val.is_finite() {
                break;
            }
            let step = val / sp;
            v = (v - step).clamp(va, vb);
            if step.abs() <= 1e-15 * (vb - va).abs().max(f64::MIN_POSITIVE) {
                break;
            }
        }
        Ok(v)
    }

    /// The unit tangent of the curve at `v`.
    pub fn unit_tangent(&self, f: &Frame<'_>, v: f64) -> Result<DVec3, ReferenceFitError> {
        let d = Self::derivative(f, self.fraction, v)?;
        d.try_normalize()
            .ok_or_else(|| ReferenceFitError::ZeroLengthInitial {
                edge: format!("near {}", f.row_name(v)),
            })
    }
}
