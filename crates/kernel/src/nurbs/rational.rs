//! A (possibly rational) tensor-product B-spline surface as CAD files carry it
//! (STEP `B_SPLINE_SURFACE_WITH_KNOTS` with or without
//! `RATIONAL_B_SPLINE_SURFACE`, IGES entity 128): any degree from 1 to
//! [`MAX_DEGREE`], any non-decreasing knots (clamped or not, multiplicities
//! expanded), weights optional. It is the reference a streamline design is
//! fitted to (`docs/math.md §12`), evaluated by the rational quotient rule
//! `S = A/W`, `S_u = (A_u − W_u S)/W` (Piegl & Tiller, *The NURBS Book*,
//! Eq. 4.8), with the homogeneous sums `A = Σ N_k M_l w_{lk} P_{lk}`,
//! `W = Σ N_k M_l w_{lk}`.

use super::surface::BSplineSurface;
use crate::grid::Grid;
use glam::DVec3;
use std::fmt;

/// The most work [`NurbsSurface::area`] and [`NurbsSurface::bounds`]
/// spend on one surface, in products of a basis function pair and a pole
/// (`(p + 1)(q + 1)` per evaluation): 64 million, four million evaluations
/// of a bicubic, so that no face a file brings takes more than a second or
/// so to describe.
pub const WORK_BUDGET: usize = 64_000_000;

/// The largest degree accepted in either direction (STEP and IGES allow
/// more in principle; CAD systems write at most 25, and a file with more is
/// refused with [`NurbsError::BadDegree`]).
pub const MAX_DEGREE: usize = 25;

/// Everything that can be wrong with the data of a NURBS surface, each with
/// what to do about it.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum NurbsError {
    /// No poles at all (or a knot vector too short to hold one span).
    Empty { what: &'static str },
    /// A degree of 0 or above [`MAX_DEGREE`].
    BadDegree { direction: char, degree: usize },
    /// The number of poles in a direction is not `knots − degree − 1`.
    PoleCountMismatch {
        direction: char,
        poles: usize,
        knots: usize,
        degree: usize,
    },
    /// The weight grid's shape differs from the pole grid's.
    WeightShape {
        rows: usize,
        cols: usize,
        pole_rows: usize,
        pole_cols: usize,
    },
    /// Knot `index` is smaller than the one before it.
    KnotsDecrease { direction: char, index: usize },
    /// A knot repeated more than `degree + 1` times.
    KnotMultiplicity {
        direction: char,
        index: usize,
        multiplicity: usize,
        degree: usize,
    },
    /// The parameter domain `[k_p, k_{n}]` is empty.
    EmptyDomain { direction: char },
    /// A NaN or infinite number.
    NonFinite {
        what: &'static str,
        row: usize,
        col: usize,
    },
    /// A weight that is zero or negative.
    NonPositiveWeight { row: usize, col: usize, weight: f64 },
    /// A scale factor that is not a positive finite number.
    BadScale { factor: f64 },
}

impl fmt::Display for NurbsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NurbsError::Empty { what } => write!(
                f,
                "the NURBS surface has no {what}; the face carries no surface: choose another face or re-export it from the CAD system"
            ),
            NurbsError::BadDegree { direction, degree } => write!(
                f,
                "NURBS degree {degree} in {direction} is outside 1 to {MAX_DEGREE}; re-export the face with a lower degree (rebuild it in the CAD system)"
            ),
            NurbsError::PoleCountMismatch {
                direction,
                poles,
                knots,
                degree,
            } => write!(
                f,
                "the NURBS surface has {poles} poles in {direction} but {knots} knots of degree {degree} need {} (knots − degree − 1); the file is inconsistent: check that the knot multiplicities were expanded, or re-export the face",
                knots.saturating_sub(degree + 1)
            ),
            NurbsError::WeightShape {
                rows,
                cols,
                pole_rows,
                pole_cols,
            } => write!(
                f,
                "the NURBS weights form a {rows} × {cols} grid but the poles a {pole_rows} × {pole_cols} one; give one weight per pole, or none for a non-rational surface"
            ),
            NurbsError::KnotsDecrease { direction, index } => write!(
                f,
                "the {direction} knots decrease at knot {index}; knots must be non-decreasing: the file is damaged or the knots were read in the wrong order"
            ),
            NurbsError::KnotMultiplicity {
                direction,
                index,
                multiplicity,
                degree,
            } => write!(
                f,
                "the {direction} knot at index {index} is repeated {multiplicity} times, more than degree + 1 = {}; remove the extra copies or re-export the face",
                degree + 1
            ),
            NurbsError::EmptyDomain { direction } => write!(
                f,
                "the NURBS surface's parameter range in {direction} is empty (its knots from index degree to the last pole's are all equal); the face is degenerate: choose another face"
            ),
            NurbsError::NonFinite { what, row, col } => write!(
                f,
                "the NURBS surface has a non-finite {what} at ({row}, {col}); the file is damaged: re-export the face"
            ),
            NurbsError::NonPositiveWeight { row, col, weight } => write!(
                f,
                "the NURBS weight at row {row}, column {col} is {weight}, not positive; weights must be > 0: re-export the face (or divide all weights by a negative common factor)"
            ),
            NurbsError::BadScale { factor } => write!(
                f,
                "scale factor {factor} is not a positive finite number; use the ratio of the file's length unit to metres (0.001 for millimetres)"
            ),
        }
    }
}

impl std::error::Error for NurbsError {}

/// A (possibly rational) B-spline surface as CAD files carry it.
///
/// `poles` has one row per `v` basis function and one column per `u` basis
/// function (rows index `v`, columns index `u`), like
/// [`BSplineSurface::poles`].
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface {
    degree_u: usize,
    degree_v: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    poles: Grid<DVec3>,
    weights: Option<Grid<f64>>,
    /// Homogeneous poles `(w P, w)`, row-major like `poles`.
    hom: Vec<[f64; 4]>,
}

/// Basis values and first derivatives at one parameter: the first nonzero
/// function's index, then `p + 1` values and `p + 1` derivatives.
struct BasisDers {
    first: usize,
    n: [f64; MAX_DEGREE + 1],
    d: [f64; MAX_DEGREE + 1],
}

fn check_knots(direction: char, degree: usize, knots: &[f64]) -> Result<(), NurbsError> {
    if degree == 0 || degree > MAX_DEGREE {
        return Err(NurbsError::BadDegree { direction, degree });
    }
    for (i, k) in knots.iter().enumerate() {
        if !k.is_finite() {
            let (row, col) = if direction == 'u' { (0, i) } else { (i, 0) };
            return Err(NurbsError::NonFinite {
                what: if direction == 'u' { "u knot" } else { "v knot" },
                row,
                col,
            });
        }
    }
    let mut run = 1;
    for i in 1..knots.len() {
        if knots[i] < knots[i - 1] {
            return Err(NurbsError::KnotsDecrease {
                direction,
                index: i,
            });
        }
        if knots[i] == knots[i - 1] {
            run += 1;
            if run > degree + 1 {
                return Err(NurbsError::KnotMultiplicity {
                    direction,
                    index: i,
                    multiplicity: run,
                    degree,
                });
            }
        } else {
            run = 1;
        }
    }
    Ok(())
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
    /// A surface from CAD data. `knots_u`/`knots_v`: the full (expanded,
    /// with multiplicities) knot vectors; `poles`: rows index `v` (count =
    /// `knots_v.len() − degree_v − 1`), columns index `u` (count =
    /// `knots_u.len() − degree_u − 1`); `weights` the same shape when
    /// rational (all positive). Every inconsistency is a [`NurbsError`].
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        poles: Grid<DVec3>,
        weights: Option<Grid<f64>>,
    ) -> Result<Self, NurbsError> {
        if poles.rows() == 0 || poles.cols() == 0 {
            return Err(NurbsError::Empty { what: "poles" });
        }
        check_knots('u', degree_u, &knots_u)?;
        check_knots('v', degree_v, &knots_v)?;
        for (direction, knots, degree, count) in [
            ('u', &knots_u, degree_u, poles.cols()),
            ('v', &knots_v, degree_v, poles.rows()),
        ] {
            if knots.len() < degree + 2 || knots.len() - degree - 1 != count || count < degree + 1 {
                return Err(NurbsError::PoleCountMismatch {
                    direction,
                    poles: count,
                    knots: knots.len(),
                    degree,
                });
            }
            if knots[degree] >= knots[count] {
                return Err(NurbsError::EmptyDomain { direction });
            }
        }
        for r in 0..poles.rows() {
            for c in 0..poles.cols() {
                if !poles.get(r, c).is_finite() {
                    return Err(NurbsError::NonFinite {
                        what: "pole",
                        row: r,
                        col: c,
                    });
                }
            }
        }
        if let Some(w) = &weights {
            if w.rows() != poles.rows() || w.cols() != poles.cols() {
                return Err(NurbsError::WeightShape {
                    rows: w.rows(),
                    cols: w.cols(),
                    pole_rows: poles.rows(),
                    pole_cols: poles.cols(),
                });
            }
            for r in 0..w.rows() {
                for c in 0..w.cols() {
                    let x = w.get(r, c);
                    if !x.is_finite() {
                        return Err(NurbsError::NonFinite {
                            what: "weight",
                            row: r,
                            col: c,
                        });
                    }
                    if x <= 0.0 {
                        return Err(NurbsError::NonPositiveWeight {
                            row: r,
                            col: c,
                            weight: x,
                        });
                    }
                }
            }
        }
        let hom = Self::homogeneous(&poles, weights.as_ref());
        Ok(NurbsSurface {
            degree_u,
            degree_v,
            knots_u,
            knots_v,
            poles,
            weights,
            hom,
        })
    }

    fn homogeneous(poles: &Grid<DVec3>, weights: Option<&Grid<f64>>) -> Vec<[f64; 4]> {
        poles
            .data()
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let w = weights.map_or(1.0, |w| w.data()[i]);
                [p.x * w, p.y * w, p.z * w, w]
            })
            .collect()
    }

    /// Degrees `(in u, in v)`.
    pub fn degrees(&self) -> (usize, usize) {
        (self.degree_u, self.degree_v)
    }

    /// Pole counts `(in u, in v)` = (columns, rows) of [`Self::poles`].
    pub fn pole_counts(&self) -> (usize, usize) {
        (self.poles.cols(), self.poles.rows())
    }

    /// Whether the surface carries weights.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// The full `u` knot vector.
    pub fn knots_u(&self) -> &[f64] {
        &self.knots_u
    }

    /// The full `v` knot vector.
    pub fn knots_v(&self) -> &[f64] {
        &self.knots_v
    }

    /// The poles, rows index `v`, columns index `u`.
    pub fn poles(&self) -> &Grid<DVec3> {
        &self.poles
    }

    /// The weights, when rational.
    pub fn weights(&self) -> Option<&Grid<f64>> {
        self.weights.as_ref()
    }

    /// The parameter domain `([u0, u1], [v0, v1])`: `[k_p, k_n]` in each
    /// direction, `n` the pole count.
    pub fn domain(&self) -> ([f64; 2], [f64; 2]) {
        let (nu, nv) = self.pole_counts();
        (
            [self.knots_u[self.degree_u], self.knots_u[nu]],
            [self.knots_v[self.degree_v], self.knots_v[nv]],
        )
    }

    /// The non-empty knot spans in `u` and in `v`, each as `[a, b]`.
    pub fn spans(&self) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
        let (nu, nv) = self.pole_counts();
        let f = |k: &[f64], p: usize, n: usize| -> Vec<[f64; 2]> {
            (p..n)
                .filter(|&i| k[i + 1] > k[i])
                .map(|i| [k[i], k[i + 1]])
                .collect()
        };
        (
            f(&self.knots_u, self.degree_u, nu),
            f(&self.knots_v, self.degree_v, nv),
        )
    }

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

    /// The same surface with `u` and `v` exchanged: `swapped().point(v, u)
    /// == point(u, v)`.
    pub fn swapped(&self) -> NurbsSurface {
        let poles = self.poles.transpose();
        let weights = self.weights.as_ref().map(Grid::transpose);
        let hom = Self::homogeneous(&poles, weights.as_ref());
        NurbsSurface {
            degree_u: self.degree_v,
            degree_v: self.degree_u,
            knots_u: self.knots_v.clone(),
            knots_v: self.knots_u.clone(),
            poles,
            weights,
            hom,
        }
    }

    /// The surface scaled about the origin by `factor` (a unit conversion:
    /// 0.001 from millimetres to metres); weights and knots are unchanged.
    /// A factor that is not positive and finite leaves the surface as it is
    /// ([`Self::try_scaled`] says so as an error).
    pub fn scaled(&self, factor: f64) -> NurbsSurface {
        self.try_scaled(factor).unwrap_or_else(|_| self.clone())
    }

    /// [`Self::scaled`], refusing a factor that is not positive and finite
    /// (or that would overflow a pole).
    pub fn try_scaled(&self, factor: f64) -> Result<NurbsSurface, NurbsError> {
        if !(factor.is_finite() && factor > 0.0) {
            return Err(NurbsError::BadScale { factor });
        }
        let data: Vec<DVec3> = self.poles.data().iter().map(|p| *p * factor).collect();
        if data.iter().any(|p| !p.is_finite()) {
            return Err(NurbsError::BadScale { factor });
        }
        let poles = Grid::new(self.poles.rows(), self.poles.cols(), data)
            .map_err(|_| NurbsError::Empty { what: "poles" })?;
        let hom = Self::homogeneous(&poles, self.weights.as_ref());
        Ok(NurbsSurface {
            poles,
            hom,
            ..self.clone()
        })
    }

    /// The non-rational surface of the §10 export ([`BSplineSurface`], on
    /// `[0, 1]²`). Its fields are public, so it may be inconsistent: then
    /// this returns the bilinear patch through its corner poles (the origin
    /// when it has none); [`Self::try_from_bspline`] returns the error.
    pub fn from_bspline(s: &BSplineSurface) -> NurbsSurface {
        Self::try_from_bspline(s).unwrap_or_else(|_| {
            let g = &s.poles;
            let corner = |r: usize, c: usize| {
                if g.rows() > 0 && g.cols() > 0 {
                    let p = g.get(r.min(g.rows() - 1), c.min(g.cols() - 1));
                    if p.is_finite() {
                        return p;
                    }
                }
                DVec3::ZERO
            };
            let last_r = g.rows().saturating_sub(1);
            let last_c = g.cols().saturating_sub(1);
            let data = vec![
                corner(0, 0),
                corner(0, last_c),
                corner(last_r, 0),
                corner(last_r, last_c),
            ];
            let poles = Grid::new(2, 2, data).unwrap_or_else(|_| Grid::filled(2, 2, DVec3::ZERO));
            let hom = Self::homogeneous(&poles, None);
            NurbsSurface {
                degree_u: 1,
                degree_v: 1,
                knots_u: vec![0.0, 0.0, 1.0, 1.0],
                knots_v: vec![0.0, 0.0, 1.0, 1.0],
                poles,
                weights: None,
                hom,
            }
        })
    }

    /// [`Self::from_bspline`], returning the error of an inconsistent surface.
    pub fn try_from_bspline(s: &BSplineSurface) -> Result<NurbsSurface, NurbsError> {
        let (p, q) = s.degree();
        NurbsSurface::new(
            p,
            q,
            s.knots_u.knots().to_vec(),
            s.knots_v.knots().to_vec(),
            s.poles.clone(),
            None,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nurbs::knots::KnotVector;

    /// A quarter cylinder of radius `r` about the `z` axis, `z ∈ [0, h]`, as
    /// a rational quadratic (`u`, the arc) × linear (`v`, the height).
    fn quarter_cylinder(r: f64, h: f64) -> NurbsSurface {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let arc = [
            DVec3::new(r, 0.0, 0.0),
            DVec3::new(r, r, 0.0),
            DVec3::new(0.0, r, 0.0),
        ];
        let mut poles = Vec::new();
        let mut weights = Vec::new();
        for z in [0.0, h] {
            for p in arc {
                poles.push(p + DVec3::new(0.0, 0.0, z));
            }
            weights.extend([1.0, w, 1.0]);
        }
        NurbsSurface::new(
            2,
            1,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 1.0, 1.0],
            Grid::new(2, 3, poles).unwrap(),
            Some(Grid::new(2, 3, weights).unwrap()),
        )
        .unwrap()
    }

    #[test]
    fn quarter_cylinder_points_are_on_the_circle() {
        let s = quarter_cylinder(2.5, 1.0);
        for i in 0..=50 {
            for j in 0..=5 {
                let p = s.point(i as f64 / 50.0, j as f64 / 5.0);
                let r = (p.x * p.x + p.y * p.y).sqrt();
                assert!((r - 2.5).abs() < 1e-12, "radius {r}");
            }
        }
        assert!(s.is_rational());
        assert_eq!(s.pole_counts(), (3, 2));
        assert_eq!(s.degrees(), (2, 1));
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let s = quarter_cylinder(1.3, 0.7);
        // a non-uniform cubic × quadratic too
        let kv_u = KnotVector::with_interior(3, &[0.2, 0.55]).unwrap();
        let kv_v = KnotVector::with_interior(2, &[0.4]).unwrap();
        let mut pts = Vec::new();
        let mut ws = Vec::new();
        for r in 0..kv_v.count() {
            for c in 0..kv_u.count() {
                let (x, y) = (c as f64, r as f64);
                pts.push(DVec3::new(x, y, (x * 1.7 + y * 0.3).sin()));
                ws.push(1.0 + 0.3 * ((x + 2.0 * y).cos()));
            }
        }
        let t = NurbsSurface::new(
            3,
            2,
            kv_u.knots().to_vec(),
            kv_v.knots().to_vec(),
            Grid::new(kv_v.count(), kv_u.count(), pts).unwrap(),
            Some(Grid::new(kv_v.count(), kv_u.count(), ws).unwrap()),
        )
        .unwrap();
        let h = 1e-6;
        for surf in [&s, &t] {
            for (u, v) in [(0.1, 0.3), (0.37, 0.81), (0.6, 0.5), (0.9, 0.05)] {
                let [p, du, dv] = surf.derivatives(u, v);
                assert!((p - surf.point(u, v)).length() < 1e-14);
                let fu = (surf.point(u + h, v) - surf.point(u - h, v)) / (2.0 * h);
                let fv = (surf.point(u, v + h) - surf.point(u, v - h)) / (2.0 * h);
                assert!(
                    (du - fu).length() < 1e-7 * (1.0 + du.length()),
                    "{du} vs {fu}"
                );
                assert!(
                    (dv - fv).length() < 1e-7 * (1.0 + dv.length()),
                    "{dv} vs {fv}"
                );
            }
        }
    }

    #[test]
    fn areas_of_a_rectangle_and_a_cylinder_patch() {
        let rect = NurbsSurface::new(
            1,
            1,
            vec![0.0, 0.0, 2.0, 2.0],
            vec![-1.0, -1.0, 3.0, 3.0],
            Grid::new(
                2,
                2,
                vec![
                    DVec3::ZERO,
                    DVec3::new(3.0, 0.0, 0.0),
                    DVec3::new(0.0, 2.0, 0.0),
                    DVec3::new(3.0, 2.0, 0.0),
                ],
            )
            .unwrap(),
            None,
        )
        .unwrap();
        assert!((rect.area() - 6.0).abs() < 1e-13);
        let cyl = quarter_cylinder(2.0, 3.0);
        let want = std::f64::consts::FRAC_PI_2 * 2.0 * 3.0;
        assert!(
            (cyl.area() - want).abs() < 1e-12 * want,
            "{} vs {want}",
            cyl.area()
        );
        let b = cyl.bounds();
        assert!((b[0] - DVec3::ZERO).length() < 1e-12);
        assert!((b[1] - DVec3::new(2.0, 2.0, 3.0)).length() < 1e-12);
        assert!(!cyl.closed_u(1e-9) && !cyl.closed_v(1e-9));
    }

    #[test]
    fn swapped_scaled_and_from_bspline() {
        let s = quarter_cylinder(1.0, 2.0);
        let w = s.swapped();
        let k = s.scaled(1e-3);
        for (u, v) in [(0.2, 0.7), (0.0, 1.0), (0.9, 0.1)] {
            assert!((w.point(v, u) - s.point(u, v)).length() < 1e-15);
            assert!((k.point(u, v) - s.point(u, v) * 1e-3).length() < 1e-15);
        }
        assert_eq!(s.scaled(f64::NAN), s);
        let b = BSplineSurface {
            knots_u: KnotVector::with_interior(3, &[0.5]).unwrap(),
            knots_v: KnotVector::bezier(2),
            poles: Grid::new(
                3,
                5,
                (0..15)
                    .map(|i| DVec3::new(i as f64, (i * i) as f64, 1.0))
                    .collect(),
            )
            .unwrap(),
        };
        let n = NurbsSurface::from_bspline(&b);
        assert!(!n.is_rational());
        for (u, v) in [(0.2, 0.7), (0.5, 0.5), (1.0, 1.0)] {
            assert!((n.point(u, v) - b.eval(u, v)).length() < 1e-12);
        }
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let g = Grid::filled(2, 2, DVec3::ZERO);
        let k = vec![0.0, 0.0, 1.0, 1.0];
        let cases = [
            NurbsSurface::new(0, 1, k.clone(), k.clone(), g.clone(), None),
            NurbsSurface::new(2, 1, k.clone(), k.clone(), g.clone(), None),
            NurbsSurface::new(1, 1, vec![0.0, 1.0, 0.5, 1.0], k.clone(), g.clone(), None),
            NurbsSurface::new(
                1,
                1,
                vec![0.0, 0.0, f64::NAN, 1.0],
                k.clone(),
                g.clone(),
                None,
            ),
            NurbsSurface::new(1, 1, vec![1.0; 4], k.clone(), g.clone(), None),
            NurbsSurface::new(
                1,
                1,
                k.clone(),
                k.clone(),
                g.clone(),
                Some(Grid::filled(2, 2, 0.0)),
            ),
            NurbsSurface::new(
                1,
                1,
                k.clone(),
                k.clone(),
                g.clone(),
                Some(Grid::filled(1, 2, 1.0)),
            ),
            NurbsSurface::new(
                1,
                1,
                k.clone(),
                k.clone(),
                Grid::filled(2, 2, DVec3::splat(f64::INFINITY)),
                None,
            ),
            NurbsSurface::new(
                1,
                1,
                k.clone(),
                k.clone(),
                Grid::filled(0, 0, DVec3::ZERO),
                None,
            ),
            NurbsSurface::new(1, 1, vec![], k.clone(), g.clone(), None),
        ];
        for c in cases {
            let e = c.unwrap_err();
            assert!(e.to_string().len() > 40, "{e}");
        }
        // evaluation outside the domain and at NaN clamps
        let s = quarter_cylinder(1.0, 1.0);
        assert!(s.point(f64::NAN, 5.0).is_finite());
        assert!(s.derivatives(-3.0, f64::INFINITY)[1].is_finite());
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        for n in 1..12 {
            let g = gauss_legendre(n);
            for d in 0..2 * n {
                let got: f64 = g.iter().map(|(x, w)| w * x.powi(d as i32)).sum();
                let want = if d % 2 == 1 {
                    0.0
                } else {
                    2.0 / (d as f64 + 1.0)
                };
                assert!((got - want).abs() < 1e-13, "n{n} d{d}: {got} vs {want}");
            }
        }
    }
}
