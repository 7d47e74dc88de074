//! Which blends of a build take the antipodal branch (docs/math.md §1).
//!
//! Two neighbouring tangents that point in opposite directions have no
//! great circle of their own: [`super::blend::blend`] and [`super::blend::mid`]
//! then turn about a fixed axis perpendicular to the first (`antipodal_axis`),
//! so the surface there depends on that documented choice rather than on
//! the designer's tangents. Every step of the tensor-product schemes
//! (docs/math.md §3) blends neighbours along a row and along a column of the
//! level it refines, and the initial curve's QI curve rotates between
//! consecutive control tangents (docs/math.md §2); this module finds the
//! pairs among those inputs that take the antipodal branch, so that a build
//! reports them from its own levels (a process-wide counter cannot say which
//! tangents, nor which build, they belong to).

use super::blend::{DEGENERATE_SIN, MID_MIN_NORM2};
use crate::grid::Grid;
use glam::DVec3;
use std::fmt;

/// `a·b` above which a pair cannot be antipodal: `|a × b| ≤ 1e-14` with
/// `a·b < 0` means `a·b < −(1 − 1e-28)`, and `|a + b|² ≤ 1e-24` means
/// `a·b ≤ −1 + 5e-25`; a dot product over `−0.5` rules both out, so the scan
/// computes a cross product only for pairs more than 120° apart.
const SCAN_DOT: f64 = -0.5;

/// Whether the blend of the unit vectors `a` and `b` takes the antipodal
/// branch: the predicate of [`super::blend::blend`] (`|a × b| ≤ 1e-14`,
/// `a·b < 0`) or of [`super::blend::mid`] (`|a + b|² ≤ 1e-24`).
#[inline]
pub fn is_antipodal(a: DVec3, b: DVec3) -> bool {
    let c = a.dot(b);
    c < SCAN_DOT
        && ((a + b).length_squared() <= MID_MIN_NORM2 || a.cross(b).length() <= DEGENERATE_SIN)
}

/// Two neighbours of one level that the next subdivision step blends about
/// the fixed axis: cells `(row, column)` of level `level` (level 0 is the
/// control net), `b` the right (`c + 1`) or lower (`r + 1`) neighbour of `a`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct AntipodalPair {
    /// The subdivision level of the two cells (0: the control net).
    pub level: u32,
    /// The first cell, `(row, column)`.
    pub a: (usize, usize),
    /// Its neighbour along the row or the column.
    pub b: (usize, usize),
}

impl fmt::Display for AntipodalPair {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ((r0, c0), (r1, c1)) = (self.a, self.b);
        write!(f, "antipodal blend between ({r0}, {c0}) and ({r1}, {c1})")?;
        if self.level > 0 {
            write!(f, " of depth {}", self.level)?;
        }
        f.write_str(
            ": they point in opposite directions, so the surface between them turns about a fixed axis; turn one of them",
        )
    }
}

/// Appends to `out` every pair of row or column neighbours of `level` (the
/// tangents of subdivision level `depth`) that takes the antipodal branch, in
/// row-major order of the first cell (its right neighbour before the one
/// below), which is also the pairs' `Ord`. One dot product per pair; a cross
/// product only for pairs more than 120° apart.
pub fn antipodal_pairs(depth: u32, level: &Grid<DVec3>, out: &mut Vec<AntipodalPair>) {
    let (rows, cols) = (level.rows(), level.cols());
    if rows > 0 && cols > 0 {
        antipodal_pairs_from(depth, level, 0..=rows - 1, 0..=cols - 1, out);
    }
}

/// [`antipodal_pairs`] for the pairs whose first cell `a` lies in `rows` ×
/// `cols` (clamped to the grid), in the same order. After the cells of a
/// window `r0 ..= r1` × `c0 ..= c1` changed, the pairs that may have changed
/// are those with a first cell in `r0 − 1 ..= r1` × `c0 − 1 ..= c1` (a pair's
/// second cell is the right or lower neighbour of the first), so a scan of
/// those brings a level's list up to date.
pub fn antipodal_pairs_from(
    depth: u32,
    level: &Grid<DVec3>,
    rows: std::ops::RangeInclusive<usize>,
    cols: std::ops::RangeInclusive<usize>,
    out: &mut Vec<AntipodalPair>,
) {
    let (n_rows, n_cols) = (level.rows(), level.cols());
    let (r1, c1) = (
        (*rows.end()).min(n_rows.saturating_sub(1)),
        (*cols.end()).min(n_cols.saturating_sub(1)),
    );
    if n_rows == 0 || n_cols == 0 || *rows.start() > r1 || *cols.start() > c1 {
        return;
    }
    let c0 = *cols.start();
    for r in *rows.start()..=r1 {
        let row = level.row(r);
        let below = (r + 1 < n_rows).then(|| level.row(r + 1));
        // most rows have no pair over 120° apart: one branch-free pass of
        // dot products rules the row out (a pair it lets through is then
        // tested as before, so the list is the same)
        let right = &row[c0..(c1 + 2).min(n_cols)];
        let down = below.map_or(&[][..], |b| &b[c0..=c1]);
        if min_dot(right, &right[1.min(right.len())..]) >= SCAN_DOT
            && min_dot(&row[c0..=c1], down) >= SCAN_DOT
        {
            continue;
        }
        for c in c0..=c1 {
            let a = row[c];
            if c + 1 < n_cols && is_antipodal(a, row[c + 1]) {
                out.push(AntipodalPair {
                    level: depth,
                    a: (r, c),
                    b: (r, c + 1),
                });
            }
            if let Some(below) = below
                && is_antipodal(a, below[c])
            {
                out.push(AntipodalPair {
                    level: depth,
                    a: (r, c),
                    b: (r + 1, c),
                });
            }
        }
    }
}

/// The smallest `a[i]·b[i]` over the common length (`+∞` when empty), with
/// four running minima so that the compares do not wait on each other.
fn min_dot(a: &[DVec3], b: &[DVec3]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut m = [f64::INFINITY; 4];
    let (qa, qb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (qa.remainder(), qb.remainder());
    for (x, y) in qa.zip(qb) {
        for k in 0..4 {
            m[k] = m[k].min(x[k].dot(y[k]));
        }
    }
    for (x, y) in ra.iter().zip(rb) {
        m[0] = m[0].min(x.dot(*y));
    }
    m[0].min(m[1]).min(m[2].min(m[3]))
}

/// The indices `k` of consecutive control tangents `k, k + 1` of a curve
/// (the initial curve's QI curve, docs/math.md §2) that point in opposite
/// directions, where the QI curve's rotation axis is the fixed one.
pub fn antipodal_legs(tangents: &[DVec3]) -> Vec<usize> {
    tangents
        .windows(2)
        .enumerate()
        .filter(|(_, w)| is_antipodal(w[0], w[1]))
        .map(|(k, _)| k)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sphere::blend::{antipodal_events, blend, mid};

    /// The predicate is the blend's own: a pair it flags takes the counted
    /// branch, and a pair a hair away from antipodal does not.
    #[test]
    fn is_antipodal_matches_the_blend_branch() {
        for a in [
            DVec3::X,
            DVec3::new(0.6, 0.8, 0.0),
            DVec3::new(1.0, 2.0, -3.0).normalize(),
        ] {
            assert!(is_antipodal(a, -a), "{a}");
            let before = antipodal_events();
            let _ = blend(a, -a, 0.3);
            let _ = mid(a, -a);
            assert!(antipodal_events() >= before + 2, "{a}: branch taken");
            let off = (-a + a.any_orthonormal_vector() * 1e-6).normalize();
            assert!(!is_antipodal(a, off), "{a}: 1e-6 rad off is a great circle");
            assert!(!is_antipodal(a, a));
        }
    }

    /// Rows and columns are both scanned, named by their cells.
    #[test]
    fn antipodal_pairs_names_row_and_column_neighbours() {
        let x = DVec3::X;
        let mut g = Grid::filled(3, 4, x);
        g.set(0, 2, -x); // right of (0, 1), left of (0, 3), above (1, 2)
        let mut out = Vec::new();
        antipodal_pairs(0, &g, &mut out);
        let cells: Vec<_> = out.iter().map(|p| (p.a, p.b)).collect();
        assert_eq!(
            cells,
            vec![((0, 1), (0, 2)), ((0, 2), (0, 3)), ((0, 2), (1, 2)),]
        );
        assert!(
            out[0]
                .to_string()
                .starts_with("antipodal blend between (0, 1) and (0, 2): ")
        );
        let mut deep = Vec::new();
        antipodal_pairs(2, &g, &mut deep);
        assert!(
            deep[0].to_string().contains("(0, 2) of depth 2:"),
            "{}",
            deep[0]
        );
        assert_eq!(antipodal_legs(&[x, -x, DVec3::Y, -DVec3::Y]), vec![0, 2]);
        assert!(antipodal_legs(&[x]).is_empty());
    }

    /// A window's rescan brings a level's list up to date: drop the pairs
    /// whose first cell is in the window grown by one up and left, scan
    /// those cells again, and the sorted list is the full scan's.
    #[test]
    fn a_window_rescan_equals_the_full_scan() {
        let x = DVec3::X;
        let mut g = Grid::filled(7, 9, x);
        for &(r, c) in &[(0, 0), (2, 3), (3, 4), (6, 8), (4, 0)] {
            g.set(r, c, -x);
        }
        let mut before = Vec::new();
        antipodal_pairs(1, &g, &mut before);
        let mut sorted = before.clone();
        sorted.sort();
        assert_eq!(before, sorted, "the scan order is the pairs' order");
        for (r0, r1, c0, c1) in [(2, 4, 3, 5), (0, 0, 0, 0), (5, 6, 6, 8), (0, 6, 0, 8)] {
            let mut h = g.clone();
            for r in r0..=r1 {
                for c in c0..=c1 {
                    let v = if (r + c) % 2 == 0 { -x } else { x };
                    h.set(r, c, v);
                }
            }
            let (rows, cols) = (r0.saturating_sub(1)..=r1, c0.saturating_sub(1)..=c1);
            let mut list = before.clone();
            list.retain(|p| !(rows.contains(&p.a.0) && cols.contains(&p.a.1)));
            antipodal_pairs_from(1, &h, rows, cols, &mut list);
            list.sort();
            let mut full = Vec::new();
            antipodal_pairs(1, &h, &mut full);
            assert_eq!(list, full, "window {r0}..={r1} × {c0}..={c1}");
        }
        let mut none = Vec::new();
        antipodal_pairs_from(0, &g, 9..=12, 0..=3, &mut none);
        antipodal_pairs(0, &Grid::filled(0, 0, x), &mut none);
        assert!(none.is_empty());
    }
}
