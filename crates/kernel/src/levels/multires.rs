//! Multiresolution details (docs/math.md §5).
//!
//! An edit at depth `d > 0` is stored as a *detail*: the edited tangent written
//! in a local orthonormal frame of the subdivided net of level `d` before any
//! detail is applied (the *base*). The frame at cell `(r, c)` is
//! `e₃ = base(r, c)`, `e₁` = the direction towards the row neighbours
//! (`base(r, c+1) − base(r, c−1)`, one-sided at the ends) made orthogonal to
//! `e₃`, `e₂ = e₃ × e₁`; where the row is flat the column neighbours are used,
//! and where both are flat a fixed axis (`fallback_axis`). A later coarse
//! edit rotates the base and its neighbours, and with them the frame, so the
//! detail is carried along; with the coarse net unchanged the frame is
//! unchanged, so undoing a coarse edit gives back the same numbers exactly.

use crate::grid::Grid;
use crate::levels::dirty_window::DirtyWindow;
use glam::DVec3;
use std::collections::BTreeMap;

/// Below this length a reference direction is treated as flat.
pub(crate) const FRAME_FLAT: f64 = 1e-9;

/// Details of all levels, keyed by `(level, row, col)`; values are unit
/// vectors in the local frame (`z` = the base tangent).
pub type Details = BTreeMap<(u32, usize, usize), DVec3>;

/// The axis least aligned with `t`, used where the net is flat in both directions.
pub(crate) fn fallback_axis(t: DVec3) -> DVec3 {
    let a = t.abs();
    if a.x <= a.y && a.x <= a.z {
        DVec3::X
    } else if a.y <= a.z {
        DVec3::Y
    } else {
        DVec3::Z
    }
}

/// The local frame `[e₁, e₂, e₃]` of cell `(r, c)` of `base`.
pub fn frame(base: &Grid<DVec3>, r: usize, c: usize) -> [DVec3; 3] {
    let e3 = base.get(r, c);
    let (rows, cols) = (base.rows(), base.cols());
    let along = base.get(r, (c + 1).min(cols - 1)) - base.get(r, c.saturating_sub(1));
    let across = base.get((r + 1).min(rows - 1), c) - base.get(r.saturating_sub(1), c);
    let mut e1 = DVec3::ZERO;
    for d in [along, across, fallback_axis(e3)] {
        let p = d - d.dot(e3) * e3;
        let len = p.length();
        if len > FRAME_FLAT && len.is_finite() {
            e1 = p / len;
            break;
        }
    }
    let e2 = e3.cross(e1);
    [e1, e2, e3]
}

/// `dir` (unit) in the local frame of `(r, c)`.
pub fn to_local(base: &Grid<DVec3>, r: usize, c: usize, dir: DVec3) -> DVec3 {
    let [e1, e2, e3] = frame(base, r, c);
    DVec3::new(dir.dot(e1), dir.dot(e2), dir.dot(e3))
}

/// The tangent a detail `local` gives at `(r, c)` (unit).
pub fn from_local(base: &Grid<DVec3>, r: usize, c: usize, local: DVec3) -> DVec3 {
    let [e1, e2, e3] = frame(base, r, c);
    let v = local.x * e1 + local.y * e2 + local.z * e3;
    v.try_normalize().unwrap_or(e3)
}

/// Writes `tangents = base` with the details of `level` applied, inside `win`.
/// Returns the number of details applied.
pub(crate) fn apply_window(
    base: &Grid<DVec3>,
    tangents: &mut Grid<DVec3>,
    details: &Details,
    level: u32,
    win: DirtyWindow,
) -> usize {
    // a window outside the grid (a detail past its level) writes nothing
    if win.rows.lo > win.rows.hi
        || win.cols.lo > win.cols.hi
        || win.rows.hi >= base.rows()
        || win.cols.hi >= base.cols()
    {
        return 0;
    }
    for r in win.rows.iter() {
        let (lo, hi) = (win.cols.lo, win.cols.hi);
        tangents.row_mut(r)[lo..=hi].copy_from_slice(&base.row(r)[lo..=hi]);
    }
    let mut n = 0;
    for r in win.rows.iter() {
        for (&(_, _, c), &local) in details.range((level, r, win.cols.lo)..=(level, r, win.cols.hi))
        {
            tangents.set(r, c, from_local(base, r, c, local));
            n += 1;
        }
    }
    n
}

/// Whether any detail sits on `level`.
pub(crate) fn has_level(details: &Details, level: u32) -> bool {
    details
        .range((level, 0, 0)..=(level, usize::MAX, usize::MAX))
        .next()
        .is_some()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_even_on_a_flat_net() {
        let flat = Grid::filled(3, 3, DVec3::X);
        let [a, b, c] = frame(&flat, 1, 1);
        for (u, v) in [(a, b), (b, c), (a, c)] {
            assert!(u.dot(v).abs() < 1e-15);
        }
        assert!((a.length() - 1.0).abs() < 1e-15 && (b.length() - 1.0).abs() < 1e-15);
        let d = DVec3::new(0.3, -0.4, 0.5).normalize();
        let back = from_local(&flat, 1, 1, to_local(&flat, 1, 1, d));
        assert!((back - d).length() < 1e-15, "round trip {back} vs {d}");
    }
}
