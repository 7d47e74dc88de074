//! The antipodal pairs of a build's levels (docs/math.md §1): every step of
//! the tensor-product schemes (docs/math.md §3) blends neighbours along a row
//! and along a column of the level it refines; the pairs among them that
//! take the antipodal branch ([`crate::sphere::antipodal::is_antipodal`]),
//! found in the levels a build made, so that it can name them.

use crate::grid::Grid;
use crate::simd::dots_at_least;
use crate::sphere::antipodal::{SCAN_DOT, is_antipodal};
use glam::DVec3;
use std::fmt;

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
        if dots_at_least(right, &right[1.min(right.len())..], SCAN_DOT)
            && dots_at_least(&row[c0..=c1], down, SCAN_DOT)
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

#[cfg(test)]
mod tests {
    use super::*;

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
