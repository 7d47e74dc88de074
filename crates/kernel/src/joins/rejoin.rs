//! A joined patch `B` brought up to date after its parent `A` changed while
//! `B`'s own design did not (docs/math.md §11): a local edit of `A` redoes, of
//! the patches that start on it, only what its changed edge moved.
//!
//! What `B`'s build reads of `A` is small. A chain (§11.1) reads, at every
//! depth `d`, `A`'s row parameters `t` and (G1) `A`'s last column of
//! tangents to make `B`'s levels, and `A`'s last column of points to place
//! `B`'s streamlines (Eq. 65 from those starts). A side join (§11.2) reads
//! `A`'s edge streamline at every depth ([`super::edge_curve::EdgeCurve`]): G0 only to place
//! `B`'s streamlines, G1 also to project `B`'s first column (Eq. 73) while
//! making its levels. So when those inputs are bit for bit what they were,
//! `B`'s levels are kept and only its points are placed again (or nothing
//! at all changes); when only a side G1 join's edge normals moved, its first
//! column is projected again and only what reads it re-blended
//! (`super::reproject`, s-first Kobbelt nets). The result is bit for bit
//! what [`super::chain::chain`] or [`super::side::side`] would build;
//! otherwise [`rejoin`] answers [`Rejoin::Rebuild`] and the caller builds
//! `B` whole.
//!
//! `A` before and after the edit are given as [`Edges`], exactly what `B`
//! reads of it (not `A`'s stacks, megabytes at depth 5), and `B`'s points
//! are placed again in place, in the rows whose start moved.

use crate::bits::{bits, same};
use crate::grid::Grid;
use crate::joins::chain::check_chain;
use crate::joins::edge_curve::EdgeCurve;
use crate::joins::edges::Edges;
use crate::joins::kinds::{Continuity, Edge};
use crate::joins::reproject::reproject;
use crate::joins::side::check_rows;
use crate::joins::stack::{Stack, place_at_starts};
use crate::levels::design::{Design, Level};
use crate::levels::dirty_window::{DirtyWindow, Span};
use crate::streamline::integrate::place_slice;
use glam::DVec3;

/// What [`rejoin`] found; each holds `B`'s stack.
#[derive(Debug, Clone, PartialEq)]
pub enum Rejoin {
    /// Nothing `B` reads of `A` changed: `B`'s stack as it was.
    Unchanged(Stack),
    /// `B`'s levels as they were (moved, not copied; a side G1 join's
    /// re-blended in place where its first column's projection changed),
    /// its points placed again in place in the rows whose start point
    /// moved or whose tangents were re-blended (the others as they were);
    /// `rows` holds the first and last row placed again at each depth
    /// (`None` where nothing moved), so that callers can be local too.
    Moved {
        stack: Stack,
        rows: Vec<Option<RowSpan>>,
    },
    /// `B`'s levels read something of `A` that changed, the depths differ,
    /// the join is G2 (a G2 chain is one net) or no longer valid: build `B`
    /// whole (its error is the whole build's). `B`'s old stack, handed back
    /// (partly re-blended when a side G1 join's projection was refused on
    /// the way, which the whole build then reports).
    Rebuild(Stack),
}

/// The first and last row (inclusive) of a grid that moved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RowSpan {
    /// The first moved row.
    pub lo: usize,
    /// The last moved row.
    pub hi: usize,
}

/// `B` (its design `b`, as joined, and its stack `b_old` built on `A` as
/// `a_old` describes it) after `A` changed to what `a_new` describes (`a`
/// is `A`'s new design), joined on `edge` with `continuity` (module
/// documentation).
pub fn rejoin(
    a: &Design,
    a_old: &Edges,
    a_new: &Edges,
    b: &Design,
    b_old: Stack,
    edge: Edge,
    continuity: Continuity,
) -> Rejoin {
    let depths = a_new.len();
    if continuity == Continuity::G2
        || depths == 0
        || a_old.len() != depths
        || b_old.levels.len() != depths
        || b_old.points.len() != depths
    {
        return Rejoin::Rebuild(b_old);
    }
    let keeps = match edge {
        Edge::End => {
            keeps_chain(a, a_old, a_new, b, continuity)
                && (a_new.levels.iter().zip(&b_old.levels))
                    .all(|(n, l)| n.end_points.len() == l.tangents.rows())
        }
        Edge::First | Edge::Last => keeps_side(a_old, a_new, b, edge),
    };
    if !keeps {
        return Rejoin::Rebuild(b_old);
    }
    let Stack {
        mut levels,
        mut points,
    } = b_old;
    // a side G1 join whose edge moved: its first column projected again,
    // and what reads it re-blended (super::reproject)
    let mut reblended: Vec<Option<DirtyWindow>> = vec![None; depths];
    if edge != Edge::End && continuity == Continuity::G1 {
        let (Some(old), Some(new)) = (curves(a_old, edge), curves(a_new, edge)) else {
            return Rejoin::Rebuild(Stack { levels, points });
        };
        if !old.iter().zip(&new).all(|(o, n)| o.same_bits(n)) {
            match reproject(b, &mut levels, &old, &new) {
                Some(w) => reblended = w,
                None => return Rejoin::Rebuild(Stack { levels, points }),
            }
        }
    }
    let mut starts = Vec::new();
    let rows: Vec<Option<RowSpan>> = (levels.iter().zip(points.iter_mut()))
        .zip(a_old.levels.iter().zip(&a_new.levels))
        .zip(&reblended)
        .map(|(((level, bp), (old, new)), re)| {
            let also = re.map(|w| w.rows);
            match edge {
                Edge::End => replace_moved(level, bp, &new.end_points, also),
                side => {
                    let (o, curve) = (old.curve(side)?, new.curve(side)?);
                    if o.same_bits(curve) && also.is_none() {
                        return None;
                    }
                    starts.clear();
                    starts.extend(level.params.t.iter().map(|&t| curve.point(t)));
                    replace_moved(level, bp, &starts, also)
                }
            }
        })
        .collect();
    let stack = Stack { levels, points };
    if rows.iter().all(Option::is_none) {
        Rejoin::Unchanged(stack)
    } else {
        Rejoin::Moved { stack, rows }
    }
}

/// Places again, in `out` (`B`'s points on `level`), the rows whose start
/// in `starts` is not bit for bit their first point and the rows `also`
/// (whose tangents were re-blended) (Eq. 65, as [`place_at_starts`] places
/// every row; the rows are independent, so the others stay); every row
/// when the sizes differ. The rows placed again, `None` when none was.
fn replace_moved(
    level: &Level,
    out: &mut Grid<DVec3>,
    starts: &[DVec3],
    also: Option<Span>,
) -> Option<RowSpan> {
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
    if out.rows() != rows || out.cols() != cols + 1 || starts.len() != rows {
        // sizes differ (not a stack of this level): every row again
        *out = place_at_starts(level, starts, None);
        return (rows > 0).then(|| RowSpan {
            lo: 0,
            hi: rows - 1,
        });
    }
    let mut span: Option<RowSpan> = None;
    for (r, &start) in starts.iter().enumerate() {
        let re = also.is_some_and(|a| a.lo <= r && r <= a.hi);
        if !re && bits(out.get(r, 0)) == bits(start) {
            continue;
        }
        let s = level.params.s.row(r);
        place_slice(level.tangents.row(r), s, s[0], start, out.row_mut(r));
        span = Some(span.map_or(RowSpan { lo: r, hi: r }, |sp| RowSpan { lo: sp.lo, hi: r }));
    }
    span
}

/// `A`'s edge curve on `edge` at every depth, as `B` read it.
fn curves(e: &Edges, edge: Edge) -> Option<Vec<&EdgeCurve>> {
    e.levels.iter().map(|l| l.curve(edge)).collect()
}

/// A chain (docs/math.md §11.1): `B`'s levels read `A`'s `t` and (G1) last
/// tangent column at every depth, so they are kept when those are bit for
/// bit what they were (and the join is still valid); its points start on
/// `A`'s last points.
fn keeps_chain(
    a: &Design,
    a_old: &Edges,
    a_new: &Edges,
    b: &Design,
    continuity: Continuity,
) -> bool {
    if check_chain(a, b, continuity).is_err() {
        return false;
    }
    a_old.levels.iter().zip(&a_new.levels).all(|(lo, ln)| {
        let (to, tn) = (&lo.t, &ln.t);
        to.len() == tn.len()
            && to.iter().zip(tn).all(|(x, y)| x.to_bits() == y.to_bits())
            && ln.end_points.len() == tn.len()
            && (continuity != Continuity::G1 || same(&lo.last_tangents, &ln.last_tangents))
    })
}

/// A side join (docs/math.md §11.2) still valid on the new `A`: `B`'s
/// rows inside its edge curve. (Its points start on that curve at `B`'s
/// `t`; under G1 its levels also read the curve's normals, and are
/// projected again where those moved, [`reproject`].)
fn keeps_side(a_old: &Edges, a_new: &Edges, b: &Design, edge: Edge) -> bool {
    let pairs: Option<Vec<_>> = (a_old.levels.iter().zip(&a_new.levels))
        .map(|(o, n)| Some((o.curve(edge)?, n.curve(edge)?)))
        .collect();
    let Some(pairs) = pairs else {
        return false;
    };
    check_rows(&b.params().t, pairs[0].1.length()).is_ok()
}
