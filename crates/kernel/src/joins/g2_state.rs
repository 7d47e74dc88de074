//! A G2 run kept between edits (docs/math.md §11.1, Eqs. 68–70; docs/math.md
//! §5 for the incremental levels): after a local edit a G2 chain re-blends
//! the merged window only.
//!
//! [`super::merged::g2_run`] subdivides the run's merged net whole. A
//! [`G2State`] keeps the merged net's levels ([`LevelState`]), so that after
//! an edit of one patch's tangents or `s` only the merged window those cells
//! reach is re-blended ([`propagate`]), only the rows of that window (and
//! the rows whose start point on the initial curve moved) are integrated
//! again, and only those rows of each patch's [`Stack`] are cut again in
//! place (none of a patch left of the window, whose points read nothing it
//! changed). The result is bit for bit what `g2_run` builds: the incremental
//! levels are the whole build's (docs/math.md §5), a row's points read only
//! that row's tangents, parameters and start (Eq. 65), and the cut is the
//! same per row (Eq. 70).

use crate::bits::bits;
use crate::grid::Grid;
use crate::joins::error::JoinError;
use crate::joins::g2_recut::{RowJob, place_and_cut};
use crate::joins::merged::{MergedRun, check_no_tuning, cut, cuts, merge_g2, merged_details};
use crate::joins::parts::PatchParts;
use crate::joins::stack::RowSpan;
use crate::joins::stack::Stack;
use crate::levels::design::Design;
use crate::levels::dirty_window::{DirtyWindow, Span};
use crate::levels::incremental::{LevelState, build_levels, propagate};
use crate::levels::multires::Details;
use crate::streamline::integrate::{place_slice, segment_at};
use glam::DVec3;

/// A G2 run's merged levels at every depth `0 ..= d` (their points are
/// held by the patches' stacks, cut).
#[derive(Debug, Clone)]
pub struct G2State {
    run: MergedRun,
    /// The members' details at their merged places ([`merged_details`]).
    details: Details,
    levels: Vec<LevelState>,
    /// Each level's row starts on the initial curve (Eq. 65's origins).
    origins: Vec<Vec<DVec3>>,
}

/// What an [`G2State::update`] did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct G2Update {
    /// Per patch: whether its stack may have changed (every stack that
    /// changed, and those whose rows were cut again; a patch left of the
    /// edit's window, whose points read nothing it changed, is not).
    pub changed: Vec<bool>,
    /// Per patch, the rows of the finest depth whose points were placed
    /// again (`None`: none; a whole build, every row), so that what reads
    /// the points (the mesh normals, the drawing) can be local too.
    pub rows: Vec<Option<RowSpan>>,
    /// Per patch, the first column of its finest points placed again in
    /// those rows (the columns before it kept their bits; 0 with a whole
    /// build), so that the mesh normals, which read a point's neighbours
    /// (docs/math.md §4), can be made again from one column before it.
    pub cols: Vec<usize>,
    /// Per depth `0 ..= d`, the rows of every patch's level whose tangents
    /// or parameters may have changed (the merged window's rows: the
    /// patches of a run share their rows; `None`: none; a whole build,
    /// every row).
    pub levels: Vec<Option<RowSpan>>,
    /// Merged tangents re-blended, over all levels (a whole build counts
    /// every entry of levels `1 ..= d`).
    pub reblended: usize,
    /// Whether the run was built whole (its shape, depth, scheme, blend
    /// order or anchor changed, or an update failed).
    pub whole: bool,
}

/// What a level's recut marks of each patch: whether it was written, and
/// (at the finest depth) the rows of its points placed again.
struct Marks<'a> {
    changed: &'a mut [bool],
    rows: Option<&'a mut [Option<RowSpan>]>,
    /// With `rows`: each patch's first column placed again.
    cols: &'a mut [usize],
}

/// The tangents of levels `1 ..= d` (what a whole build re-blends).
fn whole_count(levels: &[LevelState]) -> usize {
    levels
        .iter()
        .skip(1)
        .map(|l| l.shape().0 * l.shape().1)
        .sum()
}

impl G2State {
    /// The merged tangents a whole build blends: every entry of levels
    /// `1 ..= d` (what [`G2Update::reblended`] counts for one).
    pub fn whole_count(&self) -> usize {
        whole_count(&self.levels)
    }

    /// The run of `patches` built whole to `depth`, and each patch's stack
    /// (bit for bit [`super::merged::g2_run`]'s).
    pub fn build(patches: &[&Design], depth: u32) -> Result<(Self, Vec<Stack>), JoinError> {
        let parts: Vec<PatchParts> = patches.iter().map(|&d| d.into()).collect();
        Self::build_parts(&parts, depth)
    }

    /// [`Self::build`] of patches with their details (bit for bit
    /// [`super::merged::g2_run_parts`]'s); fine tuning is refused.
    pub fn build_parts(
        patches: &[PatchParts],
        depth: u32,
    ) -> Result<(Self, Vec<Stack>), JoinError> {
        check_no_tuning(patches)?;
        let designs: Vec<&Design> = patches.iter().map(|p| p.design).collect();
        let run = merge_g2(&designs)?;
        let details = merged_details(&run, patches, depth);
        let levels = build_levels(&run.design, &details, depth)?;
        let origins: Vec<Vec<DVec3>> = levels.iter().map(|l| origins(&run.design, l)).collect();
        let me = G2State {
            run,
            details,
            levels,
            origins,
        };
        let stacks = me.stacks(patches.len());
        Ok((me, stacks))
    }

    /// The finest depth `d`.
    pub fn depth(&self) -> u32 {
        self.levels.len().saturating_sub(1) as u32
    }

    /// The merged design (docs/math.md Eq. 68).
    pub fn design(&self) -> &Design {
        &self.run.design
    }

    /// Every patch's stack, cut from the merged levels (Eqs. 69–70).
    fn stacks(&self, n: usize) -> Vec<Stack> {
        let scheme = self.run.design.scheme();
        let mut out: Vec<Stack> = (0..n)
            .map(|_| Stack {
                levels: Vec::new(),
                points: Vec::new(),
            })
            .collect();
        for (d, (level, origins)) in self.levels.iter().zip(&self.origins).enumerate() {
            let (rows, cols) = level.shape();
            let mut points = Grid::filled(rows, cols + 1, DVec3::ZERO);
            for (r, &origin) in origins.iter().enumerate().take(rows) {
                place_slice(
                    level.tangents.row(r),
                    level.params.s.row(r),
                    level.params.sigma[r],
                    origin,
                    points.row_mut(r),
                );
            }
            let points = &points;
            let cuts = cuts(scheme, &self.run.seams, d as u32, cols);
            for (p, stack) in out.iter_mut().enumerate() {
                let (part, pts) = cut(&level.tangents, &level.params, points, &cuts, p);
                stack.levels.push(part);
                stack.points.push(pts);
            }
        }
        out
    }

    /// Brings the run up to date with `patches` (the same run, each patch's
    /// design as it is now) at `depth`, and `stacks` (each patch's, as this
    /// state cut them last) with it: in place and inside the edit's window
    /// when only tangents and parameters changed, whole otherwise. On an
    /// error (the whole build's) the state must be built again.
    pub fn update(
        &mut self,
        patches: &[&Design],
        depth: u32,
        stacks: &mut Vec<Stack>,
    ) -> Result<G2Update, JoinError> {
        let parts: Vec<PatchParts> = patches.iter().map(|&d| d.into()).collect();
        self.update_parts(&parts, depth, stacks)
    }

    /// [`Self::update`] of patches with their details: when the details
    /// changed the run is built whole.
    pub fn update_parts(
        &mut self,
        patches: &[PatchParts],
        depth: u32,
        stacks: &mut Vec<Stack>,
    ) -> Result<G2Update, JoinError> {
        check_no_tuning(patches)?;
        let designs: Vec<&Design> = patches.iter().map(|p| p.design).collect();
        let run = merge_g2(&designs)?;
        let n = patches.len();
        let same_details = merged_details(&run, patches, depth) == self.details;
        let fits = same_details && self.fits(&run, depth) && self.cut_as(stacks, n);
        let seed = if fits { self.seed(&run) } else { None };
        let Some(seed) = seed else {
            return self.rebuild(patches, depth, stacks);
        };
        // the rows' starts stay unless the initial curve or a `t` changes
        let same_curve = (self.run.design.initial()).same_bits(run.design.initial());
        self.run = run;
        let mut prop_dirty: Vec<Option<DirtyWindow>> = vec![None; self.levels.len()];
        let (mut reblended, mut params) = (0, false);
        if let Some(w) = seed {
            let mut refs: Vec<&mut LevelState> = self.levels.iter_mut().collect();
            match propagate(&self.run.design, &self.details, &mut refs, &[Some(w)]) {
                Ok(p) => {
                    reblended = p.reblended;
                    params = p.params;
                    prop_dirty = p.dirty;
                }
                // s stopped increasing somewhere: the whole build's error
                Err(_) => return self.rebuild(patches, depth, stacks),
            }
        }
        let levels = (prop_dirty.iter())
            .map(|w| w.map(|w| RowSpan::from(w.rows)))
            .collect();
        let mut changed = vec![false; n];
        let mut rows = vec![None; n];
        let mut cols = vec![usize::MAX; n];
        let last = self.levels.len() - 1;
        for (d, w) in prop_dirty.into_iter().enumerate() {
            let marks = Marks {
                changed: &mut changed,
                rows: (d == last).then_some(&mut rows[..]),
                cols: &mut cols,
            };
            self.recut_level(d, w, params, same_curve && !params, stacks, marks);
        }
        for c in &mut cols {
            if *c == usize::MAX {
                *c = 0;
            }
        }
        Ok(G2Update {
            changed,
            rows,
            cols,
            levels,
            reblended,
            whole: false,
        })
    }

    /// Level `d` brought up to date in every stack after its merged
    /// window `window` was re-blended: the rows of the window, and those
    /// whose start on the initial curve moved, placed again (Eq. 65) and
    /// cut into each patch's points (Eq. 70), and the window's tangents and
    /// (when `params`, some parameter of the edit changed) parameters cut
    /// into each patch's level; `changed` marks the patches written. With
    /// `same_starts` (the initial curve and every `t` as they were) the
    /// rows' starts are not computed again.
    fn recut_level(
        &mut self,
        d: usize,
        window: Option<DirtyWindow>,
        params: bool,
        same_starts: bool,
        stacks: &mut [Stack],
        marks: Marks,
    ) {
        let Marks {
            changed,
            rows: placed,
            cols: first_col,
        } = marks;
        let scheme = self.run.design.scheme();
        let level = &self.levels[d];
        let origins = if same_starts {
            self.origins[d].clone()
        } else {
            origins(&self.run.design, level)
        };
        // the rows whose points are placed again: the window's, and
        // those whose start moved (the initial curve changed)
        let mut rows: Vec<bool> = vec![false; level.shape().0];
        if let Some(w) = window {
            rows[w.rows.lo..=w.rows.hi].fill(true);
        }
        for (r, (o, n)) in self.origins[d].iter().zip(&origins).enumerate() {
            rows[r] |= bits(*o) != bits(*n);
        }
        let before = std::mem::replace(&mut self.origins[d], origins);
        if !rows.contains(&true) {
            return;
        }
        let (nrows, cols) = level.shape();
        let cuts = cuts(scheme, &self.run.seams, d as u32, cols);
        // the window's tangents (and parameters) cut again into each
        // patch's level (every window row is placed again below)
        if let Some(w) = window {
            for r in w.rows.lo..=w.rows.hi {
                for (p, stack) in stacks.iter_mut().enumerate() {
                    let part = &mut stack.levels[d];
                    changed[p] |= recut_window_row(level, w, &cuts, p, params, part, r);
                }
            }
        }
        // the first merged column the window changed (none: only starts moved)
        let from = window.map_or(usize::MAX, |w| w.cols.lo);
        let jobs: Vec<RowJob> = (0..nrows)
            .filter(|&r| rows[r])
            .filter_map(|r| {
                let moved = bits(before[r]) != bits(self.origins[d][r]);
                let k = segment_at(level.params.s.row(r), level.params.sigma[r]);
                // a patch's points read the merged tangents up to its last
                // column and `s` one further, and the anchor's segment (Eq.
                // 65): left of the window, they are as they were (the
                // patches kept are the first ones, as the cuts increase)
                let kept = |p: usize| !moved && cuts[p + 1].max(k) + 1 < from;
                let first = (0..stacks.len()).find(|&p| !kept(p))?;
                // the row summed again from the point before the window
                // (its sums up to there read nothing the window changed),
                // and only what changed cut again: the same bits as
                // placing it whole
                let again = match from.checked_sub(1) {
                    Some(a) if !moved && (1..cols).contains(&a) => a,
                    _ => 0,
                };
                Some(RowJob { r, first, again })
            })
            .collect();
        if jobs.is_empty() {
            return;
        }
        let done = place_and_cut(level, &self.origins[d], &cuts, &jobs, stacks, d);
        for (c, d) in changed.iter_mut().zip(&done.changed) {
            *c |= d;
        }
        if let Some(out) = placed {
            for (p, span) in done.spans.iter().enumerate() {
                out[p] = RowSpan::join(out[p], *span);
                first_col[p] = first_col[p].min(done.cols[p]);
            }
        }
    }

    /// Builds the run whole into `self` and `stacks` (every patch changed).
    fn rebuild(
        &mut self,
        patches: &[PatchParts],
        depth: u32,
        stacks: &mut Vec<Stack>,
    ) -> Result<G2Update, JoinError> {
        let (me, built) = match G2State::build_parts(patches, depth) {
            Ok(b) => b,
            Err(e) => {
                // half-written by a failed update: built whole next time
                self.levels.clear();
                return Err(e);
            }
        };
        *self = me;
        *stacks = built;
        Ok(G2Update {
            changed: vec![true; patches.len()],
            rows: (stacks.iter())
                .map(|s| {
                    let n = s.finest_points().rows();
                    (n > 0).then(|| RowSpan { lo: 0, hi: n - 1 })
                })
                .collect(),
            cols: vec![0; patches.len()],
            levels: (self.levels.iter())
                .map(|l| l.shape().0.checked_sub(1).map(|hi| RowSpan { lo: 0, hi }))
                .collect(),
            reblended: whole_count(&self.levels),
            whole: true,
        })
    }

    /// Whether `run` at `depth` has this state's shape (what an update in
    /// place keeps): depth, merged net size, seams, scheme, blend order and
    /// anchor.
    fn fits(&self, run: &MergedRun, depth: u32) -> bool {
        let (a, b) = (&self.run.design, &run.design);
        !self.levels.is_empty()
            && self.depth() == depth
            && a.net().rows() == b.net().rows()
            && a.net().cols() == b.net().cols()
            && self.run.seams == run.seams
            && a.scheme() == b.scheme()
            && a.order() == b.order()
            && a.anchor() == b.anchor()
    }

    /// Whether `stacks` are `n` stacks of the shapes this state cuts.
    fn cut_as(&self, stacks: &[Stack], n: usize) -> bool {
        let scheme = self.run.design.scheme();
        stacks.len() == n
            && stacks.iter().all(|s| s.levels.len() == self.levels.len())
            && self.levels.iter().enumerate().all(|(d, level)| {
                let (rows, cols) = level.shape();
                let cuts = cuts(scheme, &self.run.seams, d as u32, cols);
                stacks.iter().enumerate().all(|(p, s)| {
                    let w = cuts[p + 1] - cuts[p] + 1;
                    let (l, pts) = (&s.levels[d], &s.points[d]);
                    l.tangents.rows() == rows
                        && l.tangents.cols() == w
                        && l.params.s.rows() == rows
                        && l.params.s.cols() == w
                        && l.params.t.len() == rows
                        && l.params.sigma.len() == rows
                        && pts.rows() == rows
                        && pts.cols() == w + 1
                })
            })
    }

    /// The window of the merged control net that differs from `run`'s (its
    /// tangents, `s`; a row whose `t` or `σ` differs, whole):
    /// `Some(None)` when nothing does.
    fn seed(&self, run: &MergedRun) -> Option<Option<DirtyWindow>> {
        let (a, b) = (&self.run.design, &run.design);
        let (pa, pb) = (a.params(), b.params());
        let cols = a.net().cols();
        let mut win: Option<DirtyWindow> = None;
        let mut add = |w: DirtyWindow| win = Some(DirtyWindow::merge(win, w));
        for r in 0..a.net().rows() {
            let whole_row = pa.t[r].to_bits() != pb.t[r].to_bits()
                || pa.sigma[r].to_bits() != pb.sigma[r].to_bits();
            if whole_row {
                add(DirtyWindow {
                    rows: Span::single(r),
                    cols: Span::all(cols),
                });
                continue;
            }
            let (ta, tb) = (a.net().row(r), b.net().row(r));
            let (sa, sb) = (pa.s.row(r), pb.s.row(r));
            for c in 0..cols {
                if bits(ta[c]) != bits(tb[c]) || sa[c].to_bits() != sb[c].to_bits() {
                    add(DirtyWindow::cell(r, c));
                }
            }
        }
        Some(win)
    }
}

/// Each row's start on the initial curve at `level`'s `t` (Eq. 65's origin).
fn origins(design: &Design, level: &LevelState) -> Vec<DVec3> {
    level
        .params
        .t
        .iter()
        .map(|&t| design.initial().point(t))
        .collect()
}

/// Row `r` (of window `w`'s rows) of patch `p`'s level (`part`) cut again
/// from the merged `level` inside its window `w` (Eq. 69): the tangents of
/// the window's cells in the patch's columns and, when `params` (an edit
/// that changed a parameter; else they are as they were), their `s` and the
/// row's `t` and `σ` (the first patch's merged `σ`, a later one's first
/// `s`). Whether any of them changed.
fn recut_window_row(
    level: &LevelState,
    w: DirtyWindow,
    cuts: &[usize],
    p: usize,
    params: bool,
    part: &mut crate::levels::design::Level,
    r: usize,
) -> bool {
    let (lo, hi) = (cuts[p], cuts[p + 1]);
    let mut changed = false;
    let (c0, c1) = (w.cols.lo.max(lo), w.cols.hi.min(hi));
    if params {
        let sigma = if p == 0 {
            level.params.sigma[r]
        } else {
            level.params.s.get(r, lo)
        };
        changed |= assign_f64(&mut part.params.t[r..=r], &level.params.t[r..=r]);
        changed |= assign_f64(&mut part.params.sigma[r..=r], &[sigma]);
    }
    if c0 > c1 {
        return changed;
    }
    changed |= assign(
        &mut part.tangents.row_mut(r)[c0 - lo..=c1 - lo],
        &level.tangents.row(r)[c0..=c1],
    );
    if params {
        changed |= assign_f64(
            &mut part.params.s.row_mut(r)[c0 - lo..=c1 - lo],
            &level.params.s.row(r)[c0..=c1],
        );
    }
    changed
}

/// Writes `from` into `to` (of the same length); whether some bit
/// differed. Compared up to the first difference, copied from there (in a
/// drag's frame the first cell of a window row differs: the row is copied,
/// not compared cell by cell).
fn assign(to: &mut [DVec3], from: &[DVec3]) -> bool {
    let Some(k) = to.iter().zip(from).position(|(t, f)| bits(*t) != bits(*f)) else {
        return false;
    };
    to[k..].copy_from_slice(&from[k..]);
    true
}

/// [`assign`] for numbers.
fn assign_f64(to: &mut [f64], from: &[f64]) -> bool {
    let mut differs = false;
    for (t, f) in to.iter_mut().zip(from) {
        differs |= t.to_bits() != f.to_bits();
        *t = *f;
    }
    differs
}
