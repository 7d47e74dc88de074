//! The blend stage: takes what [`super::patch::track`] marked [`Dirty`] on
//! the patch and re-blends only the dirty window of each level
//! ([`streamline_kernel::levels::incremental::propagate`]), or builds everything
//! afresh; rows of the display depth whose tangents changed, or every row
//! when the initial curve changed, get new [`StreamlineTangents`]. A level
//! entity is marked changed only when its window was recomputed.

use super::components::*;
use super::edit_error::EditError;
use super::joined::{PatchStart, PatchSurface, shows_run_cut};
use super::patch::dirty::Dirty;
use super::patch::{PatchKernel, PatchStructure};
use super::resources::*;
use crate::scene::design::model::shown_design;
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::levels::dirty_window::Span;
use streamline_kernel::levels::incremental::{LevelState, build_levels, propagate};

fn streamline_of(
    initial: &streamline_kernel::streamline::initial_curve::InitialCurve,
    level: &LevelState,
    row: usize,
) -> StreamlineTangents {
    let p = &level.params;
    StreamlineTangents {
        sigma: p.sigma[row],
        origin: initial.point(p.t[row]),
        t: p.t[row],
        changed_from: 0,
    }
}

/// [`streamline_of`] in place, which marks the row changed for the integrate
/// stage (the row's tangents and `s` are read from the level there, not
/// copied: copying them was 9 % of an interior edit on the car at depth 5).
/// Re-blending never changes the initial curve (an edit of it asks for
/// `Dirty::replace_streamlines`, which places every row again), so the
/// row's start point is kept unless its `t` moved (evaluating the initial
/// curve, a QI curve under Gauss quadrature, was about 1.5 % of such an edit).
/// `from` is the first column whose tangent may have changed, `0` when the
/// parameters changed too.
fn refresh(
    kernel: &PatchKernel,
    level: &LevelState,
    row: usize,
    from: usize,
    t: &mut StreamlineTangents,
) {
    let p = &level.params;
    t.sigma = p.sigma[row];
    if t.t.to_bits() != p.t[row].to_bits() {
        t.origin = kernel.design.initial().point(p.t[row]);
        t.t = p.t[row];
    }
    t.changed_from = t.changed_from.min(from);
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn reblend(
    meter: Res<super::meter::CpuMeter>,
    mut commands: Commands,
    mut patches: Query<(Entity, Ref<PatchStructure>, &PatchKernel, &mut Dirty)>,
    mut levels: Query<(Entity, &SubdivisionLevel, &mut LevelData)>,
    mut lines: Query<(Entity, &Streamline, &mut StreamlineTangents)>,
    mut windows: Query<&mut LevelWindow>,
    mut stats: ResMut<Stats>,
    mut log: ResMut<EditLog>,
    runs: (Query<&PatchStart>, Query<&PatchSurface>),
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    let Ok((patch, st, kernel, mut dirty)) = patches.single_mut() else {
        return;
    };
    if dirty.is_clean() {
        return;
    }
    // the first patch drawn as its G2 run's cut: its own levels wait, to
    // be built afresh once it no longer is (docs/math.md §11.1)
    let (starts, surfaces) = runs;
    // (a new structure, such as another display depth, is built at once,
    // so that its level and streamline entities are the structure's)
    if shows_run_cut(patch, starts.iter(), surfaces.get(patch).ok()) && !st.is_changed() {
        dirty.take();
        dirty.rebuild();
        return;
    }
    let (mut full, replace, mut sd) = dirty.take();
    if !full && !sd.iter().all(Option::is_none) {
        full = !reblend_windows(
            kernel,
            &st,
            &mut levels,
            &mut lines,
            &mut windows,
            &mut sd,
            &mut stats,
            &mut log,
        );
    }
    if full {
        build_all(
            &mut commands,
            patch,
            &st,
            kernel,
            &levels,
            &lines,
            &mut stats,
            &mut log,
        );
    } else if replace {
        // a new initial curve or anchor: every streamline starts elsewhere;
        // its tangents and `s` are as they were, and its `σ` is level 0's
        // taken down by the scheme's scalar step (the step a full build takes)
        let sigma = super::authoring::sigma_of_levels(&kernel.design, &mut levels);
        let display = st.display_depth as usize;
        let mut n = 0;
        for (_, line, mut t) in lines.iter_mut() {
            if let Some(&s) = sigma.get(display).and_then(|s| s.get(line.row)) {
                t.sigma = s;
            }
            t.origin = kernel.design.initial().point(t.t);
            t.changed_from = 0;
            n += 1;
        }
        stats.last.streamlines_replaced += n;
    }
    stats.last.us_blend += t0.elapsed().as_secs_f64() * 1e6;
}

/// Builds the levels and streamlines afresh, as children of `patch`.
#[allow(clippy::too_many_arguments)]
fn build_all(
    commands: &mut Commands,
    patch: Entity,
    st: &PatchStructure,
    kernel: &PatchKernel,
    levels: &Query<(Entity, &SubdivisionLevel, &mut LevelData)>,
    lines: &Query<(Entity, &Streamline, &mut StreamlineTangents)>,
    stats: &mut Stats,
    log: &mut EditLog,
) {
    for (e, ..) in levels {
        commands.entity(e).despawn();
    }
    for (e, ..) in lines {
        commands.entity(e).despawn();
    }
    // mirrored: the doubled design (docs/math.md §9)
    let built =
        shown_design(&kernel.design, st.interpolate_tangents, st.mirror).and_then(|design| {
            build_levels(&design, &kernel.details, st.max_depth()).map(|b| (design, b))
        });
    let (design, built) = match built {
        Ok(b) => b,
        Err(e) => {
            log.entries.push(Err(EditError::RebuildFailed(e)));
            return;
        }
    };
    let display = &built[st.display_depth as usize];
    let mut new_lines = Vec::with_capacity(display.shape().0);
    for row in 0..display.shape().0 {
        new_lines.push((
            Streamline { row },
            streamline_of(design.initial(), display, row),
            StreamlineAlpha::default(),
            StreamlinePoints::default(),
            ChildOf(patch),
        ));
    }
    commands.spawn_batch(new_lines);
    stats.levels = built.iter().map(LevelState::shape).collect();
    stats.tangents_total = stats.levels.iter().map(|(r, c)| r * c).sum();
    stats.streamlines = display.shape().0;
    stats.last.full_rebuild = true;
    stats.last.tangents_reblended += stats.levels[1..].iter().map(|(r, c)| r * c).sum::<usize>();
    for l in built {
        commands.spawn((
            SubdivisionLevel(l.level),
            LevelData(l),
            LevelWindow(None),
            ChildOf(patch),
        ));
    }
}

/// Re-blends the dirty windows `sd` of the levels in place; a level is
/// marked changed only when its window was recomputed. `false` when the
/// kernel refused (then everything is built afresh).
#[allow(clippy::too_many_arguments)]
fn reblend_windows(
    kernel: &PatchKernel,
    st: &PatchStructure,
    levels: &mut Query<(Entity, &SubdivisionLevel, &mut LevelData)>,
    lines: &mut Query<(Entity, &Streamline, &mut StreamlineTangents)>,
    windows: &mut Query<&mut LevelWindow>,
    sd: &mut Vec<Option<streamline_kernel::levels::dirty_window::DirtyWindow>>,
    stats: &mut Stats,
    log: &mut EditLog,
) -> bool {
    let mut ls: Vec<_> = levels.iter_mut().map(|(e, l, d)| (l.0, e, d)).collect();
    ls.sort_by_key(|(l, ..)| *l);
    sd.resize(ls.len(), None);
    // mirrored: the levels are the doubled net's (docs/math.md §9)
    let doubled = match st.mirror {
        true => match shown_design(&kernel.design, st.interpolate_tangents, true) {
            Ok(d) => Some(d),
            Err(e) => {
                log.entries.push(Err(EditError::RebuildFailed(e)));
                return true;
            }
        },
        false => None,
    };
    let design = doubled.as_ref().unwrap_or(&kernel.design);
    let result = {
        let mut refs: Vec<&mut LevelState> = ls
            .iter_mut()
            .map(|(_, _, d)| &mut d.bypass_change_detection().0)
            .collect();
        propagate(design, &kernel.details, &mut refs, sd)
    };
    match result {
        Ok(p) => {
            for ((_, e, d), w) in ls.iter_mut().zip(&p.dirty) {
                if w.is_some() {
                    d.set_changed();
                    if let Ok(mut lw) = windows.get_mut(*e) {
                        *lw = LevelWindow(*w);
                    }
                }
            }
            stats.last.tangents_reblended += p.reblended;
            stats.last.details_reapplied += p.details;
            let display = st.display_depth as usize;
            if let (Some(Some(w)), Some((_, _, level))) = (p.dirty.get(display), ls.get(display)) {
                let rows: Span = w.rows;
                // only tangents inside the window changed, unless parameters did
                let from = if p.params { 0 } else { w.cols.lo };
                for (_, line, mut t) in lines.iter_mut() {
                    if rows.lo <= line.row && line.row <= rows.hi {
                        refresh(kernel, &level.0, line.row, from, &mut t);
                    }
                }
            }
            true
        }
        Err(e) => {
            log.entries.push(Err(EditError::IncrementalRefused(e)));
            false
        }
    }
}
