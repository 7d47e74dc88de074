//! A side G1 join's levels brought up to date in place after `A`'s edge
//! moved (docs/math.md §11.2, Eq. 73), bit for bit what [`super::side::side`]
//! builds on the new `A`, re-blending only what the new projections reach.
//!
//! The whole build makes each level `d` of `B` by one subdivision step of
//! level `d − 1` and then projects the first column onto the great circle
//! perpendicular to `A`'s normal at depth `d`. When `A`'s edge curves move,
//! only that first column and what reads it change: each row's projection is
//! made again from the column before projection, and the window of the rows
//! whose tangent changed is carried down the levels as an edit's is
//! ([`crate::levels::dirty_window`]). On the wing of `hood-screen-wing` at
//! depth 6 that is the first few dozen of its columns, not the whole net.
//!
//! The step kept is the s-first 4-point step, made in place
//! ([`crate::levels::dirty_window::in_place`]; other schemes need the grid
//! of the first direction, which a [`super::Stack`] does not keep, and are
//! built whole). There the first column before projection is a curve step
//! of the previous level's first column (the step along `s` copies it), and
//! the step across the rows works column by column, so the projected first
//! column it may read in place feeds only the first column, which is then
//! made again from that curve step.

use crate::bits::bits;
use crate::curve::scheme::Prepared;
use crate::grid::Grid;
use crate::joins::edge_curve::EdgeCurve;
use crate::joins::side::project;
use crate::levels::design::{Design, Level};
use crate::levels::dirty_window::{DirtyWindow, Span, in_place, refine_grid_window};
use glam::DVec3;

/// Brings `levels` (`B`'s, built by [`super::side::side`] with G1 on `A`
/// as its edge curves `old` describe, one per depth) up to date for `A`'s
/// edge curves `new`, in place. Returns the window of each level that
/// changed (`None`: untouched), or `None` when this path does not apply
/// (another step than the s-first 4-point one) or a projection is
/// refused; then `levels` may be partly updated and `B` must be built
/// whole, which reports the refusal.
pub(crate) fn reproject(
    b: &Design,
    levels: &mut [Level],
    old: &[&EdgeCurve],
    new: &[&EdgeCurve],
) -> Option<Vec<Option<DirtyWindow>>> {
    let (scheme, order) = (b.scheme(), b.order());
    if levels.len() != new.len()
        || old.len() != new.len()
        || levels.iter().any(|l| l.tangents.cols() == 0)
        || levels[..levels.len() - 1]
            .iter()
            .any(|l| !in_place(scheme, order, l.tangents.rows()))
    {
        return None;
    }
    let c = scheme.curve();
    let rule = Prepared::new(c);
    let mut windows: Vec<Option<DirtyWindow>> = Vec::with_capacity(levels.len());
    for d in 0..levels.len() {
        let (above, below) = levels.split_at_mut(d);
        let next = &mut below[0];
        let changed_above = d > 0 && windows[d - 1].is_some();
        if !changed_above && old[d].same_bits(new[d]) {
            // neither what the step reads nor the projection changed
            windows.push(None);
            continue;
        }
        let rows = next.tangents.rows();
        let was: Vec<DVec3> = (0..rows).map(|r| next.tangents.get(r, 0)).collect();
        // the first column before projection: the net's at level 0, else
        // the step across the rows of the previous level's first column
        // (the step along `s` copies it)
        let before: Vec<DVec3> = match d {
            0 => (0..rows).map(|r| b.net().get(r, 0)).collect(),
            _ => {
                let prev = &above[d - 1];
                let n = prev.tangents.rows();
                (0..rows)
                    .map(|r| rule.tangent(c.stencil(n, r), |j| prev.tangents.get(j, 0)))
                    .collect()
            }
        };
        let mut out = None;
        if changed_above && let Some(w) = windows[d - 1] {
            let prev = &above[d - 1];
            let mut none = Grid::filled(0, 0, DVec3::ZERO);
            out = Some(refine_grid_window(
                scheme,
                order,
                &prev.tangents,
                &mut none,
                &mut next.tangents,
                w,
            ));
        }
        let projected = project_column(next, new[d], &before, &was)?;
        windows.push(match (out, projected) {
            (Some(o), Some(p)) => Some(o.union(p)),
            (o, p) => o.or(p),
        });
    }
    Some(windows)
}

/// Sets `level`'s first column to `before` projected with `curve`'s normal
/// at each row's `t` (Eq. 73, as the whole build does). The window of the
/// rows whose tangent is not bit for bit `was` (column 0), `None` when
/// none; `None` outside when a projection is refused.
fn project_column(
    level: &mut Level,
    curve: &EdgeCurve,
    before: &[DVec3],
    was: &[DVec3],
) -> Option<Option<DirtyWindow>> {
    let mut rows: Option<Span> = None;
    for (r, (&b, &old)) in before.iter().zip(was).enumerate() {
        let v = project(b, curve.normal(level.params.t[r]))?;
        level.tangents.set(r, 0, v);
        if bits(v) != bits(old) {
            rows = Some(rows.map_or(Span::single(r), |s| s.union(Span::single(r))));
        }
    }
    Some(rows.map(|rows| DirtyWindow {
        rows,
        cols: Span { lo: 0, hi: 0 },
    }))
}
