//! The first patch's [`Stack`] kept up to date from its incremental
//! pipeline (docs/math.md §5, §11), for [`super::build::build_joined`]: the
//! patches that start on it and the seam reports read it, and so do the
//! editor's views and the tests (its [`super::PatchSurface`]).
//!
//! The stack is kept between edits and only what the pipeline changed is
//! written into it: each level's tangents and `s` inside the window the
//! blend stage re-blended ([`LevelWindow`]), its `t` and `σ`, the display
//! depth's points and mesh normals inside the window the mesh stage
//! announced ([`SurfaceChanges`]), and of the coarser depths' streamlines
//! only the rows whose tangents or parameters changed, or all of them when
//! the initial curve they start on did (each row is placed on its own,
//! Eq. 65, so the others keep their bits). The changes are gathered every frame ([`FirstPipeline::track`])
//! until the stack is next brought up to date, so a frame that does not
//! update it loses nothing. The result is bit for bit the whole build's
//! (the incremental build equals the whole one, docs/math.md §5; a first
//! patch with details, fine tuning or interpolated tangents is built whole
//! by [`super::build::build_joined`] instead, docs/math.md §11.4;
//! `tests/joined_patches.rs` compares every depth with
//! [`crate::scene::Document::build`] after each edit).

use crate::ecs::SurfaceData;
use crate::ecs::components::{LevelData, LevelWindow, SubdivisionLevel};
use crate::ecs::resources::{SurfaceChange, SurfaceChanges};
use bevy::prelude::*;
use streamline_kernel::joins::Stack;
use streamline_kernel::levels::design::Level;
use streamline_kernel::levels::dirty_window::DirtyWindow;
use streamline_kernel::levels::params::ParamGrid;
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::{DVec3, Design, Grid};

/// What changed of a grid since the stack was last brought up to date.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
enum Dirt {
    /// Nothing.
    #[default]
    Clean,
    /// The cells of a window.
    Cells(DirtyWindow),
    /// Everything (or not known).
    All,
}

impl Dirt {
    /// Both changes.
    fn merge(self, o: Dirt) -> Dirt {
        match (self, o) {
            (Dirt::Clean, x) | (x, Dirt::Clean) => x,
            (Dirt::Cells(a), Dirt::Cells(b)) => Dirt::Cells(a.union(b)),
            _ => Dirt::All,
        }
    }
}

/// The changes gathered since the stack was last brought up to date, and
/// where the stack's coarser streamlines start.
#[derive(Default)]
pub(crate) struct Pending {
    /// Per level, what changed of its tangents and `s`.
    levels: Vec<Dirt>,
    /// What changed of the display depth's points and normals.
    surface: Dirt,
    /// The patch whose stack was last made from the pipeline (`None`: no
    /// stack the changes can be written into).
    synced: Option<Entity>,
    /// What the initial curve the stack's streamlines start on was made
    /// from ([`curve_key`]).
    curve: Vec<u64>,
}

/// What an initial curve is made from, as bits: its QI curve's tangents,
/// order and knots, its length, origin and mirror. The curve's points are a
/// function of these alone, so two curves with the same key place every
/// streamline at the same point, bit for bit.
fn curve_key(c: &InitialCurve) -> Vec<u64> {
    let v = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut k: Vec<u64> = c.qi().tangents().iter().flat_map(|&t| v(t)).collect();
    k.push(c.qi().order() as u64);
    k.extend(c.qi().knots().iter().map(|x| x.to_bits()));
    k.push(c.length().to_bits());
    k.extend(v(c.origin()));
    if let Some((t0, plane)) = c.mirror() {
        k.push(t0.to_bits());
        k.extend(v(plane.point));
        k.extend(v(plane.normal));
    }
    k
}

/// A level entity of the first patch's pipeline, with its last window.
type LevelRow = (
    &'static SubdivisionLevel,
    Ref<'static, LevelData>,
    Option<Ref<'static, LevelWindow>>,
);

/// The first patch's pipeline, read: its level entities and its surface.
#[derive(bevy::ecs::system::SystemParam)]
pub(crate) struct FirstPipeline<'w, 's> {
    levels: Query<'w, 's, LevelRow>,
    surface: Res<'w, SurfaceData>,
    changes: SurfaceChanges<'w, 's>,
    pending: Local<'s, Pending>,
}

impl FirstPipeline<'_, '_> {
    /// Gathers what the pipeline changed since the last call: call it every
    /// frame, before anything returns early.
    pub(crate) fn track(&mut self) {
        let p = &mut *self.pending;
        p.surface = p.surface.merge(match self.changes.take() {
            SurfaceChange::Unchanged => Dirt::Clean,
            SurfaceChange::Window(w) => Dirt::Cells(w),
            SurfaceChange::All => Dirt::All,
        });
        for (l, data, window) in &self.levels {
            if !data.is_changed() {
                continue;
            }
            let l = l.0 as usize;
            if p.levels.len() <= l {
                p.levels.resize(l + 1, Dirt::Clean);
            }
            // the blend stage writes a level's window with the level; any
            // other write (a new level, σ after an initial-curve edit) is
            // not known to stay in a window
            let dirt = match window {
                Some(w) if !data.is_added() && w.last_changed() == data.last_changed() => {
                    w.0.map_or(Dirt::All, Dirt::Cells)
                }
                _ => Dirt::All,
            };
            p.levels[l] = p.levels[l].merge(dirt);
        }
    }

    /// Forgets the stack: the next [`Self::stack`] makes it whole.
    pub(crate) fn forget(&mut self) {
        self.pending.synced = None;
    }

    /// The first patch's (`patch`) [`Stack`] at `depth` and its display
    /// depth's mesh normals, read from what its incremental pipeline keeps
    /// (module documentation): `old`, the stack and normals this patch had,
    /// brought up to date in place when they were made here and keep their
    /// shape, else made whole from the pipeline (the levels copied, the
    /// display depth's points and normals [`SurfaceData`]'s, the coarser
    /// depths' streamlines integrated). `None` while the pipeline holds
    /// another depth or another net (then build it whole).
    pub(crate) fn stack(
        &mut self,
        patch: Entity,
        design: &Design,
        depth: u32,
        old: Option<(Stack, Vec<DVec3>)>,
    ) -> Option<(Stack, Vec<DVec3>)> {
        let mut levels: Vec<Option<&LevelData>> = vec![None; depth as usize + 1];
        for (l, data, _) in &self.levels {
            *levels.get_mut(l.0 as usize)? = Some(data.into_inner());
        }
        let levels: Vec<&LevelData> = levels.into_iter().collect::<Option<_>>()?;
        let p = &self.surface.points;
        let finest = &levels.last()?.0;
        let net = design.net();
        if p.rows() != finest.tangents.rows()
            || p.cols() != finest.tangents.cols() + 1
            || self.surface.normals.len() != p.data().len()
            || self.surface.normals_behind().is_some()
            || levels[0].0.tangents.data() != net.data()
        {
            self.pending.synced = None;
            return None;
        }
        let kept = old.filter(|(s, n)| {
            self.pending.synced == Some(patch) && fits(s, &levels, p) && n.len() == p.data().len()
        });
        let pending = std::mem::take(&mut *self.pending);
        let curve = curve_key(design.initial());
        let (stack, normals) = match kept {
            Some((mut stack, mut normals)) => {
                update(
                    &mut stack,
                    &levels,
                    design,
                    &pending,
                    curve != pending.curve,
                );
                match pending.surface {
                    Dirt::Clean => {}
                    Dirt::Cells(w) => {
                        let fine = stack.points.last_mut()?;
                        for r in w.rows.lo..=w.rows.hi.min(p.rows().saturating_sub(1)) {
                            let cols = w.cols.lo.min(p.cols())..(w.cols.hi + 1).min(p.cols());
                            fine.row_mut(r)[cols.clone()].copy_from_slice(&p.row(r)[cols.clone()]);
                            let at = r * p.cols();
                            normals[at + cols.start..at + cols.end].copy_from_slice(
                                &self.surface.normals[at + cols.start..at + cols.end],
                            );
                        }
                    }
                    Dirt::All => {
                        stack
                            .points
                            .last_mut()?
                            .data_mut()
                            .copy_from_slice(p.data());
                        normals.copy_from_slice(&self.surface.normals);
                    }
                }
                (stack, normals)
            }
            None => {
                let all: Vec<Level> = levels.iter().map(|l| level_of(&l.0)).collect();
                let mut points: Vec<Grid<DVec3>> = all[..depth as usize]
                    .iter()
                    .map(|l| design.streamlines(l))
                    .collect();
                points.push(p.clone());
                let stack = Stack {
                    levels: all,
                    points,
                };
                (stack, self.surface.normals.clone())
            }
        };
        *self.pending = Pending {
            levels: Vec::new(),
            surface: Dirt::Clean,
            synced: Some(patch),
            curve,
        };
        Some((stack, normals))
    }
}

/// The stack's levels and points have the pipeline's shapes.
fn fits(stack: &Stack, levels: &[&LevelData], fine: &Grid<DVec3>) -> bool {
    stack.levels.len() == levels.len()
        && stack.points.len() == levels.len()
        && (stack.levels.iter().zip(levels)).all(|(a, b)| {
            let b = &b.0;
            let shape = (b.tangents.rows(), b.tangents.cols());
            (a.tangents.rows(), a.tangents.cols()) == shape
                && (a.params.s.rows(), a.params.s.cols()) == (b.params.s.rows(), b.params.s.cols())
                && a.params.t.len() == b.params.t.len()
                && a.params.sigma.len() == b.params.sigma.len()
        })
        && (stack.levels.iter().zip(&stack.points))
            .all(|(l, p)| (p.rows(), p.cols()) == (l.tangents.rows(), l.tangents.cols() + 1))
        && stack
            .points
            .last()
            .is_some_and(|p| (p.rows(), p.cols()) == (fine.rows(), fine.cols()))
}

/// A level's tangents and parameters, copied.
fn level_of(l: &streamline_kernel::levels::incremental::LevelState) -> Level {
    Level {
        tangents: l.tangents.clone(),
        params: ParamGrid {
            s: l.params.s.clone(),
            t: l.params.t.clone(),
            sigma: l.params.sigma.clone(),
        },
    }
}

/// Writes into `stack` (of the pipeline's shapes) what `pending` says
/// changed of `levels`, and places again the coarser depths' rows that
/// moved (all of them when the initial curve `moved`).
fn update(
    stack: &mut Stack,
    levels: &[&LevelData],
    design: &Design,
    pending: &Pending,
    moved_curve: bool,
) {
    let depth = levels.len() - 1;
    for (d, (level, data)) in stack.levels.iter_mut().zip(levels).enumerate() {
        let src = &data.0;
        let rows = level.tangents.rows();
        // the rows whose streamline reads something that changed
        let mut moved = vec![false; rows];
        match pending.levels.get(d).copied().unwrap_or_default() {
            Dirt::Clean => {}
            Dirt::Cells(w) => {
                let cols = level.tangents.cols();
                let range = w.cols.lo.min(cols)..(w.cols.hi + 1).min(cols);
                let window = moved.iter_mut().enumerate();
                for (r, m) in window.take(w.rows.hi + 1).skip(w.rows.lo) {
                    level.tangents.row_mut(r)[range.clone()]
                        .copy_from_slice(&src.tangents.row(r)[range.clone()]);
                    level.params.s.row_mut(r)[range.clone()]
                        .copy_from_slice(&src.params.s.row(r)[range.clone()]);
                    *m = true;
                }
            }
            Dirt::All => {
                level
                    .tangents
                    .data_mut()
                    .copy_from_slice(src.tangents.data());
                level
                    .params
                    .s
                    .data_mut()
                    .copy_from_slice(src.params.s.data());
                moved.fill(true);
            }
        }
        for (r, m) in moved.iter_mut().enumerate() {
            let (t, sigma) = (src.params.t[r], src.params.sigma[r]);
            if level.params.t[r].to_bits() != t.to_bits()
                || level.params.sigma[r].to_bits() != sigma.to_bits()
            {
                level.params.t[r] = t;
                level.params.sigma[r] = sigma;
                *m = true;
            }
        }
        if d == depth {
            break;
        }
        // a coarser depth's streamlines: the rows that read a change (all
        // of them when their initial curve changed)
        let points = &mut stack.points[d];
        for r in (0..rows).filter(|&r| moved[r] || moved_curve) {
            design.place_row(level, r, points.row_mut(r));
        }
    }
}
