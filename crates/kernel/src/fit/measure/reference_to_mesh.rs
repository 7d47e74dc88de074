//! The reference measured against the mesh (`docs/math.md §12`, eq. 12.7):
//! the reference sampled where the mesh's points and its cells' centres are
//! expected, each sample's distance to the mesh's triangles around its place
//! (a pruned search that gives the full search's number).

use super::rows_parallel;
use crate::fit::closest::{mesh_distance_near, point_triangle};
use crate::fit::error::ReferenceFitError;
use crate::fit::reference::{AnchorCurve, Frame, RowTable};
use crate::levels::design::Level;
use crate::streamline::integrate::point_arclength;
use glam::DVec3;

/// The reference, sampled where the mesh's points and its cells' centres
/// are expected, to the mesh (eq. 12.7).
pub(crate) fn from_reference(
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
