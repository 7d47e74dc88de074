//! The streamline surface as one B-spline surface (docs/math.md §10; Piegl & Tiller, *The NURBS Book*, §9.4).
//!
//! 1. Start from the Bézier knots (`p + 1` × `q + 1` poles): a surface that
//!    is bilinear in its parameters, such as a flat template, is already exact.
//! 2. Fit: with the parameters shared along rows and columns, least squares
//!    separates. Every row of points is fitted with the `u` basis (one
//!    banded normal matrix, factored once), then every column of the rows'
//!    poles with the `v` basis; both passes interpolate their end points, so
//!    the four corners (and the boundary rows' poles) are exact.
//! 3. Judge the round. The row pass' residual `r_u` (the distance from each
//!    point to its row's curve) and the column pass' residual `r_v` (in the
//!    poles: by convexity of the basis, an upper bound of what `v` adds)
//!    bound the deviation at the fitted points by `max r_u + max r_v`. While
//!    that bound is over 0.8 of the tolerance, every span whose own
//!    direction's residual is over 0.4 of it is split. After that, each
//!    round is measured at every check sample (the grid one depth finer) and
//!    the fit stops when the largest distance there is within the tolerance.
//! 4. Splitting: knots are inserted at the data parameters' quantiles in the
//!    span (a local form of the averaged knots of Eq. 9.69, so every new
//!    span keeps data), into as many pieces as a degree-`p` spline's
//!    `h^{p+1}` error rate says bring the residual under the target (2 to 8). In a check round, a span over the tolerance is split in the
//!    direction whose residual is at least half the tolerance there, else a
//!    quarter, else in both.

use super::deviation::{Deviation, measure};
use super::error::{Direction, FitError};
use super::knots::{KnotVector, MAX_DEGREE, MIN_DEGREE};
use super::lsq::EndFixedFit;
use super::samples::Samples;
use super::surface::BSplineSurface;
use crate::grid::Grid;
use crate::levels::design::Design;
use glam::DVec3;

/// The default relative tolerance: this fraction of the bounding box's diagonal.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-4;

/// How close the fit must come.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tolerance {
    /// A fraction of the diagonal of the fitted points' bounding box.
    Relative(f64),
    /// A distance in scene units.
    Absolute(f64),
}

/// Degrees and tolerance of a fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// `(p, q)`: degree in `u` (along the streamlines) and `v`, each 2–5.
    pub degree: (usize, usize),
    /// The largest allowed deviation.
    pub tolerance: Tolerance,
}

impl FitOptions {
    /// Bicubic, within `1e-4` of the diagonal.
    pub const DEFAULT: FitOptions = FitOptions {
        degree: (3, 3),
        tolerance: Tolerance::Relative(DEFAULT_RELATIVE_TOLERANCE),
    };
}

impl Default for FitOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What a fit reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitReport {
    /// `(p, q)`.
    pub degree: (usize, usize),
    /// Pole counts `(in u, in v)`.
    pub poles: (usize, usize),
    /// The absolute tolerance met.
    pub tolerance: f64,
    /// Largest and mean distance at the check samples.
    pub deviation: Deviation,
    /// `(rows, columns)` of the check grid.
    pub checked: (usize, usize),
    /// Fit-and-measure rounds.
    pub rounds: usize,
}

/// A fitted surface and its report.
#[derive(Debug, Clone)]
pub struct Fit {
    /// The B-spline surface.
    pub surface: BSplineSurface,
    /// Its figures.
    pub report: FitReport,
}

/// Checks the options; returns the absolute tolerance for `data`.
pub(crate) fn check_options(opts: &FitOptions, data: &Samples) -> Result<f64, FitError> {
    let (p, q) = opts.degree;
    for (direction, degree) in [(Direction::U, p), (Direction::V, q)] {
        if !(MIN_DEGREE..=MAX_DEGREE).contains(&degree) {
            return Err(FitError::BadDegree { direction, degree });
        }
    }
    let (value, tol) = match opts.tolerance {
        Tolerance::Relative(r) => (r, r * data.diagonal()),
        Tolerance::Absolute(a) => (a, a),
    };
    if !(value.is_finite() && value > 0.0) {
        return Err(FitError::BadTolerance { value });
    }
    if !(tol.is_finite() && tol > 0.0) {
        // a relative tolerance on points that all coincide
        return Err(FitError::BadTolerance { value: tol });
    }
    Ok(tol)
}

/// Fits the design built at `depth`, checked against `depth + 1`.
pub fn fit_design(design: &Design, depth: u32, opts: &FitOptions) -> Result<Fit, FitError> {
    let (data, check) = Samples::build_pair(design, depth)?;
    fit(&data, &check, opts)
}

/// The rows' and columns' fits for one pair of knot vectors.
pub(super) struct Pass {
    /// The fitted surface.
    pub(super) surface: BSplineSurface,
    rows: EndFixedFit,
    cols: EndFixedFit,
    /// The rows' poles, `data.v.len() × nu`.
    row_poles: Vec<DVec3>,
}

impl Pass {
    /// Largest row-pass residual per `u` span, and largest column-pass
    /// residual (in the poles) per `v` span: what each direction explains
    /// of the deviation (computed only for a round that goes on).
    fn residuals(&self, data: &Samples) -> (Vec<f64>, Vec<f64>) {
        (self.residuals_u(data), self.residuals_v(data))
    }

    /// The row pass' largest residual per `u` span (see [`Self::residuals`]).
    pub(super) fn residuals_u(&self, data: &Samples) -> Vec<f64> {
        let nu = self.rows.count();
        let mut res_u = vec![0.0f64; self.surface.knots_u.spans()];
        for (j, poles) in self.row_poles.chunks(nu).enumerate() {
            for (k, pt) in data.points.row(j).iter().enumerate() {
                let r = &mut res_u[self.rows.span_of(k)];
                *r = r.max((self.rows.point(poles, k) - *pt).length_squared());
            }
        }
        res_u.iter().map(|r| r.sqrt()).collect()
    }

    /// The column pass' largest residual (in the poles) per `v` span (see
    /// [`Self::residuals`]): a curve of poles a row, not a point of the
    /// grid, so it costs a fraction of [`Self::residuals_u`].
    pub(super) fn residuals_v(&self, data: &Samples) -> Vec<f64> {
        let nu = self.rows.count();
        let mut res_v = vec![0.0f64; self.surface.knots_v.spans()];
        let mut curve = Vec::with_capacity(nu);
        for (l, &v) in data.v.iter().enumerate() {
            self.surface.curve_at_into(v, &mut curve);
            let worst = curve
                .iter()
                .zip(&self.row_poles[l * nu..(l + 1) * nu])
                .map(|(a, b)| (*a - *b).length_squared())
                .fold(0.0f64, f64::max);
            let r = &mut res_v[self.cols.span_of(l)];
            *r = r.max(worst);
        }
        res_v.iter().map(|r| r.sqrt()).collect()
    }
}

fn too_few(direction: Direction, data: &Samples, tolerance: f64, reached: f64) -> FitError {
    let points = match direction {
        Direction::U => data.u.len(),
        Direction::V => data.v.len(),
    };
    FitError::TooFewPoints {
        direction,
        points,
        tolerance,
        reached,
    }
}

fn pass(
    ku: &KnotVector,
    kv: &KnotVector,
    data: &Samples,
    tol: f64,
    reached: f64,
) -> Result<Pass, FitError> {
    let (mv, mu) = (data.v.len(), data.u.len());
    if ku.count() > mu {
        return Err(too_few(Direction::U, data, tol, reached));
    }
    if kv.count() > mv {
        return Err(too_few(Direction::V, data, tol, reached));
    }
    let rows =
        EndFixedFit::new(ku, &data.u).map_err(|_| too_few(Direction::U, data, tol, reached))?;
    let cols =
        EndFixedFit::new(kv, &data.v).map_err(|_| too_few(Direction::V, data, tol, reached))?;
    let nu = rows.count();
    // row pass, then column pass
    let mut row_poles = vec![DVec3::ZERO; mv * nu];
    for (j, out) in row_poles.chunks_mut(nu).enumerate() {
        rows.fit_row(data.points.row(j), out);
    }
    let mut poles = Vec::new();
    cols.fit_columns(&row_poles, nu, &mut poles);
    let poles = Grid::new(kv.count(), nu, poles).expect("count × nu");
    let surface = BSplineSurface {
        knots_u: ku.clone(),
        knots_v: kv.clone(),
        poles,
    };
    Ok(Pass {
        surface,
        rows,
        cols,
        row_poles,
    })
}

/// The separable least-squares fit of `data` on given knot vectors alone
/// (no refinement): rows with `knots_u`, then columns with `knots_v`, ends
/// interpolated.
pub fn fit_knots(
    data: &Samples,
    knots_u: &KnotVector,
    knots_v: &KnotVector,
) -> Result<BSplineSurface, FitError> {
    Ok(fit_pass(data, knots_u, knots_v)?.surface)
}

/// [`fit_knots`] with its passes kept, for their residuals
/// ([`Pass::residuals`]): what each direction explains of a deviation.
pub(super) fn fit_pass(
    data: &Samples,
    knots_u: &KnotVector,
    knots_v: &KnotVector,
) -> Result<Pass, FitError> {
    pass(knots_u, knots_v, data, f64::NAN, f64::NAN)
}

/// Knots that split span `j` of `knots` into `pieces` with about as many
/// of the data parameters in each (Eq. 9.69 within the span: knot `i` is
/// `(1 − α) ū_{k−1} + α ū_k` over the span's own parameters, `k = ⌊i d⌋`,
/// `α = i d − k`, `d` = parameters per piece). Fewer pieces when the span
/// holds fewer than two parameters a piece; none when it cannot be split.
pub(super) fn split_points(
    knots: &KnotVector,
    params: &[f64],
    j: usize,
    pieces: usize,
    out: &mut Vec<f64>,
) {
    let (a, b) = knots.span_range(j);
    let last = j + 1 == knots.spans();
    let lo = params.partition_point(|x| *x < a);
    let hi = if last {
        params.len()
    } else {
        params.partition_point(|x| *x < b)
    };
    let inside = &params[lo..hi];
    let pieces = pieces.min(inside.len() / 2);
    if pieces < 2 {
        return;
    }
    let d = inside.len() as f64 / pieces as f64;
    let mut prev = a;
    for i in 1..pieces {
        let id = i as f64 * d;
        let k = (id.floor() as usize).clamp(1, inside.len() - 1);
        let alpha = id - k as f64;
        let knot = (1.0 - alpha) * inside[k - 1] + alpha * inside[k];
        if knot > prev && knot < b {
            out.push(knot);
            prev = knot;
        }
    }
}

/// How many pieces bring a span's error `e` of a degree-`p` fit under the
/// target `tol`, the error of a spline shrinking as `h^{p+1}`.
pub(super) fn pieces_for(e: f64, tol: f64, p: usize) -> usize {
    let ratio = (e / tol).max(1.0);
    (ratio.powf(1.0 / (p + 1) as f64).ceil() as usize).clamp(2, 8)
}

/// The rounds judged at the fitted points go on until those are within
/// this fraction of the tolerance: the check grid between them is usually
/// a little farther, and a round measured there costs four times as much.
const DATA_MARGIN: f64 = 0.8;

/// Fits `data` until the largest distance to `check` is within the tolerance.
pub fn fit(data: &Samples, check: &Samples, opts: &FitOptions) -> Result<Fit, FitError> {
    let tol = check_options(opts, data)?;
    let (p, q) = opts.degree;
    let mut ku = KnotVector::bezier(p);
    let mut kv = KnotVector::bezier(q);
    let mut reached = f64::INFINITY;
    let mut checked = false;
    // until the fitted points are within the margin (by the passes'
    // residuals, which bound their deviation), each direction is refined by
    // its own residual; then rounds are measured at the check grid
    let mut on_check = false;
    for round in 1.. {
        let pass = pass(&ku, &kv, data, tol, reached)?;
        let worst = |r: &[f64]| r.iter().copied().fold(0.0f64, f64::max);
        // the residuals, computed once a round needs them
        let mut res = None;
        if !on_check {
            let (res_u, res_v) = res.insert(pass.residuals(data));
            // |Q − F| ≤ |Q − C_j| + |C_j − F|: the row residual plus the
            // column residual of the poles (the basis is a convex combination)
            let bound = worst(res_u) + worst(res_v);
            reached = reached.min(bound);
            on_check = bound <= DATA_MARGIN * tol;
        }
        let (eff, mut pick_u, mut pick_v) = if on_check {
            // parametric: a face judged by foot points may pass with check
            // points off its boundary, which OpenCascade's projection (an
            // orthogonal one) does not see (docs/math.md §10)
            let mut m = measure(&pass.surface, check, f64::INFINITY, None);
            if m.deviation.max <= tol {
                // the fitted points too: a round that reached the check grid
                // without its bound under the margin has not bounded them
                let at_data = measure(&pass.surface, data, f64::INFINITY, None);
                if at_data.deviation.max > tol {
                    m = at_data;
                }
            }
            // the closest reached is what the check grid measured, once it has
            reached = if checked {
                reached.min(m.deviation.max)
            } else {
                m.deviation.max
            };
            checked = true;
            if m.deviation.max <= tol {
                let report = FitReport {
                    degree: (p, q),
                    poles: pass.surface.pole_counts(),
                    tolerance: tol,
                    deviation: m.deviation,
                    checked: (check.v.len(), check.u.len()),
                    rounds: round,
                };
                return Ok(Fit {
                    surface: pass.surface,
                    report,
                });
            }
            // spans over the tolerance at the check samples, split in the
            // direction whose residual carries the error
            let (res_u, res_v) = res.get_or_insert_with(|| pass.residuals(data));
            let over = |e: &[f64]| -> Vec<usize> { (0..e.len()).filter(|&j| e[j] > tol).collect() };
            let (over_u, over_v) = (over(&m.span_u), over(&m.span_v));
            let (mut pick_u, mut pick_v) = (Vec::new(), Vec::new());
            for gamma in [0.5, 0.25, 0.0] {
                pick_u = over_u
                    .iter()
                    .copied()
                    .filter(|&j| res_u[j] >= gamma * tol)
                    .collect();
                pick_v = over_v
                    .iter()
                    .copied()
                    .filter(|&j| res_v[j] >= gamma * tol)
                    .collect();
                if !(pick_u.is_empty() && pick_v.is_empty()) {
                    break;
                }
            }
            (tol, pick_u, pick_v)
        } else {
            let eff = DATA_MARGIN * tol;
            let (res_u, res_v) = res.as_ref().expect("computed above");
            let over =
                |r: &[f64]| -> Vec<usize> { (0..r.len()).filter(|&j| r[j] > 0.5 * eff).collect() };
            (eff, over(res_u), over(res_v))
        };
        pick_u.sort_unstable();
        pick_v.sort_unstable();
        let (res_u, res_v) = res.as_ref().expect("computed for the picks");
        let mut new_u = Vec::new();
        for &j in &pick_u {
            let pieces = pieces_for(res_u[j], eff, p);
            split_points(&ku, &data.u, j, pieces, &mut new_u);
        }
        let mut new_v = Vec::new();
        for &j in &pick_v {
            let pieces = pieces_for(res_v[j], eff, q);
            split_points(&kv, &data.v, j, pieces, &mut new_v);
        }
        if new_u.is_empty() && new_v.is_empty() {
            // the fitted points' bound cannot be split further under the
            // margin: the check grid judges (the margin only saves rounds)
            if !on_check && !checked {
                on_check = true;
                continue;
            }
            let dir = if pick_u.is_empty() {
                Direction::V
            } else {
                Direction::U
            };
            return Err(too_few(dir, data, tol, reached));
        }
        for k in new_u {
            ku.insert(k);
        }
        for k in new_v {
            kv.insert(k);
        }
    }
    unreachable!("the loop returns")
}
