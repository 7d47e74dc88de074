//! A joined patch `B` brought up to date after its parent `A` changed while
//! `B`'s own design did not (docs/math.md §11; what issue 28 asks of a
//! local edit: "of the patches that start on it, only what its changed
//! edge moved").
//!
//! What `B`'s build reads of `A` is small. A chain (§11.1) reads, at every
//! depth `d`, `A`'s row parameters `t` and (G1) `A`'s last column of
//! tangents to make `B`'s levels, and `A`'s last column of points to place
//! `B`'s streamlines (Eq. 65 from those starts). A side join (§11.2) reads
//! `A`'s edge streamline at every depth ([`EdgeCurve`]): G0 only to place
//! `B`'s streamlines, G1 also to project `B`'s first column (Eq. 73) while
//! making its levels. So when those inputs are bit for bit what they were,
//! `B`'s levels are kept and only its points are placed again (or nothing
//! at all changes), and the result is bit for bit what [`super::chain::chain`]
//! or [`super::side::side`] would build; otherwise [`rejoin`] answers `None`
//! and the caller builds `B` whole.

use crate::grid::Grid;
use crate::joins::chain::check_chain;
use crate::joins::edge_curve::EdgeCurve;
use crate::joins::kinds::{Continuity, Edge};
use crate::joins::side::check_rows;
use crate::joins::stack::{Stack, place_at_starts};
use crate::levels::design::{Design, Level};
use crate::streamline::integrate::place_slice;
use glam::DVec3;

/// What [`rejoin`] found; each holds `B`'s stack.
#[derive(Debug, Clone, PartialEq)]
pub enum Rejoin {
    /// Nothing `B` reads of `A` changed: `B`'s stack as it was.
    Unchanged(Stack),
    /// `B`'s levels as they were (moved, not copied), its points placed
    /// again in the rows whose start point moved (the others copied);
    /// `replaced` holds the old points of each depth that moved (`None`:
    /// the same), so that `B`'s stack before can still be read
    /// ([`StackRef::points_before`]) by the patches that start on `B`, and
    /// `rows` the first and last row placed again at each depth (`None`
    /// where nothing moved), so that callers can be local too.
    Moved {
        stack: Stack,
        replaced: Vec<Option<Grid<DVec3>>>,
        rows: Vec<Option<RowSpan>>,
    },
    /// `B`'s levels read something of `A` that changed, the depths differ,
    /// the join is G2 (a G2 chain is one net) or no longer valid: build `B`
    /// whole (its error is the whole build's). `B`'s old stack, handed back.
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

impl RowSpan {
    /// The span of `rows` (`None` when empty).
    fn of(rows: &[usize]) -> Option<Self> {
        Some(RowSpan {
            lo: *rows.iter().min()?,
            hi: *rows.iter().max()?,
        })
    }
}

/// A stack's levels and each depth's points, borrowed: a stack as it was
/// before an edit, whose parts may be held apart.
#[derive(Debug, Clone, Copy)]
pub struct StackRef<'a> {
    /// Levels `0 ..= d`.
    pub levels: &'a [Level],
    /// The streamline points of each level.
    pub points: &'a [&'a Grid<DVec3>],
}

impl<'a> StackRef<'a> {
    /// The finest depth `d`.
    fn depth(&self) -> u32 {
        self.levels.len().saturating_sub(1) as u32
    }

    /// The points of `stack` before a [`Rejoin::Moved`] replaced
    /// `replaced` (into `out`, which the view borrows).
    pub fn points_before(
        stack: &'a Stack,
        replaced: &'a [Option<Grid<DVec3>>],
        out: &mut Vec<&'a Grid<DVec3>>,
    ) {
        out.clear();
        out.extend(
            stack
                .points
                .iter()
                .enumerate()
                .map(|(d, p)| replaced.get(d).and_then(Option::as_ref).unwrap_or(p)),
        );
    }
}

/// The points of a stack, borrowed one by one (for a [`StackRef`]).
pub fn point_refs(stack: &Stack) -> Vec<&Grid<DVec3>> {
    stack.points.iter().collect()
}

/// `B` (its design `b`, as joined, and its stack `b_old` built on `a_old`)
/// after `A` changed from `a_old` to `a_new` (both `A`'s stacks; `a` is
/// `A`'s new design), joined on `edge` with `continuity` (module
/// documentation).
pub fn rejoin(
    a: &Design,
    a_old: StackRef,
    a_new: &Stack,
    b: &Design,
    b_old: Stack,
    edge: Edge,
    continuity: Continuity,
) -> Rejoin {
    let depth = a_new.depth();
    if continuity == Continuity::G2 || a_old.depth() != depth || b_old.depth() != depth {
        return Rejoin::Rebuild(b_old);
    }
    let placed = match edge {
        Edge::End => rechain(a, a_old, a_new, b, &b_old, continuity),
        Edge::First | Edge::Last => reside(a_old, a_new, b, &b_old, edge, continuity),
    };
    match placed {
        None => Rejoin::Rebuild(b_old),
        Some(points) if points.iter().all(Option::is_none) => Rejoin::Unchanged(b_old),
        Some(points) => {
            let Stack {
                levels,
                points: mut old,
            } = b_old;
            let mut rows = Vec::with_capacity(points.len());
            let replaced = old
                .iter_mut()
                .zip(points)
                .map(|(slot, p)| {
                    rows.push(p.as_ref().map(|(_, span)| *span));
                    p.map(|(p, _)| std::mem::replace(slot, p))
                })
                .collect();
            Rejoin::Moved {
                stack: Stack {
                    levels,
                    points: old,
                },
                replaced,
                rows,
            }
        }
    }
}

/// `B`'s new points at each depth with the rows placed again (`None`: as
/// they were), or `None` when its levels must be made again.
type Placed = Option<Vec<Option<(Grid<DVec3>, RowSpan)>>>;

/// `old` (`B`'s points on `level`) with the rows whose start in `starts`
/// is not bit for bit their first point placed again (Eq. 65, as
/// [`place_at_starts`] places every row; the rows are independent, so the
/// others are copied); `None` when no start moved or the sizes differ.
fn replace_moved(
    level: &Level,
    old: &Grid<DVec3>,
    starts: &[DVec3],
) -> Option<(Grid<DVec3>, RowSpan)> {
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
    if old.rows() != rows || old.cols() != cols + 1 || starts.len() != rows {
        // sizes differ (not a stack of this level): every row again
        let all = place_at_starts(level, starts);
        let span = RowSpan::of(&(0..rows).collect::<Vec<_>>())?;
        return Some((all, span));
    }
    let moved: Vec<usize> = (0..rows)
        .filter(|&r| bits(old.get(r, 0)) != bits(starts[r]))
        .collect();
    let span = RowSpan::of(&moved)?;
    let mut out = old.clone();
    for &r in &moved {
        let s = level.params.s.row(r);
        place_slice(level.tangents.row(r), s, s[0], starts[r], out.row_mut(r));
    }
    Some((out, span))
}

/// The bits of a vector.
fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

/// Two slices of vectors bit for bit equal.
fn same(a: &[DVec3], b: &[DVec3]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| bits(*x) == bits(*y))
}

/// A chain (docs/math.md §11.1): `B`'s levels read `A`'s `t` and (G1) last
/// tangent column at every depth; its points start on `A`'s last points.
fn rechain(
    a: &Design,
    a_old: StackRef,
    a_new: &Stack,
    b: &Design,
    b_old: &Stack,
    continuity: Continuity,
) -> Placed {
    check_chain(a, b, continuity).ok()?;
    if a_old.levels.len() != a_new.levels.len() || a_old.points.len() != a_new.points.len() {
        return None;
    }
    for (lo, ln) in a_old.levels.iter().zip(&a_new.levels) {
        let (to, tn) = (&lo.params.t, &ln.params.t);
        if to.len() != tn.len() || to.iter().zip(tn).any(|(x, y)| x.to_bits() != y.to_bits()) {
            return None;
        }
        if continuity == Continuity::G1 {
            let (co, cn) = (lo.tangents.cols(), ln.tangents.cols());
            if co != cn
                || lo.tangents.rows() != ln.tangents.rows()
                || !same(&lo.tangents.column(co - 1), &ln.tangents.column(cn - 1))
            {
                return None;
            }
        }
    }
    let mut out = Vec::with_capacity(b_old.points.len());
    for (((po, pn), level), bp) in (a_old.points.iter().zip(&a_new.points))
        .zip(&b_old.levels)
        .zip(&b_old.points)
    {
        let (old, new) = (po.column(po.cols() - 1), pn.column(pn.cols() - 1));
        if old.len() != level.tangents.rows() || new.len() != old.len() {
            return None;
        }
        out.push(replace_moved(level, bp, &new));
    }
    Some(out)
}

/// A side join (docs/math.md §11.2): `B`'s levels read `A`'s edge curve
/// only for G1; its points start on that curve at `B`'s `t`.
fn reside(
    a_old: StackRef,
    a_new: &Stack,
    b: &Design,
    b_old: &Stack,
    edge: Edge,
    continuity: Continuity,
) -> Placed {
    let old: Vec<EdgeCurve> = (0..=a_old.depth())
        .map(|d| EdgeCurve::at(a_old.levels, a_old.points.get(d as usize)?, d, edge))
        .collect::<Option<_>>()?;
    let new: Vec<EdgeCurve> = (0..=a_new.depth())
        .map(|d| EdgeCurve::of(a_new, d, edge))
        .collect::<Option<_>>()?;
    if old.len() != new.len() {
        return None;
    }
    check_rows(&b.params().t, new[0].length()).ok()?;
    if continuity == Continuity::G1 && !old.iter().zip(&new).all(|(o, n)| o.same_bits(n)) {
        return None;
    }
    Some(
        (b_old.levels.iter().zip(&b_old.points))
            .zip(old.iter().zip(&new))
            .map(|((level, bp), (o, curve))| {
                if o.same_bits(curve) {
                    return None;
                }
                let starts: Vec<DVec3> = level.params.t.iter().map(|&t| curve.point(t)).collect();
                replace_moved(level, bp, &starts)
            })
            .collect(),
    )
}
