//! Measuring a fit (`docs/math.md §12`, "Deviation, both ways"): a built
//! mesh against the reference, every point from where its row's `t` and its
//! arc length expect it (eq. 12.6), with the cells' tangent-error scores
//! that say where to grow; and the reference, sampled at the same places
//! and the cells' centres, to the mesh (eq. 12.7).

use super::closest::{mesh_distance_near, point_triangle, refine_closest, refine_closest_steps};
use super::construct::Nodes;
use super::error::ReferenceFitError;
use super::reference::{AnchorCurve, Frame, RowTable};
use crate::levels::design::Level;
use crate::streamline::integrate::point_arclength;
use glam::DVec3;
use std::collections::HashMap;

/// The measurements of one mesh row.
#[derive(Clone)]
pub(super) struct RowResult {
    pub(super) dist: Vec<f64>,
    /// Of each measured point, the position error its row's tangent error
    /// explains: the angle × interval summed from the anchor to the point
    /// (a bound on the gap that the tangents alone open).
    pub(super) explained: Vec<f64>,
    /// Of each measured point, its fraction of the row's length.
    pub(super) at: Vec<f64>,
    /// Of each measured point, where Newton starts (`u`), and whether its
    /// distance is the converged one or the first step's (never less).
    start: Vec<f64>,
    exact: Vec<bool>,
    /// Angle × interval of each level tangent.
    pub(super) contrib: Vec<f64>,
    /// Fraction of the row's length at each level tangent.
    pub(super) frac: Vec<f64>,
    pub(super) table: RowTable,
}

/// The measurement of a whole mesh.
pub(super) struct Measure {
    pub(super) dist: Vec<f64>,
    /// The furthest measured point: its row's `t / L_t`, its distance,
    /// the part of it that its row's tangent error explains, and its
    /// fraction of the row's length.
    pub(super) worst: (f64, f64, f64, f64),
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

/// Runs `work` on every row index, on two threads, one taking the even
/// indices and the other the odd ones (so that rows that cost more, such
/// as those a row insertion changed, which lie together, are shared).
pub(super) fn rows_parallel<T: Send>(
    rows: usize,
    work: &(dyn Fn(usize) -> Result<T, ReferenceFitError> + Sync),
) -> Result<Vec<T>, ReferenceFitError> {
    let mut even: Vec<Result<T, ReferenceFitError>> = Vec::new();
    let mut odd: Vec<Result<T, ReferenceFitError>> = Vec::new();
    crate::parallel::join(
        || even = (0..rows).step_by(2).map(work).collect(),
        || odd = (1..rows).step_by(2).map(work).collect(),
    );
    let mut out = Vec::with_capacity(rows);
    let mut odd = odd.into_iter();
    for e in even {
        out.push(e?);
        if let Some(o) = odd.next() {
            out.push(o?);
        }
    }
    Ok(out)
}

/// What a mesh row's measurement depends on: its `t`, the stride, and its
/// points, level tangents and arc lengths, bit for bit.
#[derive(Clone, PartialEq)]
struct RowKey {
    t: u64,
    stride: usize,
    every: usize,
    points: Vec<[u64; 3]>,
    tangents: Vec<[u64; 3]>,
    s: Vec<u64>,
}

impl RowKey {
    fn new(level: &Level, points: &[DVec3], r: usize, stride: usize, every: usize) -> Self {
        let bits = |p: &DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
        let width = level.tangents.cols() + 1;
        RowKey {
            t: level.params.t[r].to_bits(),
            stride,
            every,
            points: points[r * width..(r + 1) * width]
                .iter()
                .map(bits)
                .collect(),
            tangents: level.tangents.row(r).iter().map(bits).collect(),
            s: level.params.s.row(r).iter().map(|x| x.to_bits()).collect(),
        }
    }

    /// A quick hash (multiply and rotate over the bits; the key itself is
    /// compared on a hit).
    fn hash(&self) -> u64 {
        let mut h = 0x9e37_79b9_7f4a_7c15u64;
        let mut mix = |x: u64| h = (h ^ x).wrapping_mul(0x0100_0000_01b3).rotate_left(29);
        mix(self.t);
        mix(self.stride as u64);
        mix(self.every as u64);
        self.points
            .iter()
            .chain(&self.tangents)
            .flatten()
            .for_each(|&x| mix(x));
        self.s.iter().for_each(|&x| mix(x));
        h
    }
}

/// The rows measured by the last net, kept for the next one: a row that
/// the insertion of a row elsewhere left bit for bit as it was (the
/// subdivision is local) is not measured again. Its results are the same
/// numbers, so the cache changes nothing but the time.
#[derive(Default)]
pub(super) struct RowCache {
    rows: HashMap<u64, (RowKey, RowResult)>,
}

/// Measures a built mesh against the reference (eq. 12.6) at every
/// `stride`-th row and point, and scores the cells by the tangent errors
/// of every `every`-th level tangent of those rows; rows met unchanged in
/// `cache` are taken from it (and a row measured with stride 2 lends its
/// points to the same row measured with stride 1), and the cache then holds
/// this mesh's rows.
#[allow(clippy::too_many_arguments)]
pub(super) fn measure(
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
            out.push(mesh_distance_pruned(points, rows, width, p, r, k));
        }
        if r + 1 < rows {
            let t = 0.5 * (level.params.t[r] + level.params.t[r + 1]);
            let mid = RowTable::new(f, anchor.v_at(t))?;
            for k in 0..width - 1 {
                let a = 0.5 * (point_arclength(s, k) + point_arclength(s, k + 1));
                let p = f.r.point(mid.u_at((a - s0) / span), mid.v);
                out.push(mesh_distance_pruned(points, rows, width, p, r, k));
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

/// [`mesh_distance_near`] with radius 1, the same number: the cell the
/// sample is expected in first, then a neighbour only when its bounding
/// box is nearer than the best distance found (its triangles cannot be
/// nearer than its box), which leaves two triangles of eighteen for a
/// sample near its place.
pub(super) fn mesh_distance_pruned(
    points: &[DVec3],
    rows: usize,
    width: usize,
    p: DVec3,
    r: usize,
    k: usize,
) -> f64 {
    if rows < 2 || width < 2 {
        return mesh_distance_near(points, rows, width, p, r, k, 1);
    }
    let r0 = r.saturating_sub(1).min(rows - 2);
    let r1 = (r + 1).min(rows - 2);
    let k0 = k.saturating_sub(1).min(width - 2);
    let k1 = (k + 1).min(width - 2);
    let tri = |i: usize, j: usize| {
        let a = points[i * width + j];
        let b = points[i * width + j + 1];
        let d = points[(i + 1) * width + j];
        let e = points[(i + 1) * width + j + 1];
        point_triangle(p, a, b, d).min(point_triangle(p, b, e, d))
    };
    // the cell expected first, then the others whose box is near enough
    let (ri, kj) = (r.min(rows - 2), k.min(width - 2));
    let mut best = tri(ri, kj);
    for i in r0..=r1 {
        for j in k0..=k1 {
            if (i, j) == (ri, kj) {
                continue;
            }
            let c = [
                points[i * width + j],
                points[i * width + j + 1],
                points[(i + 1) * width + j],
                points[(i + 1) * width + j + 1],
            ];
            let lo = c[0].min(c[1]).min(c[2]).min(c[3]);
            let hi = c[0].max(c[1]).max(c[2]).max(c[3]);
            let gap = (lo - p).max(p - hi).max(DVec3::ZERO).length();
            // (a margin for rounding, so that the number is the full
            // search's)
            if gap <= best * (1.0 + 1e-9) || gap.is_nan() || best.is_nan() {
                best = best.min(tri(i, j));
            }
        }
    }
    best
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A wavy grid of `rows × width` points, and samples near and far from it.
    fn grid(rows: usize, width: usize, seed: f64) -> (Vec<DVec3>, Vec<(DVec3, usize, usize)>) {
        let mut x = seed;
        let mut next = || {
            x = (x * 9301.0 + 0.49297).fract();
            x - 0.5
        };
        let mut points = Vec::new();
        for i in 0..rows {
            for j in 0..width {
                let (a, b) = (j as f64 / 10.0, i as f64 / 10.0);
                points.push(DVec3::new(
                    a,
                    b,
                    0.05 * (3.0 * a).sin() * (2.0 * b).cos() + 0.01 * next(),
                ));
            }
        }
        let mut samples = Vec::new();
        for r in 0..rows {
            for k in 0..width {
                let base = points[r * width + k];
                for scale in [1e-4, 0.03, 0.2] {
                    let q = base + DVec3::new(next(), next(), next()) * scale;
                    samples.push((q, r, k));
                }
            }
        }
        (points, samples)
    }

    /// The pruned search finds exactly the full search's distance, near
    /// and far from the sample's place, on small and degenerate grids.
    #[test]
    fn pruned_mesh_distance_is_the_full_search() {
        for (rows, width, seed) in [(7, 9, 0.3), (2, 2, 0.7), (2, 6, 0.1), (5, 2, 0.9)] {
            let (points, samples) = grid(rows, width, seed);
            for &(q, r, k) in &samples {
                let full = mesh_distance_near(&points, rows, width, q, r, k, 1);
                let pruned = mesh_distance_pruned(&points, rows, width, q, r, k);
                assert_eq!(full.to_bits(), pruned.to_bits(), "{q} at ({r}, {k})");
            }
        }
        // negative control: the search is not blind to the mesh, a sample
        // moved off it by 0.1 is that much further
        let (points, _) = grid(7, 9, 0.3);
        let p = points[3 * 9 + 4];
        let on = mesh_distance_pruned(&points, 7, 9, p, 3, 4);
        let off = mesh_distance_pruned(&points, 7, 9, p + DVec3::new(0.0, 0.0, 0.1), 3, 4);
        assert!(on < 1e-12 && off > 0.05, "{on} {off}");
    }
}
