//! One patch kept between edits, on its own initial curve or on an edge of
//! an earlier patch (docs/math.md §5, §11.1, §11.2): after an edit of its
//! own tangents or `s`, or of what it reads of its parent, each depth
//! re-blends only the window the edit reaches ([`LevelState`]) and places
//! again only the rows whose tangents, parameters or start changed (Eq. 65:
//! a row reads only its own tangents, parameters and start point).
//!
//! The result is bit for bit the whole build's ([`Stack::build_parts`],
//! [`super::chain::chain`], [`super::side::side`]): the windowed step is
//! the whole step per entry (docs/math.md §5), and a join's fix of each
//! level — a chain's `t` and G1 seam column (Eqs. 66–67), a side join's
//! `σ` and G1 projection (Eq. 73) — is made again on every row after the
//! level's step and compared bit for bit, so that what it changes joins
//! the window the next step reads. A side G1 projection is made from the
//! column before it; that column is kept per level ([`PatchState`]), so a
//! move of the parent's edge projects again without re-blending.
//!
//! The levels' tangents and parameters are held once, by the patch's
//! stack: an update lends them to the state, re-blends and fixes them in
//! place and gives them back, so no window is copied between the two.
//!
//! Fine tuning reads every row of a level (its constraint, docs/math.md
//! §6): a tuned level whose tangents, parameters or starts changed places
//! all its rows again, while its levels are still re-blended in the window
//! only. A change of the net's shape, scheme, blend order, anchor, depth,
//! details or kind of start builds whole ([`PatchUpdate::whole`]).

use crate::bits::bits;
use crate::finetune::SurfaceTuning;
use crate::joins::error::JoinError;
use crate::joins::kinds::{Continuity, Edge};
use crate::joins::parts::PatchParts;
pub use crate::joins::patch_start::Start;
use crate::joins::patch_start::{Kind, Parent, place_level, place_row, whole};
use crate::joins::stack::{RowSpan, Stack};
use crate::levels::design::{Design, Level};
use crate::levels::dirty_window::{DirtyWindow, Span};
use crate::levels::incremental::LevelState;
use crate::levels::multires::Details;
use glam::DVec3;

/// A patch's levels kept between edits, with what their fix and their
/// placement read (module documentation).
#[derive(Debug, Clone)]
pub struct PatchState {
    kind: Kind,
    /// The design as last built.
    design: Design,
    details: Details,
    tuning: Option<SurfaceTuning>,
    /// Each level's blend state; its tangents and parameters are the
    /// stack's, lent to it during an update ([`lend`]) and empty between.
    levels: Vec<LevelState>,
    /// Each level's shape (rows, columns), to check a stack against.
    shapes: Vec<(usize, usize)>,
    /// Per level, column 0 before a G1 join's fix (after the step and the
    /// details); empty for other starts. The next update's step reads it
    /// there: an in-place step (s-first Kobbelt) reads the level's own
    /// entries outside its window, which must be the step's, not the fix's.
    before: Vec<Vec<DVec3>>,
    /// Per level, each row's start: a joined row's first point, or the
    /// point of the initial curve at the row's `t` (Eq. 65's origin).
    starts: Vec<Vec<DVec3>>,
}

/// What a [`PatchState::update`] did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PatchUpdate {
    /// Per depth, the first and last row placed again (`None`: none).
    pub rows: Vec<Option<RowSpan>>,
    /// Tangents re-blended over the levels `1 ..= d` (a whole build counts
    /// every entry).
    pub reblended: usize,
    /// Whether the patch was built whole.
    pub whole: bool,
}

impl PatchUpdate {
    /// What a whole build of `stack` did: every row placed, every tangent
    /// of levels `1 ..= d` blended.
    pub fn whole(stack: &Stack) -> Self {
        PatchUpdate {
            rows: (stack.points.iter())
                .map(|p| {
                    (p.rows() > 0).then(|| RowSpan {
                        lo: 0,
                        hi: p.rows() - 1,
                    })
                })
                .collect(),
            reblended: (stack.levels.iter().skip(1))
                .map(|l| l.tangents.data().len())
                .sum(),
            whole: true,
        }
    }
}

/// The tangents and parameters of a [`LevelState`], moved out (its own
/// left empty: between updates the patch's stack holds them, [`lend`]).
fn take_level(s: &mut LevelState) -> Level {
    let empty = Level {
        tangents: crate::grid::Grid::filled(0, 0, DVec3::ZERO),
        params: crate::levels::params::ParamGrid {
            s: crate::grid::Grid::filled(0, 0, 0.0),
            t: Vec::new(),
            sigma: Vec::new(),
        },
    };
    let mut out = empty;
    lend_one(s, &mut out);
    out
}

/// Swaps a level's tangents and parameters between the state and `level`.
fn lend_one(s: &mut LevelState, level: &mut Level) {
    std::mem::swap(&mut s.tangents, &mut level.tangents);
    std::mem::swap(&mut s.params, &mut level.params);
}

/// Swaps every level's tangents and parameters between the state's
/// `levels` and `stack`'s: the state keeps one copy of them, the stack's
/// (module documentation), and an update borrows it to re-blend in place
/// and gives it back, so that no window is copied from one to the other.
fn lend(levels: &mut [LevelState], stack: &mut Stack) {
    for (s, level) in levels.iter_mut().zip(&mut stack.levels) {
        lend_one(s, level);
    }
}

/// `span` with row `r` added.
fn add_row(span: Option<Span>, r: usize) -> Option<Span> {
    Some(span.map_or(Span::single(r), |s| s.union(Span::single(r))))
}

impl PatchState {
    /// `parts` on `start` built whole to `depth` (an edge start builds to
    /// its parent's depth, as the joins do): the state and the stack, bit
    /// for bit the whole build's, or its error.
    pub fn build(parts: PatchParts, start: Start, depth: u32) -> Result<(Self, Stack), JoinError> {
        match Self::build_mine(parts, start, depth) {
            Ok(built) => Ok(built),
            // the whole build's own error (its checks, in its order)
            Err(mine) => Err(whole(parts, start, depth).err().unwrap_or(mine)),
        }
    }

    fn build_mine(parts: PatchParts, start: Start, depth: u32) -> Result<(Self, Stack), JoinError> {
        let design = parts.design;
        let parent = Parent::of(design, start)?;
        let depth = match start {
            Start::Edge { a, .. } => a.depth(),
            Start::Curve => depth,
        };
        let net = design.net();
        design.scheme().check_depth(net.rows(), net.cols(), depth)?;
        let details = parts.details.cloned().unwrap_or_default();
        let g1 = matches!(parent.kind, Kind::Edge(_, Continuity::G1));
        let mut levels: Vec<LevelState> = Vec::with_capacity(depth as usize + 1);
        let mut before: Vec<Vec<DVec3>> = Vec::new();
        for d in 0..=depth as usize {
            let mut level = match levels.last() {
                None => LevelState::root(design),
                Some(prev) => LevelState::child(design, &details, prev)?,
            };
            let (rows, cols) = level.shape();
            let mut col = vec![DVec3::ZERO; if g1 { rows } else { 0 }];
            let all = Some(DirtyWindow::all(rows, cols));
            parent.fix(d, &mut level, all, &mut col)?;
            if g1 {
                before.push(col);
            }
            levels.push(level);
        }
        let tuning = parts.tuning;
        let starts: Vec<Vec<DVec3>> = (levels.iter().enumerate())
            .map(|(d, ls)| parent.starts(design, d, ls))
            .collect();
        let shapes = levels.iter().map(LevelState::shape).collect();
        let mut stack = Stack {
            levels: levels.iter_mut().map(take_level).collect(),
            points: Vec::with_capacity(levels.len()),
        };
        for (level, s) in stack.levels.iter().zip(&starts) {
            let points = place_level(parent.kind, design, level, s, tuning);
            stack.points.push(points);
        }
        let me = PatchState {
            kind: parent.kind,
            design: design.clone(),
            details,
            tuning: tuning.cloned(),
            levels,
            shapes,
            before,
            starts,
        };
        Ok((me, stack))
    }

    /// The finest depth `d`.
    pub fn depth(&self) -> u32 {
        self.levels.len().saturating_sub(1) as u32
    }

    /// Brings the patch up to date with `parts` on `start` at `depth`, and
    /// `stack` (this state's, as last built or updated) with it, in place
    /// (module documentation). On an error (the whole build's) the state
    /// and the stack must be built again.
    pub fn update(
        &mut self,
        parts: PatchParts,
        start: Start,
        depth: u32,
        stack: &mut Stack,
    ) -> Result<PatchUpdate, JoinError> {
        let design = parts.design;
        let depth = match start {
            Start::Edge { a, .. } => a.depth(),
            Start::Curve => depth,
        };
        // (compared, not cloned: an edit's update runs every frame of a drag)
        let same_details = parts
            .details
            .map_or(self.details.is_empty(), |d| *d == self.details);
        if !(same_details && self.fits(design, start, depth, stack)) {
            return self.rebuild(parts, start, depth, stack);
        }
        let seed = self.seed(design);
        let parent = Parent::of(design, start)?;
        match self.update_levels(parts, &parent, seed, stack) {
            Ok(u) => Ok(u),
            // a parameter stopped increasing or a projection was refused:
            // the whole build's error
            Err(mine) => {
                let e = whole(parts, start, depth).err().unwrap_or(mine);
                Err(e)
            }
        }
    }

    /// The whole build, into this state and `stack`.
    fn rebuild(
        &mut self,
        parts: PatchParts,
        start: Start,
        depth: u32,
        stack: &mut Stack,
    ) -> Result<PatchUpdate, JoinError> {
        let (me, built) = Self::build(parts, start, depth)?;
        *self = me;
        *stack = built;
        Ok(PatchUpdate::whole(stack))
    }

    /// Whether an update in place can bring this state to `design` on
    /// `start` at `depth`.
    fn fits(&self, design: &Design, start: Start, depth: u32, stack: &Stack) -> bool {
        let old = &self.design;
        let levels = depth as usize + 1;
        start.kind() == self.kind
            && self.levels.len() == levels
            && self.shapes.len() == levels
            && stack.levels.len() == levels
            && stack.points.len() == levels
            && old.net().rows() == design.net().rows()
            && old.net().cols() == design.net().cols()
            && old.scheme() == design.scheme()
            && old.order() == design.order()
            && old.anchor() == design.anchor()
            && (stack.levels.iter().zip(&self.shapes)).all(|(l, &(rows, cols))| {
                l.tangents.rows() == rows
                    && l.tangents.cols() == cols
                    && l.params.s.rows() == rows
                    && l.params.s.cols() == cols
                    && l.params.t.len() == rows
                    && l.params.sigma.len() == rows
            })
            && match start {
                Start::Edge {
                    a, edge: Edge::End, ..
                } => (a.levels.iter().zip(&self.shapes)).all(|(al, s)| al.tangents.rows() == s.0),
                _ => true,
            }
    }

    /// The window of level 0 that `design` changed against the design as
    /// last built (`None`: nothing).
    fn seed(&self, design: &Design) -> Option<DirtyWindow> {
        let (old, new) = (&self.design, design);
        let (rows, cols) = (new.net().rows(), new.net().cols());
        let mut rs: Option<Span> = None;
        let mut cs: Option<Span> = None;
        for r in 0..rows {
            let (on, nn) = (old.net().row(r), new.net().row(r));
            let (os, ns) = (old.params().s.row(r), new.params().s.row(r));
            for c in 0..cols {
                if bits(on[c]) != bits(nn[c]) || os[c].to_bits() != ns[c].to_bits() {
                    rs = add_row(rs, r);
                    cs = add_row(cs, c);
                }
            }
            let (ot, nt) = (old.params().t[r], new.params().t[r]);
            let (og, ng) = (old.params().sigma[r], new.params().sigma[r]);
            if ot.to_bits() != nt.to_bits() || og.to_bits() != ng.to_bits() {
                rs = add_row(rs, r);
                cs = add_row(cs, 0);
            }
        }
        rs.zip(cs).map(|(rows, cols)| DirtyWindow { rows, cols })
    }

    /// The update in place (module documentation): the levels are
    /// re-blended and fixed in the stack's own tangents and parameters,
    /// lent to the state ([`lend`]), then the moved rows are placed again.
    fn update_levels(
        &mut self,
        parts: PatchParts,
        parent: &Parent,
        seed: Option<DirtyWindow>,
        stack: &mut Stack,
    ) -> Result<PatchUpdate, JoinError> {
        let design = parts.design;
        let tuning_changed = parts.tuning != self.tuning.as_ref();
        // (given back also on an error: the stack then holds what the
        // failed update wrote, as when it was written in place)
        lend(&mut self.levels, stack);
        let stepped = self.step_levels(design, parent, seed);
        lend(&mut self.levels, stack);
        let (place, reblended) = stepped?;
        self.tuning = parts.tuning.cloned();
        let mut rows_out = Vec::with_capacity(place.len());
        for (d, place) in place.into_iter().enumerate() {
            let (old, points) = (&stack.levels[d], &mut stack.points[d]);
            let rows = old.tangents.rows();
            let placed = match parts.tuning {
                Some(t) if place.is_some() || tuning_changed => {
                    *points = place_level(parent.kind, design, old, &self.starts[d], Some(t));
                    Some(Span::all(rows))
                }
                Some(_) => None,
                None if tuning_changed => {
                    *points = place_level(parent.kind, design, old, &self.starts[d], None);
                    Some(Span::all(rows))
                }
                None => {
                    if let Some(p) = place {
                        for r in p.iter() {
                            place_row(parent.kind, old, self.starts[d][r], r, points.row_mut(r));
                        }
                    }
                    place
                }
            };
            rows_out.push(placed.map(|s| RowSpan { lo: s.lo, hi: s.hi }));
        }
        Ok(PatchUpdate {
            rows: rows_out,
            reblended,
            whole: false,
        })
    }

    /// Each level re-blended inside the edit's window and fixed again, in
    /// the tangents and parameters lent to the state, and each level's rows
    /// to place again (the window's, those whose `t`, `σ` or start moved),
    /// with the tangents re-blended.
    fn step_levels(
        &mut self,
        design: &Design,
        parent: &Parent,
        seed: Option<DirtyWindow>,
    ) -> Result<(Vec<Option<Span>>, usize), JoinError> {
        let same_curve = self.design.initial().same_bits(design.initial());
        // whether a parameter changed at level 0 (else the levels'
        // parameters are re-blended by no step)
        let params = seed.is_some_and(|w| {
            w.rows.iter().any(|r| {
                let (o, n) = (self.design.params(), design.params());
                o.t[r].to_bits() != n.t[r].to_bits()
                    || o.sigma[r].to_bits() != n.sigma[r].to_bits()
                    || (o.s.row(r).iter().zip(n.s.row(r))).any(|(x, y)| x.to_bits() != y.to_bits())
            })
        });
        self.design = design.clone();
        let mut reblended = 0;
        let mut out = Vec::with_capacity(self.levels.len());
        let mut window: Option<DirtyWindow> = None;
        for d in 0..self.levels.len() {
            let (above, below) = self.levels.split_at_mut(d);
            let level = &mut below[0];
            // column 0, `t` and `σ` as last built, to find what the fix moved
            let rows = level.tangents.rows();
            let col0: Vec<DVec3> = (0..rows).map(|r| level.tangents.get(r, 0)).collect();
            let (t_was, sigma_was) = (level.params.t.clone(), level.params.sigma.clone());
            // the step (level 0: the net itself, inside the seed)
            let fresh = match d {
                0 => seed.inspect(|w| {
                    for r in w.rows.iter() {
                        for c in w.cols.iter() {
                            level.tangents.set(r, c, design.net().get(r, c));
                            level.params.s.set(r, c, design.params().s.get(r, c));
                        }
                        level.params.t[r] = design.params().t[r];
                        level.params.sigma[r] = design.params().sigma[r];
                    }
                }),
                _ => match window {
                    Some(w) => {
                        if let Some(b) = self.before.get(d) {
                            for (r, &v) in b.iter().enumerate() {
                                level.tangents.set(r, 0, v);
                            }
                        }
                        let prev = &above[d - 1];
                        let (out, n) = level.update_with(design, &self.details, prev, w, params)?;
                        reblended += n.reblended;
                        Some(out)
                    }
                    None => None,
                },
            };
            let mut none: [DVec3; 0] = [];
            let before = match self.before.get_mut(d) {
                Some(b) => b.as_mut_slice(),
                None => &mut none[..],
            };
            parent.fix(d, level, fresh, before)?;
            // what the fix changed outside the step's window: column 0, `t`
            // and `σ`, against the level as it was
            let mut col: Option<Span> = None;
            let mut moved_rows: Option<Span> = None;
            for r in 0..rows {
                if bits(level.tangents.get(r, 0)) != bits(col0[r]) {
                    col = add_row(col, r);
                }
                if level.params.t[r].to_bits() != t_was[r].to_bits()
                    || level.params.sigma[r].to_bits() != sigma_was[r].to_bits()
                {
                    moved_rows = add_row(moved_rows, r);
                }
            }
            let col_window = col.map(|rows| DirtyWindow {
                rows,
                cols: Span { lo: 0, hi: 0 },
            });
            window = match (fresh, col_window) {
                (Some(f), Some(c)) => Some(f.union(c)),
                (f, c) => f.or(c),
            };
            // the rows to place again: the window's, those whose `t`, `σ`
            // or start moved
            let starts = match (parent.kind, same_curve, moved_rows) {
                // an own curve's origins read only `t` and the curve
                (Kind::Curve, true, None) => None,
                _ => Some(parent.starts(design, d, level)),
            };
            let mut place = window
                .map(|w| w.rows)
                .into_iter()
                .fold(moved_rows, |a, s| Some(a.map_or(s, |a| a.union(s))));
            if let Some(s) = &starts {
                for (r, (n, o)) in s.iter().zip(&self.starts[d]).enumerate() {
                    if bits(*n) != bits(*o) {
                        place = add_row(place, r);
                    }
                }
                self.starts[d].clone_from(s);
            }
            out.push(place);
        }
        Ok((out, reblended))
    }
}
