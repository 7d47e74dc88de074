//! Measuring a fit (`docs/math.md §12`, "Deviation, both ways"): a built
//! mesh against the reference, every point from where its row's `t` and its
//! arc length expect it (eq. 12.6), with the cells' tangent-error scores
//! that say where to grow; and the reference, sampled at the same places
//! and the cells' centres, to the mesh (eq. 12.7).

use super::closest::{mesh_distance_near, refine_closest};
use super::construct::Nodes;
use super::error::ReferenceFitError;
use super::reference::{AnchorCurve, Frame, RowTable};
use crate::levels::design::Level;
use crate::streamline::integrate::point_arclength;
use glam::DVec3;

/// The measurements of one mesh row.
pub(super) struct RowResult {
    pub(super) dist: Vec<f64>,
    /// Of each measured point, the position error its row's tangent error
    /// explains: the angle × interval summed from the anchor to the point
    /// (a bound on the gap that the tangents alone open).
    pub(super) explained: Vec<f64>,
    /// Angle × interval of each level tangent.
    pub(super) contrib: Vec<f64>,
    /// Fraction of the row's length at each level tangent.
    pub(super) frac: Vec<f64>,
    pub(super) table: RowTable,
}

/// The measurement of a whole mesh.
pub(super) struct Measure {
    pub(super) dist: Vec<f64>,
    /// The furthest measured point: its row's `t / L_t`, its distance, and
    /// the part of it that its row's tangent error explains.
    pub(super) worst: (f64, f64, f64),
    /// Cell scores on node rows and between them, `rows − 1` × `cols − 1`.
    pub(super) on_nodes: Vec<Vec<f64>>,
    pub(super) between: Vec<Vec<f64>>,
    pub(super) tables: Vec<RowTable>,
}

pub(super) fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The interval of increasing `xs` holding `x` (clamped to the first and last).
pub(super) fn interval(xs: &[f64], x: f64) -> usize {
    xs.partition_point(|&v| v <= x)
        .saturating_sub(1)
        .min(xs.len().saturating_sub(2))
}

/// Runs `work` on every row index, on two threads.
pub(super) fn rows_parallel<T: Send>(
    rows: usize,
    work: &(dyn Fn(usize) -> Result<T, ReferenceFitError> + Sync),
) -> Result<Vec<T>, ReferenceFitError> {
    let h = rows / 2;
    let mut first: Vec<Result<T, ReferenceFitError>> = Vec::new();
    let mut second: Vec<Result<T, ReferenceFitError>> = Vec::new();
    crate::parallel::join(
        || first = (0..h).map(work).collect(),
        || second = (h..rows).map(work).collect(),
    );
    first.into_iter().chain(second).collect()
}

/// Measures a built mesh against the reference (eq. 12.6) and scores the cells.
#[allow(clippy::too_many_arguments)]
pub(super) fn measure(
    f: &Frame<'_>,
    anchor: &AnchorCurve,
    nodes: &Nodes,
    lt: f64,
    level: &Level,
    points: &[DVec3],
    stride: usize,
    stop: f64,
    anchor_fraction: f64,
) -> Result<Measure, ReferenceFitError> {
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
    let width = cols + 1;
    // the rows measured: every `stride`-th and the last
    let picked: Vec<usize> = (0..rows)
        .filter(|r| r % stride == 0 || r + 1 == rows)
        .collect();
    let work = |i: usize| -> Result<RowResult, ReferenceFitError> {
        let r = picked[i];
        let v = anchor.v_at(level.params.t[r]);
        let table = RowTable::new(f, v)?;
        let s = level.params.s.row(r);
        let (s0, span) = (s[0], s[cols - 1] - s[0]);
        let span = if span > 0.0 { span } else { 1.0 };
        let mut contrib = Vec::with_capacity(cols);
        let mut frac = Vec::with_capacity(cols);
        for k in (0..cols).step_by(stride) {
            let x = (s[k] - s0) / span;
            let d = f.r.derivatives(table.u_at(x), v)[1];
            let ds = 0.5 * (s[(k + stride).min(cols - 1)] - s[k.saturating_sub(stride)]);
            let a = d
                .try_normalize()
                .map_or(0.0, |t| angle(level.tangents.get(r, k), t));
            contrib.push(a * ds);
            frac.push(x);
        }
        // the tangent error summed from the anchor's fraction
        let mut prefix = Vec::with_capacity(contrib.len() + 1);
        prefix.push(0.0);
        for c in &contrib {
            prefix.push(prefix.last().copied().unwrap_or(0.0) + c);
        }
        let upto = |x: f64| prefix[frac.partition_point(|&y| y <= x)];
        let at_anchor = upto(anchor_fraction);
        let mut dist = Vec::with_capacity(width);
        let mut explained = Vec::with_capacity(width);
        for k in (0..width).filter(|k| k % stride == 0 || k + 1 == width) {
            let x = (point_arclength(s, k) - s0) / span;
            let u = table.u_at(x);
            dist.push(refine_closest(f.r, points[r * width + k], u, v, f.du, f.dv, stop).0);
            explained.push((upto(x) - at_anchor).abs());
        }
        Ok(RowResult {
            dist,
            explained,
            contrib,
            frac,
            table,
        })
    };
    let results = rows_parallel(picked.len(), &work)?;
    let (cb, rb) = (breaks(&nodes.cols), breaks(&nodes.rows));
    let (nc, nr) = (cb.len() - 1, rb.len() - 1);
    let mut on_nodes = vec![vec![0.0f64; nc]; nr];
    let mut between = vec![vec![0.0f64; nc]; nr];
    let psi: Vec<f64> = level.params.t.iter().map(|t| t / lt).collect();
    // the mesh row nearest each node row
    let node_rows: Vec<usize> = rb
        .iter()
        .map(|&y| {
            picked
                .iter()
                .copied()
                .min_by(|&a, &b| (psi[a] - y).abs().total_cmp(&(psi[b] - y).abs()))
                .unwrap_or(0)
        })
        .collect();
    let mut dist = Vec::with_capacity(rows * width);
    let mut tables = Vec::with_capacity(rows);
    let mut sums = vec![0.0f64; nc];
    let mut worst = (0.0, 0.0, 0.0);
    for (&r, res) in picked.iter().zip(results) {
        for (d, e) in res.dist.iter().zip(&res.explained) {
            if *d > worst.1 {
                worst = (psi[r], *d, *e);
            }
        }
        sums.iter_mut().for_each(|x| *x = 0.0);
        for (c, x) in res.contrib.iter().zip(&res.frac) {
            sums[interval(&cb, *x)] += c;
        }
        let mut on_node = false;
        for (j, &nr_j) in node_rows.iter().enumerate() {
            if nr_j == r {
                on_node = true;
                for a in [j.wrapping_sub(1), j] {
                    if a < nr {
                        for (cell, s) in on_nodes[a].iter_mut().zip(&sums) {
                            *cell = cell.max(*s);
                        }
                    }
                }
            }
        }
        if !on_node {
            let a = interval(&rb, psi[r]);
            for (cell, s) in between[a].iter_mut().zip(&sums) {
                *cell = cell.max(*s);
            }
        }
        dist.extend(res.dist);
        tables.push(res.table);
    }
    Ok(Measure {
        dist,
        worst,
        on_nodes,
        between,
        tables,
    })
}

/// The reference, sampled where the mesh's points and its cells' centres
/// are expected, to the mesh (eq. 12.7).
pub(super) fn from_reference(
    f: &Frame<'_>,
    anchor: &AnchorCurve,
    level: &Level,
    points: &[DVec3],
    tables: &[RowTable],
) -> Result<(Vec<f64>, (usize, usize)), ReferenceFitError> {
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
    let width = cols + 1;
    let work = |r: usize| -> Result<Vec<f64>, ReferenceFitError> {
        let s = level.params.s.row(r);
        let (s0, span) = (s[0], s[cols - 1] - s[0]);
        let span = if span > 0.0 { span } else { 1.0 };
        let table = tables
            .get(r)
            .ok_or(ReferenceFitError::NonFinite { what: "row" })?;
        let mut out = Vec::with_capacity(2 * width);
        for k in 0..width {
            let x = (point_arclength(s, k) - s0) / span;
            let p = f.r.point(table.u_at(x), table.v);
            out.push(mesh_distance_near(points, rows, width, p, r, k, 1));
        }
        if r + 1 < rows {
            let t = 0.5 * (level.params.t[r] + level.params.t[r + 1]);
            let mid = RowTable::new(f, anchor.v_at(t))?;
            for k in 0..width - 1 {
                let a = 0.5 * (point_arclength(s, k) + point_arclength(s, k + 1));
                let p = f.r.point(mid.u_at((a - s0) / span), mid.v);
                out.push(mesh_distance_near(points, rows, width, p, r, k, 1));
            }
        }
        Ok(out)
    };
    let per_row = rows_parallel(rows, &work)?;
    // the worst sample's mesh cell: a point's or a cell centre's
    let mut worst = (0.0f64, (0, 0));
    for (r, d) in per_row.iter().enumerate() {
        for (i, &x) in d.iter().enumerate() {
            if x > worst.0 {
                worst = (x, (r, if i < width { i } else { i - width }));
            }
        }
    }
    Ok((per_row.into_iter().flatten().collect(), worst.1))
}

/// The cells' bounds in one direction: the nodes, and 0 and 1 where the
/// nodes stop short of them (Doo–Sabin's), so that the border can grow too.
pub(super) fn breaks(xs: &[f64]) -> Vec<f64> {
    let mut b = Vec::with_capacity(xs.len() + 2);
    if xs.first().is_some_and(|&x| x > 0.0) {
        b.push(0.0);
    }
    b.extend_from_slice(xs);
    if xs.last().is_some_and(|&x| x < 1.0) {
        b.push(1.0);
    }
    b
}
