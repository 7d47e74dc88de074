//! Distances between a reference and points or a mesh (`docs/math.md §12`,
//! "Deviation, both ways").
//!
//! * A point to the reference: from the nearest of a dense sample of the
//!   reference (a k-d tree), Gauss–Newton on `|R(u, v) − p|²` with the
//!   parameters kept in the domain (a coordinate at its bound whose step
//!   points out is held there) and the step halved until the distance falls
//!   (eq. 12.6). The answer is never more than the distance to the nearest
//!   sample, and is the distance to the closest point where the Newton
//!   iteration converges to it (always, for points within the reference's
//!   smallest radius of curvature of it).
//! * A point to a design's mesh: the smallest distance to the triangles
//!   around the mesh position it is expected at (eq. 12.7).

use super::error::ReferenceFitError;
use super::reference::ReferenceSurface;
use glam::DVec3;

/// Largest and mean of a set of distances.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Distances {
    /// The largest distance.
    pub max: f64,
    /// The mean distance.
    pub mean: f64,
}

impl Distances {
    /// Of a list (zero for none).
    pub fn of(d: &[f64]) -> Self {
        if d.is_empty() {
            return Distances::default();
        }
        Distances {
            max: d.iter().copied().fold(0.0, f64::max),
            mean: d.iter().sum::<f64>() / d.len() as f64,
        }
    }
}

/// Gauss–Newton iterations at most per closest point.
const NEWTON_STEPS: usize = 12;

/// The closest point of `r` to `p` from the start `(u, v)`: `(distance, u,
/// v)`. Stops when a step moves the surface point by no more than `stop`.
pub(crate) fn refine_closest(
    r: &dyn ReferenceSurface,
    p: DVec3,
    u: f64,
    v: f64,
    du: [f64; 2],
    dv: [f64; 2],
    stop: f64,
) -> (f64, f64, f64) {
    refine_closest_steps(r, p, u, v, du, dv, stop, NEWTON_STEPS)
}

/// [`refine_closest`] with at most `steps` Gauss–Newton steps: with one,
/// a first estimate (never less than the distance found with more), from
/// whose `(u, v)` [`refine_closest`] goes on as it would have.
#[allow(clippy::too_many_arguments)]
pub(crate) fn refine_closest_steps(
    r: &dyn ReferenceSurface,
    p: DVec3,
    u: f64,
    v: f64,
    du: [f64; 2],
    dv: [f64; 2],
    stop: f64,
    steps: usize,
) -> (f64, f64, f64) {
    let (mut u, mut v) = (u.clamp(du[0], du[1]), v.clamp(dv[0], dv[1]));
    let [mut s, mut su, mut sv] = r.derivatives(u, v);
    let mut d2 = (p - s).length_squared();
    let eps_u = 1e-15 * (du[1] - du[0]);
    let eps_v = 1e-15 * (dv[1] - dv[0]);
    for _ in 0..steps {
        let e = p - s;
        let (a11, a12, a22) = (su.dot(su), su.dot(sv), sv.dot(sv));
        let (b1, b2) = (su.dot(e), sv.dot(e));
        let hold_u = (u <= du[0] && b1 < 0.0) || (u >= du[1] && b1 > 0.0);
        let hold_v = (v <= dv[0] && b2 < 0.0) || (v >= dv[1] && b2 > 0.0);
        let (mut x, mut y) = (0.0, 0.0);
        let det = a11 * a22 - a12 * a12;
        match (hold_u, hold_v) {
            (true, true) => break,
            (true, false) => {
                if a22 > 0.0 {
                    y = b2 / a22;
                }
            }
            (false, true) => {
                if a11 > 0.0 {
                    x = b1 / a11;
                }
            }
            (false, false) => {
                if det > 1e-14 * a11 * a22 && det > 0.0 {
                    x = (b1 * a22 - b2 * a12) / det;
                    y = (a11 * b2 - a12 * b1) / det;
                } else if a11 >= a22 && a11 > 0.0 {
                    x = b1 / a11;
                } else if a22 > 0.0 {
                    y = b2 / a22;
                }
            }
        }
        if !(x.is_finite() && y.is_finite()) {
            break;
        }
        let mut step = 1.0;
        let mut moved = false;
        for _ in 0..8 {
            let nu = (u + step * x).clamp(du[0], du[1]);
            let nv = (v + step * y).clamp(dv[0], dv[1]);
            let [ns, nsu, nsv] = r.derivatives(nu, nv);
            let nd2 = (p - ns).length_squared();
            if nd2 <= d2 {
                let small = ((nu - u).abs() <= eps_u && (nv - v).abs() <= eps_v)
                    || (ns - s).length() <= stop;
                (u, v, s, su, sv, d2) = (nu, nv, ns, nsu, nsv, nd2);
                moved = !small;
                break;
            }
            step *= 0.5;
        }
        if !moved {
            break;
        }
    }
    (d2.sqrt(), u, v)
}

/// A static k-d tree over points (median splits, leaves of up to 8).
#[derive(Debug, Clone)]
struct KdTree {
    points: Vec<DVec3>,
    /// Original index of each point, in tree order.
    index: Vec<u32>,
    /// Split axis of the node whose median sits at this position.
    axis: Vec<u8>,
}

const LEAF: usize = 8;

impl KdTree {
    fn new(points: &[DVec3]) -> Self {
        let mut order: Vec<u32> = (0..points.len() as u32).collect();
        let mut axis = vec![0u8; points.len()];
        Self::build(points, &mut order, &mut axis, 0);
        let sorted = order.iter().map(|&i| points[i as usize]).collect();
        KdTree {
            points: sorted,
            index: order,
            axis,
        }
    }

    fn build(points: &[DVec3], idx: &mut [u32], axis: &mut [u8], offset: usize) {
        let n = idx.len();
        if n <= LEAF {
            return;
        }
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for &i in idx.iter() {
            lo = lo.min(points[i as usize]);
            hi = hi.max(points[i as usize]);
        }
        let ext = hi - lo;
        let a = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        let mid = n / 2;
        idx.select_nth_unstable_by(mid, |&i, &j| {
            points[i as usize][a].total_cmp(&points[j as usize][a])
        });
        axis[offset + mid] = a as u8;
        let (left, right) = idx.split_at_mut(mid);
        Self::build(points, left, axis, offset);
        Self::build(points, &mut right[1..], axis, offset + mid + 1);
    }

    /// The nearest point's original index and squared distance.
    fn nearest(&self, q: DVec3) -> (usize, f64) {
        let mut best = (0usize, f64::INFINITY);
        self.search(q, 0, self.points.len(), &mut best);
        (self.index.get(best.0).map_or(0, |&i| i as usize), best.1)
    }

    fn search(&self, q: DVec3, lo: usize, hi: usize, best: &mut (usize, f64)) {
        let n = hi - lo;
        if n == 0 {
            return;
        }
        if n <= LEAF {
            for i in lo..hi {
                let d = (self.points[i] - q).length_squared();
                if d < best.1 {
                    *best = (i, d);
                }
            }
            return;
        }
        let mid = lo + n / 2;
        let p = self.points[mid];
        let d = (p - q).length_squared();
        if d < best.1 {
            *best = (mid, d);
        }
        let a = self.axis[mid] as usize;
        let diff = q[a] - p[a];
        let (first, second) = if diff < 0.0 {
            ((lo, mid), (mid + 1, hi))
        } else {
            ((mid + 1, hi), (lo, mid))
        };
        self.search(q, first.0, first.1, best);
        if diff * diff < best.1 {
            self.search(q, second.0, second.1, best);
        }
    }
}

/// The reference a [`ClosestPoints`] measures against: borrowed (a fit, a
/// measurement that ends with the caller) or shared (an index kept while the
/// design changes, as the editor's map keeps it).
enum Held<'a> {
    Borrowed(&'a dyn ReferenceSurface),
    Shared(std::sync::Arc<dyn ReferenceSurface + Send>),
}

impl Held<'_> {
    fn get(&self) -> &dyn ReferenceSurface {
        match self {
            Held::Borrowed(r) => *r,
            Held::Shared(r) => r.as_ref(),
        }
    }
}

/// The closest points of a reference: a dense sample in a k-d tree, then
/// Gauss–Newton (eq. 12.6). Build once, query often (the editor's
/// deviation map).
pub struct ClosestPoints<'a> {
    reference: Held<'a>,
    du: [f64; 2],
    dv: [f64; 2],
    params: Vec<(f64, f64)>,
    tree: KdTree,
    /// Newton stops when a step moves the surface point by no more than
    /// this ([`NEWTON_STOP`] of the samples' diagonal).
    stop: f64,
}

/// Newton on a closest point stops once a step moves the surface point by
/// this fraction of the reference's size: the step after it would move it by
/// about the distance over the radius of curvature times as much, and the
/// distance by the square of that (far below 1e-12 of the distance).
pub const NEWTON_STOP: f64 = 1e-7;

/// Samples per direction of [`ClosestPoints`]: 16 per knot span, at least
/// 64 and at most 256.
fn sample_params(range: [f64; 2], breaks: &[f64]) -> Vec<f64> {
    let n = (16 * (breaks.len() + 1)).clamp(64, 256);
    let ends = super::reference::panels(range, breaks, n);
    // `panels` puts at least `n` equal pieces in every span
    ends
}

impl<'a> ClosestPoints<'a> {
    /// Samples `reference` (about 64 to 256 points per direction, by its knot
    /// spans). A domain that is empty or not finite, or a non-finite point,
    /// is an error.
    pub fn new(reference: &'a dyn ReferenceSurface) -> Result<Self, ReferenceFitError> {
        Self::build(Held::Borrowed(reference))
    }

    fn build(held: Held<'a>) -> Result<Self, ReferenceFitError> {
        let reference = held.get();
        let (du, dv) = reference.domain();
        for (direction, d) in [('u', du), ('v', dv)] {
            if !(d[0].is_finite() && d[1].is_finite() && d[1] > d[0]) {
                return Err(ReferenceFitError::EmptyDomain { direction });
            }
        }
        let us = sample_params(du, &reference.breaks_u());
        let vs = sample_params(dv, &reference.breaks_v());
        let mut points = Vec::with_capacity(us.len() * vs.len());
        let mut params = Vec::with_capacity(us.len() * vs.len());
        for &v in &vs {
            for &u in &us {
                let p = reference.point(u, v);
                if !p.is_finite() {
                    return Err(ReferenceFitError::NonFinite { what: "point" });
                }
                points.push(p);
                params.push((u, v));
            }
        }
        let (lo, hi) = points.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        Ok(ClosestPoints {
            reference: held,
            du,
            dv,
            params,
            tree: KdTree::new(&points),
            stop: NEWTON_STOP * (hi - lo).length(),
        })
    }

    /// [`Self::new`] on a reference it keeps, for an index that outlives
    /// the caller's borrow (the editor keeps one in a resource).
    pub fn shared(
        reference: std::sync::Arc<dyn ReferenceSurface + Send>,
    ) -> Result<ClosestPoints<'static>, ReferenceFitError> {
        ClosestPoints::build(Held::Shared(reference))
    }

    /// The reference measured against.
    pub fn reference(&self) -> &dyn ReferenceSurface {
        self.reference.get()
    }

    /// Number of samples.
    pub fn samples(&self) -> usize {
        self.params.len()
    }

    /// The distance from `p` to the reference and the parameters `(u, v)`
    /// of the closest point found. A non-finite `p` gives an infinite distance.
    pub fn closest(&self, p: DVec3) -> (f64, f64, f64) {
        if !p.is_finite() {
            return (f64::INFINITY, self.du[0], self.dv[0]);
        }
        let (i, d2) = self.tree.nearest(p);
        let (u, v) = self
            .params
            .get(i)
            .copied()
            .unwrap_or((self.du[0], self.dv[0]));
        let (d, nu, nv) =
            refine_closest(self.reference.get(), p, u, v, self.du, self.dv, self.stop);
        if d <= d2.sqrt() {
            (d, nu, nv)
        } else {
            (d2.sqrt(), u, v)
        }
    }

    /// The distance from every point to the reference (on two threads for
    /// large inputs).
    pub fn distances(&self, points: &[DVec3]) -> Vec<f64> {
        let mut out = vec![0.0; points.len()];
        let work = |pts: &[DVec3], out: &mut [f64]| {
            for (o, p) in out.iter_mut().zip(pts) {
                *o = self.closest(*p).0;
            }
        };
        if points.len() < 2048 {
            work(points, &mut out);
        } else {
            let h = points.len() / 2;
            let (pa, pb) = points.split_at(h);
            let (oa, ob) = out.split_at_mut(h);
            crate::parallel::join(|| work(pa, oa), || work(pb, ob));
        }
        out
    }
}

/// The distance from every point to `reference` (builds a
/// [`ClosestPoints`]; keep one to query again).
pub fn distances_to_reference(
    reference: &dyn ReferenceSurface,
    points: &[DVec3],
) -> Result<Vec<f64>, ReferenceFitError> {
    Ok(ClosestPoints::new(reference)?.distances(points))
}

/// The distance from `p` to the triangle `a b c` (Ericson, *Real-Time
/// Collision Detection*, §5.1.5).
pub(crate) fn point_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let t = d1 / (d1 - d3);
        return (ap - ab * t).length();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let t = d2 / (d2 - d6);
        return (ap - ac * t).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (bp - (c - b) * t).length();
    }
    let denom = va + vb + vc;
    if denom.is_nan() || denom.abs() <= 0.0 {
        // a degenerate triangle: its edges
        return [(a, b), (b, c), (c, a)]
            .iter()
            .map(|&(x, y)| point_segment(p, x, y))
            .fold(f64::INFINITY, f64::min);
    }
    let (v, w) = (vb / denom, vc / denom);
    (p - (a + ab * v + ac * w)).length()
}

fn point_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let l = ab.length_squared();
    let t = if l > 0.0 {
        ((p - a).dot(ab) / l).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).length()
}

/// The distance from `p` to the triangles of the `rows × width` point grid
/// (split as the surface mesh splits its quads) in the cells within
/// `radius` of cell `(r, k)`.
pub(crate) fn mesh_distance_near(
    points: &[DVec3],
    rows: usize,
    width: usize,
    p: DVec3,
    r: usize,
    k: usize,
    radius: usize,
) -> f64 {
    if rows < 2 || width < 2 {
        return points
            .iter()
            .map(|q| q.distance(p))
            .fold(f64::INFINITY, f64::min);
    }
    let r0 = r.saturating_sub(radius).min(rows - 2);
    let r1 = (r + radius).min(rows - 2);
    let k0 = k.saturating_sub(radius).min(width - 2);
    let k1 = (k + radius).min(width - 2);
    let mut best = f64::INFINITY;
    for i in r0..=r1 {
        for j in k0..=k1 {
            let a = points[i * width + j];
            let b = points[i * width + j + 1];
            let d = points[(i + 1) * width + j];
            let e = points[(i + 1) * width + j + 1];
            best = best.min(point_triangle(p, a, b, d));
            best = best.min(point_triangle(p, b, e, d));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kd_tree_nearest_is_the_brute_force_nearest() {
        let mut pts = Vec::new();
        let mut x = 0.3f64;
        for _ in 0..5000 {
            x = (x * 9301.0 + 0.49297).fract();
            let y = (x * 7.13).fract();
            let z = (x * 3.7 + y).fract();
            pts.push(DVec3::new(x, y * 0.5, z * 0.1));
        }
        let tree = KdTree::new(&pts);
        for q in pts
            .iter()
            .step_by(37)
            .map(|p| *p + DVec3::new(0.01, -0.02, 0.003))
        {
            let (i, d2) = tree.nearest(q);
            let want = pts
                .iter()
                .map(|p| (*p - q).length_squared())
                .fold(f64::INFINITY, f64::min);
            assert_eq!(d2, want);
            assert_eq!((pts[i] - q).length_squared(), want);
        }
    }
}
