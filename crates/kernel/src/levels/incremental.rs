//! Subdivision levels kept between edits, updated inside dirty windows
//! (docs/architecture.md, "Incremental rebuild, exactly"; docs/math.md §5 for the details).
//!
//! A [`LevelState`] holds one level: the intermediate grid of its first blend
//! direction (none for s-first Kobbelt, `crate::levels::dirty_window::in_place`), the
//! *base* (subdivided, before details; kept only where the level has details),
//! the tangents (with the details of that level applied) and the parameters. [`LevelState::update`]
//! recomputes only the entries that read a dirty entry of the previous level,
//! with the same per-entry rules as the full step, so the result is identical
//! to a rebuild from scratch ([`reference_levels`]).

use crate::curve::scalar;
use crate::error::KernelError;
use crate::finetune::{
    Constraint, SurfaceRows, SurfaceTuning, fine_tune_into, fine_tune_rows_into,
};
use crate::grid::Grid;
use crate::levels::design::{Design, Level};
use crate::levels::dirty_window::{DirtyWindow, half_shape, refine_grid_window};
use crate::levels::multires::{self, Details};
use crate::levels::params::ParamGrid;
use crate::streamline::initial_curve::InitialCurve;
use crate::streamline::integrate::place_into;
use glam::DVec3;

/// One subdivision level and what is needed to update it in place.
#[derive(Debug, Clone, PartialEq)]
pub struct LevelState {
    /// Depth of this level (0 = the control net).
    pub level: u32,
    /// Intermediate grid of the first blend direction (empty at level 0 and
    /// where the step writes the next level in place, `crate::levels::dirty_window::in_place`).
    pub half: Grid<DVec3>,
    /// The same for the `s` parameters.
    pub half_s: Grid<f64>,
    /// Subdivided tangents before this level's details, kept from the first
    /// detail on this level; empty (`0 × 0`) while the level has none, when it
    /// equals `tangents` and is not copied ([`Self::base`]).
    base: Grid<DVec3>,
    /// Tangents with this level's details applied.
    pub tangents: Grid<DVec3>,
    /// Parameters of this level.
    pub params: ParamGrid,
}

/// What an update recomputed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct UpdateCount {
    /// Tangents re-blended (entries of `base` recomputed).
    pub reblended: usize,
    /// Details re-applied.
    pub details: usize,
}

impl LevelState {
    /// Level 0: the design's control net and parameters.
    pub fn root(design: &Design) -> Self {
        LevelState {
            level: 0,
            half: Grid::filled(0, 0, DVec3::ZERO),
            half_s: Grid::filled(0, 0, 0.0),
            base: Grid::filled(0, 0, DVec3::ZERO),
            tangents: design.net.clone(),
            params: design.params.clone(),
        }
    }

    /// Level `prev.level + 1`, built in full.
    pub fn child(
        design: &Design,
        details: &Details,
        prev: &LevelState,
    ) -> Result<Self, KernelError> {
        let (rows, cols) = (prev.tangents.rows(), prev.tangents.cols());
        let (nr, nc) = design.scheme.check_depth(rows, cols, 1)?;
        let (hr, hc) = half_shape(design.scheme, design.order, rows, cols);
        let mut me = LevelState {
            level: prev.level + 1,
            half: Grid::filled(hr, hc, DVec3::ZERO),
            half_s: Grid::filled(hr, hc, 0.0),
            base: Grid::filled(0, 0, DVec3::ZERO),
            tangents: Grid::filled(nr, nc, DVec3::ZERO),
            params: ParamGrid {
                s: Grid::filled(nr, nc, 0.0),
                t: vec![0.0; nr],
                sigma: vec![0.0; nr],
            },
        };
        me.update(design, details, prev, DirtyWindow::all(rows, cols))?;
        Ok(me)
    }

    /// Grid shape `(rows, cols)`.
    pub fn shape(&self) -> (usize, usize) {
        (self.tangents.rows(), self.tangents.cols())
    }

    /// The subdivided tangents before this level's details (docs/math.md §5: the grid
    /// whose local frames details are written in).
    pub fn base(&self) -> &Grid<DVec3> {
        if self.keeps_base() {
            &self.base
        } else {
            &self.tangents
        }
    }

    fn keeps_base(&self) -> bool {
        self.base.rows() != 0
    }

    /// Starts keeping the base apart from the tangents (before the first
    /// detail of this level is applied; until then they are equal).
    fn keep_base(&mut self, details: &Details) {
        if !self.keeps_base() && multires::has_level(details, self.level) {
            self.base.clone_from(&self.tangents);
        }
    }

    /// Recomputes the entries that read `win` of `prev` (its dirty window),
    /// then re-applies the details there (widened by one cell where this level
    /// has details, since a frame reads its neighbours). Returns this level's
    /// dirty window and the counts. Fails, leaving the window half-written, only
    /// if `s` stops increasing: callers validate parameter edits beforehand
    /// ([`check_params`]).
    pub fn update(
        &mut self,
        design: &Design,
        details: &Details,
        prev: &LevelState,
        win: DirtyWindow,
    ) -> Result<(DirtyWindow, UpdateCount), KernelError> {
        self.update_with(design, details, prev, win, true)
    }

    /// [`Self::update`], re-blending the parameters only when `params` is
    /// set: when no parameter of the previous level changed (an edit of
    /// directions alone), this level's parameters are still right.
    pub(crate) fn update_with(
        &mut self,
        design: &Design,
        details: &Details,
        prev: &LevelState,
        win: DirtyWindow,
        params: bool,
    ) -> Result<(DirtyWindow, UpdateCount), KernelError> {
        let (scheme, order) = (design.scheme, design.order);
        self.keep_base(details);
        let into = if self.keeps_base() {
            &mut self.base
        } else {
            &mut self.tangents
        };
        let out = refine_grid_window(scheme, order, &prev.tangents, &mut self.half, into, win);
        if params {
            refine_grid_window(
                scheme,
                order,
                &prev.params.s,
                &mut self.half_s,
                &mut self.params.s,
                win,
            );
            let c = scheme.curve();
            for r in out.rows.iter() {
                self.params.t[r] = scalar::at(c, &prev.params.t, r);
                self.params.sigma[r] = scalar::at(c, &prev.params.sigma, r);
            }
            check_window(&self.params, self.level, out)?;
        }
        let (rows, cols) = self.shape();
        if !self.keeps_base() {
            // no details here: the tangents are the base, written above
            return Ok((
                out,
                UpdateCount {
                    reblended: out.area(),
                    details: 0,
                },
            ));
        }
        let dirty = if multires::has_level(details, self.level) {
            out.widen(1, rows, cols)
        } else {
            out
        };
        let applied =
            multires::apply_window(&self.base, &mut self.tangents, details, self.level, dirty);
        Ok((
            dirty,
            UpdateCount {
                reblended: out.area(),
                details: applied,
            },
        ))
    }

    /// Re-applies the details of this level inside `win` (after a detail edit).
    pub(crate) fn reapply_details(&mut self, details: &Details, win: DirtyWindow) -> DirtyWindow {
        let (rows, cols) = self.shape();
        let win = win.widen(0, rows, cols);
        self.keep_base(details);
        if self.keeps_base() {
            multires::apply_window(&self.base, &mut self.tangents, details, self.level, win);
        }
        win
    }
}

fn check_window(p: &ParamGrid, level: u32, w: DirtyWindow) -> Result<(), KernelError> {
    let cols = p.s.cols();
    let (lo, hi) = (w.cols.lo.saturating_sub(1), (w.cols.hi + 1).min(cols - 1));
    for r in w.rows.iter() {
        let row = p.s.row(r);
        for c in lo..=hi {
            if !row[c].is_finite() {
                return Err(KernelError::NonFiniteParameter {
                    what: "arc-length parameter s",
                    at: crate::Place::Grid { row: r, col: c },
                });
            }
            if c > 0 && row[c] <= row[c - 1] {
                return Err(KernelError::ParamsNotIncreasing {
                    level,
                    at: crate::Place::Grid { row: r, col: c },
                });
            }
        }
    }
    Ok(())
}

/// Checks that the parameters of `design` stay strictly increasing down to `depth`.
pub fn check_params(design: &Design, depth: u32) -> Result<(), KernelError> {
    let mut p = design.params.clone();
    for d in 1..=depth {
        p = p.refine(design.scheme, design.order, d)?;
    }
    Ok(())
}

/// Levels `0 ..= depth` built in full with the incremental types.
pub fn build_levels(
    design: &Design,
    details: &Details,
    depth: u32,
) -> Result<Vec<LevelState>, KernelError> {
    design
        .scheme
        .check_depth(design.net.rows(), design.net.cols(), depth)?;
    let mut out = vec![LevelState::root(design)];
    for _ in 0..depth {
        let next = LevelState::child(design, details, out.last().expect("root"))?;
        out.push(next);
    }
    Ok(out)
}

/// An independent full rebuild, used as the reference in tests: each level is
/// the plain [`Design::refine`] of the previous level's tangents, then every
/// detail is applied from the frame of the refined (base) grid.
pub fn reference_levels(
    design: &Design,
    details: &Details,
    depth: u32,
) -> Result<Vec<Level>, KernelError> {
    let mut out = vec![design.base()];
    for d in 1..=depth {
        let mut next = design.refine(out.last().expect("level 0"), d)?;
        let base = next.tangents.clone();
        for (&(l, r, c), &local) in details.range((d, 0, 0)..=(d, usize::MAX, usize::MAX)) {
            debug_assert_eq!(l, d);
            if r < base.rows() && c < base.cols() {
                next.tangents
                    .set(r, c, multires::from_local(&base, r, c, local));
            }
        }
        out.push(next);
    }
    Ok(out)
}

/// Row `r` of a level placed on the initial curve (Eq. 65 and Eqs. 1–2).
pub fn place_row(
    initial: &InitialCurve,
    tangents: &Grid<DVec3>,
    params: &ParamGrid,
    r: usize,
    out: &mut Vec<DVec3>,
) {
    place_into(
        tangents.row(r),
        params.s.row(r),
        params.sigma[r],
        initial.point(params.t[r]),
        out,
    );
}

/// [`place_row`] with fine tuning (docs/math.md §6): row `r` scaled by its
/// function of [`SurfaceTuning::row_functions`]. Under a constraint that
/// function depends on every row (the correction is smooth across the
/// streamlines, (T5)), so this solves for the whole level: to place every
/// row, call [`place_rows_tuned`] once.
pub fn place_row_tuned(
    initial: &InitialCurve,
    tangents: &Grid<DVec3>,
    params: &ParamGrid,
    r: usize,
    tuning: Option<&SurfaceTuning>,
    out: &mut Vec<DVec3>,
) {
    let Some(tuning) = tuning else {
        return place_row(initial, tangents, params, r, out);
    };
    let rows = surface_rows(tangents, params);
    let f = if tuning.constraint == Constraint::Free {
        tuning.row_function(rows.v()[r])
    } else {
        tuning.row_functions(rows).swap_remove(r)
    };
    fine_tune_into(
        tangents.row(r),
        params.s.row(r),
        params.sigma[r],
        initial.point(params.t[r]),
        &f,
        Constraint::Free,
        out,
    );
}

/// Every row of a level placed on the initial curve, fine-tuned by `tuning`
/// when given (docs/math.md §6): the rows one after another in `out`,
/// `cols + 1` points each.
pub fn place_rows_tuned(
    initial: &InitialCurve,
    tangents: &Grid<DVec3>,
    params: &ParamGrid,
    tuning: Option<&SurfaceTuning>,
    out: &mut Vec<DVec3>,
) {
    out.clear();
    let Some(tuning) = tuning else {
        let mut row = Vec::new();
        for r in 0..tangents.rows() {
            place_row(initial, tangents, params, r, &mut row);
            out.extend_from_slice(&row);
        }
        return;
    };
    let origins: Vec<DVec3> = params.t.iter().map(|&t| initial.point(t)).collect();
    fine_tune_rows_into(surface_rows(tangents, params), &origins, tuning, out);
}

/// [`place_rows_tuned`] as a grid: the level's streamline points, one row per
/// streamline, `cols + 1` points each.
pub fn tuned_points(
    initial: &InitialCurve,
    tangents: &Grid<DVec3>,
    params: &ParamGrid,
    tuning: Option<&SurfaceTuning>,
) -> Grid<DVec3> {
    let (rows, cols) = (tangents.rows(), tangents.cols() + 1);
    let mut data = Vec::with_capacity(rows * cols);
    place_rows_tuned(initial, tangents, params, tuning, &mut data);
    Grid::new(rows, cols, data).expect("every row has cols + 1 points")
}

/// A level's rows as fine tuning reads them.
pub fn surface_rows<'a>(tangents: &'a Grid<DVec3>, params: &'a ParamGrid) -> SurfaceRows<'a> {
    SurfaceRows {
        tangents,
        s: &params.s,
        t: &params.t,
        sigma: &params.sigma,
    }
}

/// What [`propagate`] did at each level.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Propagation {
    /// The dirty window of each level (`None`: untouched).
    pub dirty: Vec<Option<DirtyWindow>>,
    /// Tangents re-blended over all levels.
    pub reblended: usize,
    /// Details re-applied over all levels.
    pub details: usize,
    /// Whether some parameter (`s`, `t` or σ) in the seed changed, so that
    /// the levels' parameters were re-blended too; when not, only tangents
    /// inside the dirty windows changed.
    pub params: bool,
}

/// Carries edits down the levels. `seeds[l]` is the window edited directly on
/// level `l` (level 0: control tangents or parameters, already changed in
/// `design`; deeper: details, already changed in `details`). `levels[0]` is
/// refreshed from `design` inside its seed, then each level recomputes what
/// reads a dirty entry of the level above: the parameters too only if some
/// parameter in the seed changed (parameters depend on parameters alone, so
/// an edit of directions leaves every level's parameters as they are).
pub fn propagate(
    design: &Design,
    details: &Details,
    levels: &mut [&mut LevelState],
    seeds: &[Option<DirtyWindow>],
) -> Result<Propagation, KernelError> {
    let mut prop = Propagation {
        dirty: vec![None; levels.len()],
        ..Default::default()
    };
    let mut params = false;
    if let (Some(root), Some(Some(w))) = (levels.first_mut(), seeds.first()) {
        let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
        for r in w.rows.iter() {
            for c in w.cols.iter() {
                root.tangents.set(r, c, design.net.get(r, c));
            }
            let cols = w.cols.lo..=w.cols.hi;
            let (old, new) = (
                &mut root.params.s.row_mut(r)[cols.clone()],
                &design.params.s.row(r)[cols],
            );
            params |= !same(old, new)
                || !same(
                    &[root.params.t[r], root.params.sigma[r]],
                    &[design.params.t[r], design.params.sigma[r]],
                );
            old.copy_from_slice(new);
            root.params.t[r] = design.params.t[r];
            root.params.sigma[r] = design.params.sigma[r];
        }
        prop.dirty[0] = Some(*w);
    }
    for l in 1..levels.len() {
        let (above, below) = levels.split_at_mut(l);
        let (prev, me) = (&*above[l - 1], &mut *below[0]);
        let mut dirty = None;
        if let Some(w) = prop.dirty[l - 1] {
            let (d, n) = me.update_with(design, details, prev, w, params)?;
            prop.reblended += n.reblended;
            prop.details += n.details;
            dirty = Some(d);
        }
        if let Some(Some(seed)) = seeds.get(l) {
            let w = me.reapply_details(details, *seed);
            dirty = Some(DirtyWindow::merge(dirty, w));
        }
        prop.dirty[l] = dirty;
    }
    prop.params = params;
    Ok(prop)
}
