//! The mesh measured against the reference (`docs/math.md §12`, eq. 12.6):
//! every point from where its row's `t` and its arc length expect it, one
//! Newton step each and the furthest converged, and the cells' tangent-error
//! scores that say where to grow.

use super::row_cache::{RowCache, RowKey};
use super::{Measure, RowResult, angle, breaks, interval, rows_parallel};
use crate::fit::closest::{refine_closest, refine_closest_steps};
use crate::fit::construct::Nodes;
use crate::fit::error::ReferenceFitError;
use crate::fit::reference::{AnchorCurve, Frame, RowTable};
use crate::levels::design::Level;
use crate::streamline::integrate::point_arclength;
use glam::DVec3;

/// Measures a built mesh against the reference (eq. 12.6) at every
/// `stride`-th row and point, and scores the cells by the tangent errors
/// of every `every`-th level tangent of those rows; rows met unchanged in
/// `cache` are taken from it (and a row measured with stride 2 lends its
/// points to the same row measured with stride 1), and the cache then holds
/// this mesh's rows.
#[allow(clippy::too_many_arguments)]
pub(crate) fn measure(
    f: &Frame<'_>,
    anchor: &AnchorCurve,
    nodes: &Nodes,
    lt: f64,
    level: &Level,
    points: &[DVec3],
    (stride, every): (usize, usize),
    stop: f64,
    anchor_fraction: f64,
    cache: &mut RowCache,
) -> Result<Measure, ReferenceFitError> {
    let rows = level.tangents.rows();
    // the rows measured: every `stride`-th and the last
    let picked: Vec<usize> = (0..rows)
        .filter(|r| r % stride == 0 || r + 1 == rows)
        .collect();
    let known = &cache.rows;
    let work = |i: usize| -> Result<(u64, RowKey, RowResult), ReferenceFitError> {
        let r = picked[i];
        let key = RowKey::new(level, points, r, stride, every);
        let h = key.hash();
        if let Some((k, res)) = known.get(&h)
            && *k == key
        {
            return Ok((h, key, res.clone()));
        }
        // the same row measured with stride 2 and scored alike
        let prior = (stride == 1 && every == 2)
            .then(|| RowKey::new(level, points, r, 2, 2))
            .and_then(|k2| known.get(&k2.hash()).filter(|(k, _)| *k == k2))
            .map(|(_, res)| res);
        let row = (stride, every);
        Ok((
            h,
            key,
            measure_row(
                f,
                anchor,
                level,
                points,
                r,
                row,
                stop,
                anchor_fraction,
                prior,
            )?,
        ))
    };
    let mut measured = rows_parallel(picked.len(), &work)?;
    converge_furthest(
        f,
        anchor,
        level,
        points,
        &picked,
        stride,
        stop,
        &mut measured,
    );
    let m = scores(
        nodes,
        lt,
        level,
        &picked,
        measured.iter().map(|(_, _, res)| res),
    );
    cache.rows = measured
        .into_iter()
        .map(|(h, key, res)| (h, (key, res)))
        .collect();
    m
}

/// Converges every point whose first-step distance is over the largest
/// converged one, so that the furthest point and its distance are what
/// converging every point would give (a first step's distance is never
/// less than the converged one): the others keep their first step's,
/// within a few ulps of their distance from a start so close.
#[allow(clippy::too_many_arguments)]
fn converge_furthest(
    f: &Frame<'_>,
    anchor: &AnchorCurve,
    level: &Level,
    points: &[DVec3],
    picked: &[usize],
    stride: usize,
    stop: f64,
    rows: &mut [(u64, RowKey, RowResult)],
) {
    let width = level.tangents.cols() + 1;
    let converge = |i: usize, j: usize, rows: &mut [(u64, RowKey, RowResult)]| -> f64 {
        let res = &mut rows[i].2;
        if !res.exact[j] {
            let r = picked[i];
            let k = (j * stride).min(width - 1);
            let v = anchor.v_at(level.params.t[r]);
            let d = refine_closest(
                f.r,
                points[r * width + k],
                res.start[j],
                v,
                f.du,
                f.dv,
                stop,
            )
            .0;
            res.dist[j] = d;
            res.exact[j] = true;
        }
        res.dist[j]
    };
    let mut top = (0, 0, f64::NEG_INFINITY);
    for (i, row) in rows.iter().enumerate() {
        for (j, &d) in row.2.dist.iter().enumerate() {
            if d > top.2 {
                top = (i, j, d);
            }
        }
    }
    if top.2 == f64::NEG_INFINITY {
        return;
    }
    let mut most = converge(top.0, top.1, rows);
    for i in 0..rows.len() {
        for j in 0..rows[i].2.dist.len() {
            if !rows[i].2.exact[j] && rows[i].2.dist[j] > most {
                most = most.max(converge(i, j, rows));
            }
        }
    }
}

/// The measurement of mesh row `r` (eq. 12.6) at every `stride`-th point
/// and the tangent errors of every `every`-th level tangent; `prior`, the
/// same row measured with stride 2 and `every` 2, lends its table, its
/// tangent errors and its points' distances.
#[allow(clippy::too_many_arguments)]
fn measure_row(
    f: &Frame<'_>,
    anchor: &AnchorCurve,
    level: &Level,
    points: &[DVec3],
    r: usize,
    (stride, every): (usize, usize),
    stop: f64,
    anchor_fraction: f64,
    prior: Option<&RowResult>,
) -> Result<RowResult, ReferenceFitError> {
    let cols = level.tangents.cols();
    let width = cols + 1;
    let v = anchor.v_at(level.params.t[r]);
    let table = match prior {
        Some(p) => p.table.clone(),
        None => RowTable::new(f, v)?,
    };
    let s = level.params.s.row(r);
    let (s0, span) = (s[0], s[cols - 1] - s[0]);
    let span = if span > 0.0 { span } else { 1.0 };
    let (contrib, frac) = match prior {
        Some(p) => (p.contrib.clone(), p.frac.clone()),
        None => {
            let mut contrib = Vec::with_capacity(cols);
            let mut frac = Vec::with_capacity(cols);
            for k in (0..cols).step_by(every) {
                let x = (s[k] - s0) / span;
                let d = f.r.derivatives(table.u_at(x), v)[1];
                let ds = 0.5 * (s[(k + every).min(cols - 1)] - s[k.saturating_sub(every)]);
                let a = d
                    .try_normalize()
                    .map_or(0.0, |t| angle(level.tangents.get(r, k), t));
                contrib.push(a * ds);
                frac.push(x);
            }
            (contrib, frac)
        }
    };
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
    let mut at = Vec::with_capacity(width);
    let mut start = Vec::with_capacity(width);
    let mut exact = Vec::with_capacity(width);
    // one Newton step for every point; the furthest are converged
    // afterwards (`converge_furthest`)
    for k in (0..width).filter(|k| k % stride == 0 || k + 1 == width) {
        let x = (point_arclength(s, k) - s0) / span;
        at.push(x);
        explained.push((upto(x) - at_anchor).abs());
        // the prior's point k (its `k / 2`-th, or its last)
        let lent = prior.and_then(|p| {
            let j = if k % 2 == 0 {
                k / 2
            } else if k + 1 == width {
                p.dist.len() - 1
            } else {
                return None;
            };
            Some((p.dist[j], p.start[j], p.exact[j]))
        });
        let (d, u, e) = match lent {
            Some(l) => l,
            None => {
                let u = table.u_at(x);
                let p = points[r * width + k];
                (
                    refine_closest_steps(f.r, p, u, v, f.du, f.dv, stop, 1).0,
                    u,
                    false,
                )
            }
        };
        dist.push(d);
        start.push(u);
        exact.push(e);
    }
    Ok(RowResult {
        dist,
        explained,
        at,
        start,
        exact,
        contrib,
        frac,
        table,
    })
}

/// The cells' scores and the furthest point of the measured rows.
fn scores<'a>(
    nodes: &Nodes,
    lt: f64,
    level: &Level,
    picked: &[usize],
    results: impl Iterator<Item = &'a RowResult>,
) -> Result<Measure, ReferenceFitError> {
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
    let width = cols + 1;
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
    let mut worst = (0.0, 0.0, 0.0, 0.0);
    for (&r, res) in picked.iter().zip(results) {
        for ((d, e), x) in res.dist.iter().zip(&res.explained).zip(&res.at) {
            if *d > worst.1 {
                worst = (psi[r], *d, *e, *x);
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
        dist.extend_from_slice(&res.dist);
        tables.push(res.table.clone());
    }
    Ok(Measure {
        dist,
        worst,
        on_nodes,
        between,
        tables,
    })
}
