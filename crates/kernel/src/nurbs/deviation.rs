//! The distance from sampled surface points to a fitted B-spline surface
//! (docs/math.md §10). Each point is first compared with the fit at its own
//! parameters: this parametric distance `|S_ij − F(u_i, v_j)|` is never less
//! than the distance from `S_ij` to the nearest point of `F`, so a point
//! within the tolerance by it is within by any measure. A point farther
//! than the tolerance (up to [`FOOT_RANGE`] times it) is then measured to
//! its foot point on `F`: Newton's
//! iteration for the nearest point, started at `(u_i, v_j)` and kept within
//! four sample spacings of it. The check grid's parameters are its own
//! (normalised arc length and `t`, one depth finer than the data), and where
//! a subdivision scheme moves the boundary with depth (Catmull–Clark and
//! Doo–Sabin shorten the boundary streamlines) they slide against the
//! data's by about a sample spacing: the parametric distance then measures
//! that slide (`|∂F/∂u| δu`, halving per depth) rather than the fit, and a
//! fit judged by it alone is refused at every depth. The foot point's
//! distance is still the distance to a point of `F`, never less than the
//! nearest one's (what OpenCascade's projection reports, tests/python/).

use super::samples::Samples;
use super::surface::{BSplineSurface, BasisTable};
use crate::grid::Grid;
use glam::DVec3;

/// Largest and mean distance over a grid of samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deviation {
    /// The largest distance.
    pub max: f64,
    /// The mean distance.
    pub mean: f64,
    /// Row and column of the sample with the largest distance.
    pub at: (usize, usize),
}

/// Distances with the largest per knot span of the surface, for refinement.
#[derive(Debug, Clone)]
pub(crate) struct Measured {
    pub deviation: Deviation,
    pub span_u: Vec<f64>,
    pub span_v: Vec<f64>,
}

/// Measures `surface` against `samples`, every sample farther than
/// `tolerance` by its parameters measured to its foot point (module docs);
/// with `field`, also writes every distance.
pub(crate) fn measure(
    surface: &BSplineSurface,
    samples: &Samples,
    tolerance: f64,
    field: Option<&mut Vec<f64>>,
) -> Measured {
    match surface.knots_u.degree() {
        2 => measure_p::<2>(surface, samples, tolerance, field),
        3 => measure_p::<3>(surface, samples, tolerance, field),
        4 => measure_p::<4>(surface, samples, tolerance, field),
        _ => measure_p::<5>(surface, samples, tolerance, field),
    }
}

/// Points up to this many tolerances away by their parameters are measured
/// to their foot points; farther ones are over by any measure worth the
/// time (a parameter slide of a sample spacing is a few tolerances where a
/// fit passes; a fit far off has most of its points there, and a foot point
/// each cost as much as the whole parametric measure).
const FOOT_RANGE: f64 = 32.0;

/// Four sample spacings either side of parameter `i` of `params`.
fn window(params: &[f64], i: usize) -> (f64, f64) {
    let before = if i > 0 {
        params[i] - params[i - 1]
    } else {
        0.0
    };
    let after = if i + 1 < params.len() {
        params[i + 1] - params[i]
    } else {
        0.0
    };
    let w = 4.0 * before.max(after);
    ((params[i] - w).max(0.0), (params[i] + w).min(1.0))
}

/// The distance from `q` to the surface point nearest it near `(u, v)`:
/// Newton's iteration on `(F − q)·F_u = (F − q)·F_v = 0` (derivatives by
/// central differences), the parameters kept inside `wu × wv`; the least
/// distance met, never more than `start` (the distance at `(u, v)`).
pub(crate) fn foot_distance(
    surface: &BSplineSurface,
    q: DVec3,
    (mut u, mut v): (f64, f64),
    wu: (f64, f64),
    wv: (f64, f64),
    start: f64,
) -> f64 {
    let h = 1e-7;
    let mut best = start;
    for _ in 0..8 {
        let (u0, u1) = ((u - h).max(0.0), (u + h).min(1.0));
        let (v0, v1) = ((v - h).max(0.0), (v + h).min(1.0));
        let fu = (surface.eval(u1, v) - surface.eval(u0, v)) / (u1 - u0);
        let fv = (surface.eval(u, v1) - surface.eval(u, v0)) / (v1 - v0);
        let r = surface.eval(u, v) - q;
        let (a, b, c) = (fu.dot(fu), fu.dot(fv), fv.dot(fv));
        let (gu, gv) = (fu.dot(r), fv.dot(r));
        let det = a * c - b * b;
        if !(det > 0.0 && det.is_finite()) {
            break;
        }
        let du = (c * gu - b * gv) / det;
        let dv = (a * gv - b * gu) / det;
        let (nu, nv) = ((u - du).clamp(wu.0, wu.1), (v - dv).clamp(wv.0, wv.1));
        let d = (surface.eval(nu, nv) - q).length();
        if !(d.is_finite()) {
            break;
        }
        best = best.min(d);
        let moved = (nu - u).abs() + (nv - v).abs();
        (u, v) = (nu, nv);
        if moved < 1e-14 {
            break;
        }
    }
    best
}

/// [`measure`] for degree `P` in `u` (unrolled: it runs at every check sample).
fn measure_p<const P: usize>(
    surface: &BSplineSurface,
    samples: &Samples,
    tolerance: f64,
    mut field: Option<&mut Vec<f64>>,
) -> Measured {
    debug_assert_eq!(surface.knots_u.degree(), P);
    let tu = BasisTable::new(&surface.knots_u, &samples.u);
    let mut span_u = vec![0.0f64; surface.knots_u.spans()];
    let mut span_v = vec![0.0f64; surface.knots_v.spans()];
    let (mut max, mut sum, mut at) = (0.0f64, 0.0, (0, 0));
    let mut curve = Vec::with_capacity(surface.poles.cols());
    if let Some(f) = field.as_deref_mut() {
        f.clear();
    }
    for (j, &v) in samples.v.iter().enumerate() {
        surface.curve_at_into(v, &mut curve);
        let row = samples.points.row(j);
        let (mut row_max, mut row_at) = (0.0f64, 0);
        for (i, ((first, b), q)) in tu.rows.iter().zip(row).enumerate() {
            let c = &curve[*first..*first + P + 1];
            let mut pt = c[0] * b[0];
            for a in 1..=P {
                pt += c[a] * b[a];
            }
            let mut d = (pt - *q).length();
            if d > tolerance && d <= FOOT_RANGE * tolerance {
                let wu = window(&samples.u, i);
                let wv = window(&samples.v, j);
                d = foot_distance(surface, *q, (samples.u[i], v), wu, wv, d);
            }
            sum += d;
            if d > row_max {
                row_max = d;
                row_at = i;
            }
            let su = &mut span_u[*first];
            *su = su.max(d);
            if let Some(f) = field.as_deref_mut() {
                f.push(d);
            }
        }
        if row_max > max {
            max = row_max;
            at = (j, row_at);
        }
        let sv = &mut span_v[surface.knots_v.span(v)];
        *sv = sv.max(row_max);
    }
    let n = samples.points.data().len() as f64;
    Measured {
        deviation: Deviation {
            max,
            mean: sum / n,
            at,
        },
        span_u,
        span_v,
    }
}

/// Largest and mean parametric distance from `samples` to `surface`.
pub fn deviation(surface: &BSplineSurface, samples: &Samples) -> Deviation {
    measure(surface, samples, f64::INFINITY, None).deviation
}

/// Largest and mean distance from `samples` to `surface`, every sample
/// farther than `tolerance` by its parameters measured to its foot point
/// (module docs): what a fit within `tolerance` is judged by.
pub fn deviation_within(surface: &BSplineSurface, samples: &Samples, tolerance: f64) -> Deviation {
    measure(surface, samples, tolerance, None).deviation
}

/// The parametric distance at every sample (the deviation map), shaped like the samples.
pub fn deviation_field(surface: &BSplineSurface, samples: &Samples) -> Grid<f64> {
    let mut f = Vec::with_capacity(samples.points.data().len());
    measure(surface, samples, f64::INFINITY, Some(&mut f));
    Grid::new(samples.points.rows(), samples.points.cols(), f).expect("one per sample")
}
