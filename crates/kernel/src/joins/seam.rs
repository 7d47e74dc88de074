//! The seam report (docs/math.md §11.3, Eqs. 74–75): for a join at one depth,
//! measured on the two meshes, the largest gap, the largest normal angle and
//! the curvature deviation `(κ_A − κ_B)/(|κ_A| + |κ_B|)` of the normal
//! curvature across the seam (Alias's measure; 0 where both are flat).

use crate::analysis::angle_between;
use crate::grid::Grid;
use crate::joins::error::JoinError;
use crate::joins::kinds::Edge;
use crate::joins::stack::Stack;
use glam::DVec3;

/// Turning angles (radians) at most this large on both sides count as flat:
/// the curvature deviation is 0 there.
pub const FLAT_TURN: f64 = 1e-12;

/// A patch's mesh at one depth: its point grid and its vertex normals
/// (row-major, as [`crate::streamline::surface_mesh::SurfaceMesh`] has them).
#[derive(Debug, Clone, Copy)]
pub struct PatchMesh<'a> {
    /// `rows × points per row`.
    pub points: &'a Grid<DVec3>,
    /// One unit normal per point.
    pub normals: &'a [DVec3],
}

impl PatchMesh<'_> {
    fn normal(&self, r: usize, c: usize) -> DVec3 {
        self.normals[r * self.points.cols() + c]
    }
}

/// The measures at one seam point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeamSample {
    /// Distance between `B`'s start point and `A`'s edge.
    pub gap: f64,
    /// Angle between the two normals, degrees.
    pub angle_deg: f64,
    /// `(κ_A − κ_B)/(|κ_A| + |κ_B|)`, in `[−1, 1]`.
    pub curvature_dev: f64,
}

/// A seam's measures: the largest of each over its points, and the points'.
#[derive(Debug, Clone, PartialEq)]
pub struct SeamReport {
    /// The largest gap.
    pub gap: f64,
    /// The largest normal angle, degrees.
    pub angle_deg: f64,
    /// The curvature deviation largest in size (with its sign).
    pub curvature_dev: f64,
    /// One sample per row of `B`.
    pub samples: Vec<SeamSample>,
}

impl SeamReport {
    fn from_samples(samples: Vec<SeamSample>) -> Self {
        let gap = samples.iter().fold(0.0, |m, s| s.gap.max(m));
        let angle_deg = samples.iter().fold(0.0, |m, s| s.angle_deg.max(m));
        let curvature_dev = samples.iter().fold(0.0f64, |m, s| {
            if s.curvature_dev.abs() > m.abs() {
                s.curvature_dev
            } else {
                m
            }
        });
        SeamReport {
            gap,
            angle_deg,
            curvature_dev,
            samples,
        }
    }
}

/// The seam of `B` joined to `A` on `edge`, on both patches' meshes at depth `d`.
pub fn seam_at(a: &Stack, b: &Stack, edge: Edge, d: u32) -> Result<SeamReport, JoinError> {
    let (ma, mb) = (a.mesh(d), b.mesh(d));
    let pa = PatchMesh {
        points: &a.points[d as usize],
        normals: &ma.normals,
    };
    let pb = PatchMesh {
        points: &b.points[d as usize],
        normals: &mb.normals,
    };
    match edge {
        Edge::End => chain_seam(pa, pb),
        side => Ok(side_seam(pa, side, pb)),
    }
}

/// A chain's seam (Eq. 74): row `j`'s gap `|A(j, last) − B(j, 0)|`, the angle
/// between the two meshes' normals there (oriented: a chain keeps the
/// winding), and the normal curvature of `A`'s last and `B`'s first turn of
/// the streamline (Eq. 75) about the mean of the two normals.
pub fn chain_seam(a: PatchMesh, b: PatchMesh) -> Result<SeamReport, JoinError> {
    let (ra, rb) = (a.points.rows(), b.points.rows());
    if ra != rb {
        return Err(JoinError::ChainRowCount { a: ra, b: rb });
    }
    let last = a.points.cols() - 1;
    let samples = (0..ra)
        .map(|j| {
            let (pa, pb) = (a.points.row(j), b.points.row(j));
            let (na, nb) = (a.normal(j, last), b.normal(j, 0));
            let n = (na + nb).try_normalize().unwrap_or(na);
            let ka = normal_curvature(pa[last - 2], pa[last - 1], pa[last], n);
            let kb = normal_curvature(pb[0], pb[1], pb[2], n);
            SeamSample {
                gap: (pa[last] - pb[0]).length(),
                angle_deg: angle_between(na, nb).to_degrees(),
                curvature_dev: deviation(ka, kb),
            }
        })
        .collect();
    Ok(SeamReport::from_samples(samples))
}

/// A side seam (Eq. 74): for each row of `B`, the distance from its start
/// point to `A`'s edge polyline and `A`'s normal there (its mesh normals at
/// the nearest segment's ends, linear between); the angle between that and
/// `B`'s normal as lines (a side patch's winding is its own); the normal
/// curvature of `B`'s first turn and of `A`'s cross curve (its columns'
/// last turn towards the edge, linear along the segment), both about `A`'s
/// normal (Eq. 75). A patch of two rows has no cross curvature (0).
pub fn side_seam(a: PatchMesh, edge: Edge, b: PatchMesh) -> SeamReport {
    let rows = a.points.rows();
    let (r0, r1, r2) = match edge {
        Edge::Last => (rows - 1, rows.saturating_sub(2), rows.saturating_sub(3)),
        _ => (0, 1.min(rows - 1), 2.min(rows - 1)),
    };
    let row = a.points.row(r0);
    let edge_line = Polyline::new(row);
    let mut hint = 0;
    let samples = (0..b.points.rows())
        .map(|j| {
            let pb = b.points.row(j);
            let (k, lambda, gap) = edge_line.nearest(pb[0], hint);
            hint = k;
            let lerp = |x: DVec3, y: DVec3| x * (1.0 - lambda) + y * lambda;
            let na = lerp(a.normal(r0, k), a.normal(r0, k + 1))
                .try_normalize()
                .unwrap_or(a.normal(r0, k));
            let angle = angle_between(na, b.normal(j, 0));
            let cross = |c: usize| {
                let p = |r: usize| a.points.get(r, c);
                if rows < 3 {
                    (0.0, 0.0)
                } else {
                    normal_curvature(p(r2), p(r1), p(r0), na)
                }
            };
            let (c0, c1) = (cross(k), cross(k + 1));
            let ka = (
                c0.0 * (1.0 - lambda) + c1.0 * lambda,
                c0.1 * (1.0 - lambda) + c1.1 * lambda,
            );
            let kb = normal_curvature(pb[0], pb[1], pb[2], na);
            SeamSample {
                gap,
                angle_deg: angle.min(std::f64::consts::PI - angle).to_degrees(),
                curvature_dev: deviation(ka, kb),
            }
        })
        .collect();
    SeamReport::from_samples(samples)
}

/// The segment of polyline `row` nearest `q`, the fraction along it and
/// the distance: the first of the nearest segments, scanning them all.
#[cfg(test)]
fn nearest(row: &[DVec3], q: DVec3) -> (usize, f64, f64) {
    let mut best = (0, 0.0, f64::INFINITY);
    for k in 0..row.len().saturating_sub(1) {
        let c = to_segment(row, k, q);
        if c.2 < best.2 {
            best = c;
        }
    }
    best
}

/// Segment `k` of polyline `row` (from point `k` to `k + 1`): the
/// fraction along it of the point nearest `q`, and its distance, as
/// `(k, fraction, distance)`.
#[inline]
fn to_segment(row: &[DVec3], k: usize, q: DVec3) -> (usize, f64, f64) {
    let (w0, w1) = (row[k], row[k + 1]);
    let e = w1 - w0;
    let len2 = e.length_squared();
    let lambda = if len2 > 0.0 {
        ((q - w0).dot(e) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (k, lambda, (w0 + e * lambda - q).length())
}

/// A polyline's segments as balls (midpoint, half length), for many
/// nearest-segment queries: a side seam asks one per row of `B` (257 rows
/// on a 258-point edge for hood-screen-wing at depth 6: 0.5 ms a frame
/// scanned in full, 0.14 ms so). The balls are also grouped in runs of
/// [`BLOCK`], each with a ball about its midpoints, so that a query passes
/// over a far run in one test.
struct Polyline<'a> {
    row: &'a [DVec3],
    /// Each segment's midpoint and half length.
    balls: Vec<(DVec3, f64)>,
    /// Each run of [`BLOCK`] balls: a centre, the largest distance from it
    /// to a midpoint of the run, and the run's largest half length.
    blocks: Vec<(DVec3, f64, f64)>,
    /// The largest coordinate's magnitude, for the rounding margin.
    scale: f64,
}

/// How many segments a run of [`Polyline::blocks`] holds.
const BLOCK: usize = 16;

impl<'a> Polyline<'a> {
    fn new(row: &'a [DVec3]) -> Self {
        let balls: Vec<(DVec3, f64)> = row
            .windows(2)
            .map(|w| ((w[0] + w[1]) * 0.5, (w[1] - w[0]).length() * 0.5))
            .collect();
        let blocks = balls
            .chunks(BLOCK)
            .map(|run| {
                let (lo, hi) = run.iter().fold(
                    (DVec3::INFINITY, DVec3::NEG_INFINITY),
                    |(lo, hi), &(m, _)| (lo.min(m), hi.max(m)),
                );
                let centre = (lo + hi) * 0.5;
                let radius = (run.iter()).fold(0.0f64, |r, &(m, _)| r.max((m - centre).length()));
                let half = run.iter().fold(0.0f64, |h, &(_, l)| h.max(l));
                (centre, radius, half)
            })
            .collect();
        let scale = row.iter().fold(0.0f64, |m, p| m.max(p.abs().max_element()));
        Polyline {
            row,
            balls,
            blocks,
            scale,
        }
    }

    /// What the full scan ([`nearest`] in the tests) finds, bit for bit: the
    /// first nearest segment, its fraction and distance. Segment `hint`'s
    /// distance `d` bounds the nearest one's; a segment whose ball lies
    /// farther than `d` from `q` (its distance is at least
    /// `|q − midpoint| − half length`), with a margin far above the
    /// rounding of either distance, is farther than the nearest and is
    /// passed over; every other one is measured as the full scan measures
    /// it, in the same order, so the first nearest is the same segment.
    /// A run of balls is passed over whole only where each of its balls
    /// would be: `q` lies farther from the run's centre, less its radius,
    /// than the largest of their reaches by a margin far above the rounding
    /// of the centre and radius (a NaN or infinite distance passes over
    /// none, as the balls' own tests do).
    fn nearest(&self, q: DVec3, hint: usize) -> (usize, f64, f64) {
        let n = self.balls.len();
        if n == 0 {
            return (0, 0.0, f64::INFINITY);
        }
        let bound = to_segment(self.row, hint.min(n - 1), q).2;
        // distances are computed to within a few ulps of the coordinates
        // (an absolute error) and of themselves (a relative one)
        let slack = 1e-9 * self.scale.max(q.abs().max_element());
        let mut best = (0, 0.0, f64::INFINITY);
        for b in 0..self.blocks.len() {
            if self.run_is_far(b, q, bound, slack) {
                continue;
            }
            let first = b * BLOCK;
            for (k, &(mid, half)) in self.balls.iter().enumerate().skip(first).take(BLOCK) {
                let reach = (bound + half) * (1.0 + 1e-9) + slack;
                if (q - mid).length_squared() > reach * reach {
                    continue;
                }
                let c = to_segment(self.row, k, q);
                if c.2 < best.2 {
                    best = c;
                }
            }
        }
        best
    }

    /// Whether every ball of run `b` lies farther from `q` than its reach
    /// from the bound `bound` ([`Self::nearest`]), with a margin.
    fn run_is_far(&self, b: usize, q: DVec3, bound: f64, slack: f64) -> bool {
        let (centre, radius, largest) = self.blocks[b];
        let far = (q - centre).length() - radius;
        far > ((bound + largest) * (1.0 + 1e-9) + slack) * (1.0 + 1e-6) + slack
    }
}

/// The turn of the polyline `p0 → p1 → p2` towards `n` and its normal
/// curvature (Eq. 75): `θ = (u₂ − u₁)·n` for the unit segment directions,
/// `κ = 2θ/(|e₁| + |e₂|)` (the turn over the arc length between the segments'
/// middles). A zero segment gives `(0, 0)`.
pub fn normal_curvature(p0: DVec3, p1: DVec3, p2: DVec3, n: DVec3) -> (f64, f64) {
    let (e1, e2) = (p1 - p0, p2 - p1);
    let (l1, l2) = (e1.length(), e2.length());
    if l1 == 0.0 || l2 == 0.0 || !(l1 + l2).is_finite() {
        return (0.0, 0.0);
    }
    let turn = (e2 / l2 - e1 / l1).dot(n);
    (turn, 2.0 * turn / (l1 + l2))
}

/// `(κ_A − κ_B)/(|κ_A| + |κ_B|)` from `(turn, κ)` pairs; 0 where both turns are
/// at most [`FLAT_TURN`].
fn deviation((ta, ka): (f64, f64), (tb, kb): (f64, f64)) -> f64 {
    if ta.abs() <= FLAT_TURN && tb.abs() <= FLAT_TURN {
        return 0.0;
    }
    (ka - kb) / (ka.abs() + kb.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A polyline of up to 60 points about `scale` (a random walk, every
    /// seventh step zero, every seventh from the fifth back onto an earlier
    /// point), and queries on each segment, at its start, a hair off it and
    /// far from it.
    fn polyline() -> impl Strategy<Value = (Vec<DVec3>, Vec<DVec3>, f64)> {
        let unit = || prop::array::uniform3(-1.0f64..1.0).prop_map(DVec3::from_array);
        (
            -6i32..7,
            unit(),
            prop::collection::vec((unit(), 0.0f64..1.0, unit(), unit()), 1..60),
        )
            .prop_map(|(e, start, steps)| {
                let scale = 10f64.powi(e);
                let mut row = vec![start * scale];
                for (i, (step, ..)) in steps.iter().enumerate() {
                    let p = match (i + 1) % 7 {
                        3 => row[i],
                        5 => row[i.div_ceil(2)],
                        _ => row[i] + *step * scale * 0.3,
                    };
                    row.push(p);
                }
                let mut queries = Vec::new();
                for (k, &(_, t, hair, far)) in steps.iter().enumerate() {
                    let on = row[k].lerp(row[k + 1], t);
                    queries.extend([on, row[k], on + hair * scale * 1e-9, on + far * scale * 2.0]);
                }
                (row, queries, scale)
            })
    }

    fn bits((k, l, d): (usize, f64, f64)) -> (usize, u64, u64) {
        (k, l.to_bits(), d.to_bits())
    }

    proptest! {
        /// The pruned search finds what the full scan finds, bit for bit,
        /// from any hint: on the polyline, at its points, a hair off it
        /// and far off it, with zero-length segments and points visited
        /// twice (ties), at scales from 1e-6 to 1e6.
        #[test]
        fn the_pruned_search_is_the_full_scan((row, queries, _) in polyline(), h in 0usize..80) {
            let line = Polyline::new(&row);
            for (i, &q) in queries.iter().enumerate() {
                let hint = (h + i) % (row.len() + 3);
                prop_assert_eq!(bits(line.nearest(q, hint)), bits(nearest(&row, q)), "query {}", i);
            }
        }
    }

    /// Control: the pruning passes over segments (else it would be the full
    /// scan by another name): on a long straight edge a query near its
    /// middle measures only a few of its segments.
    #[test]
    fn the_pruning_passes_over_far_segments() {
        let row: Vec<DVec3> = (0..513)
            .map(|i| DVec3::new(i as f64 * 0.01, 0.0, 0.0))
            .collect();
        let line = Polyline::new(&row);
        let q = DVec3::new(2.555, 0.001, 0.0);
        let bound = to_segment(&row, 255, q).2;
        let slack = 1e-9 * line.scale.max(q.abs().max_element());
        let measured = (line.balls.iter())
            .filter(|&&(mid, half)| {
                let reach = (bound + half) * (1.0 + 1e-9) + slack;
                (q - mid).length_squared() <= reach * reach
            })
            .count();
        assert!(measured <= 3, "{measured} segments measured");
        // and whole runs of them in one test each
        let runs = (0..line.blocks.len())
            .filter(|&b| !line.run_is_far(b, q, bound, slack))
            .count();
        assert!(runs <= 2, "{runs} runs of segments measured");
        assert_eq!(bits(line.nearest(q, 255)), bits(nearest(&row, q)));
        // NaN and infinite queries: as the full scan
        for q in [
            DVec3::NAN,
            DVec3::INFINITY,
            DVec3::new(1e308, -1e308, 1e308),
        ] {
            assert_eq!(bits(line.nearest(q, 7)), bits(nearest(&row, q)));
        }
    }
}
