//! Where a later face's rows lie on its parent and how a face of a shell is
//! measured (docs/math.md §11.5): a side-joined patch's start points placed
//! on its parent's edge row (its row parameter `w`), the shared `v` knots of
//! a chain, and the distance from a face's check samples to the shell near
//! it (the face, and the parent across its start edge).

use super::deviation::{Deviation, foot_distance, measure};
use super::samples::Samples;
use super::surface::BSplineSurface;
use crate::joins::Edge;
use glam::DVec3;

/// The parameter `u` at which `p` lies on the polyline `row` (points at
/// parameters `u`), and its distance to it.
fn on_polyline(row: &[DVec3], u: &[f64], p: DVec3) -> (f64, f64) {
    let mut best = (f64::INFINITY, 0.0);
    for k in 0..row.len() - 1 {
        let (a, b) = (row[k], row[k + 1]);
        let ab = b - a;
        let t = if ab.length_squared() > 0.0 {
            ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d = (a + ab * t - p).length();
        if d < best.0 {
            best = (d, u[k] + t * (u[k + 1] - u[k]));
        }
    }
    (best.1, best.0)
}

/// `b`'s start column's parameters on `a`'s edge row: `(w, u₀, u₁)`, or why not.
pub(super) fn side_params(
    a: &Samples,
    b: &Samples,
    edge: Edge,
) -> Result<(Vec<f64>, f64, f64), String> {
    let r = if edge == Edge::First {
        0
    } else {
        a.points.rows() - 1
    };
    let row = a.points.row(r);
    let scale = a.diagonal().max(f64::MIN_POSITIVE);
    let mut us = Vec::with_capacity(b.points.rows());
    let ends = (a.u[0], a.u[a.u.len() - 1]);
    for j in 0..b.points.rows() {
        let (u, d) = on_polyline(row, &a.u, b.points.get(j, 0));
        if d > 1e-9 * scale && (u == ends.0 || u == ends.1) {
            // past an end: the parent's streamline is shorter at this depth
            // than the row's `t` (an approximating scheme shortens it with
            // depth, docs/math.md §11.5)
            return Err(format!(
                "the later patch's row {j} starts {d:.3e} past the end of the earlier patch's {} streamline as sampled for the export; a Catmull–Clark or Doo–Sabin streamline gets shorter as it is sampled deeper, so keep the later patch's rows (its t) further inside it, or choose the Kobbelt scheme",
                edge.name()
            ));
        }
        if d > 1e-9 * scale {
            return Err(format!(
                "the later patch's row {j} starts {d:.3e} away from the earlier patch's {} streamline; build both with joins::join",
                edge.name()
            ));
        }
        us.push(u);
    }
    let (u0, u1) = (us[0], us[us.len() - 1]);
    let w: Vec<f64> = us.iter().map(|u| (u - u0) / (u1 - u0)).collect();
    if !w.windows(2).all(|x| x[1] > x[0]) || !(u1 - u0).is_finite() || u0 == u1 {
        return Err(format!(
            "the later patch's start points do not run one way along the earlier patch's {} streamline",
            edge.name()
        ));
    }
    Ok((w, u0, u1))
}

/// `b`'s check grid's `w`: its start points placed on `a`'s check edge row,
/// normalised by the data's `(u₀, u₁)` (clamped into `[0, 1]`).
pub(super) fn check_params(a: &Samples, b: &Samples, edge: Edge, u0: f64, u1: f64) -> Vec<f64> {
    let r = if edge == Edge::First {
        0
    } else {
        a.points.rows() - 1
    };
    let row = a.points.row(r);
    let mut w: Vec<f64> = (0..b.points.rows())
        .map(|j| ((on_polyline(row, &a.u, b.points.get(j, 0)).0 - u0) / (u1 - u0)).clamp(0.0, 1.0))
        .collect();
    let n = w.len();
    (w[0], w[n - 1]) = (0.0, 1.0);
    w
}

/// The union of the required knots (kept exactly) and the optional ones
/// (a face's own, which its points carry among themselves: a fit placed
/// them) farther than `gap` from every required knot, so that no span
/// between a required knot and an optional one is narrower than `gap`.
pub(super) fn merge_knots(required: &[f64], optional: &[f64], gap: f64) -> Vec<f64> {
    let mut req: Vec<f64> = required.to_vec();
    req.sort_by(f64::total_cmp);
    req.dedup();
    let mut kept = req.clone();
    for &k in optional {
        let at = req.partition_point(|x| *x < k);
        let clear = (at == 0 || k - req[at - 1] > gap) && (at == req.len() || req[at] - k > gap);
        if clear {
            kept.push(k);
        }
    }
    kept.sort_by(f64::total_cmp);
    kept.dedup();
    kept
}

/// Where a later face's parameters `(u, v)` near its start edge lie on its
/// parent face: a chain's `(1, v)`, a side join's `(u₀ + v (u₁ − u₀), edge)`.
#[derive(Debug, Clone, Copy)]
pub(super) enum ParentMap {
    Chain,
    Side(f64, (f64, f64)),
}

impl ParentMap {
    pub(super) fn start(self, v: f64) -> (f64, f64) {
        match self {
            ParentMap::Chain => (1.0, v),
            ParentMap::Side(edge, (u0, u1)) => (u0 + v * (u1 - u0), edge),
        }
    }
}

/// The distance from a face's check samples to the shell near it: each
/// sample farther than `tol` from the face (by its foot point,
/// [`super::deviation_within`]) is also measured to its foot point on the
/// parent face across the face's start edge. Where the subdivision moves a
/// seam with depth (an approximating scheme shortens `A`'s boundary
/// streamlines, and a G2 chain is cut at a column that moves by a fraction
/// of a leg per depth, docs/math.md §11.1), the check grid one depth finer
/// starts a strip of points beyond the data's seam, on the parent's side:
/// those points are the parent's surface, and measured on the face alone
/// their distance is the strip's width (halving per depth), not the fit's.
/// Returns the deviation and the largest distance per `u` and per `v` span
/// of the face.
pub(super) fn measure_face(
    surface: &BSplineSurface,
    check: &Samples,
    tol: f64,
    parent: Option<(&BSplineSurface, ParentMap)>,
) -> (Deviation, Vec<f64>, Vec<f64>) {
    let mut field = Vec::with_capacity(check.points.data().len());
    measure(surface, check, tol, Some(&mut field));
    let cols = check.points.cols();
    let mut span_u = vec![0.0f64; surface.knots_u.spans()];
    let mut span_v = vec![0.0f64; surface.knots_v.spans()];
    let row_span: Vec<usize> = check.v.iter().map(|v| surface.knots_v.span(*v)).collect();
    let (mut max, mut sum, mut at) = (0.0f64, 0.0, (0, 0));
    for (n, d) in field.iter_mut().enumerate() {
        let (j, i) = (n / cols, n % cols);
        if *d > tol
            && let Some((a, map)) = parent
        {
            let q = check.points.get(j, i);
            let start = map.start(check.v[j]);
            let here = (a.eval(start.0, start.1) - q).length();
            let foot = foot_distance(a, q, start, (0.0, 1.0), (0.0, 1.0), here);
            *d = d.min(foot);
        }
        sum += *d;
        if *d > max {
            max = *d;
            at = (j, i);
        }
        let s = &mut span_u[surface.knots_u.span(check.u[i])];
        *s = s.max(*d);
        let s = &mut span_v[row_span[j]];
        *s = s.max(*d);
    }
    let dev = Deviation {
        max,
        mean: sum / field.len() as f64,
        at,
    };
    (dev, span_u, span_v)
}
