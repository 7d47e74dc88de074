//! The blend stage: takes what the edits marked [`Dirty`] and re-blends only
//! the dirty window of each level
//! ([`streamline_kernel::levels::incremental::propagate`]), or builds everything
//! afresh; rows of the display depth whose tangents changed, or every row
//! when the initial curve changed, get new [`StreamlineTangents`].

use super::components::*;
use super::resources::*;
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
/// [`Dirty::replace_streamlines`], which places every row again), so the
/// row's start point is kept unless its `t` moved (evaluating the initial
/// curve, a QI curve under Gauss quadrature, was about 1.5 % of such an edit).
/// `from` is the first column whose tangent may have changed, `0` when the
/// parameters changed too.
fn refresh(model: &Model, level: &LevelState, row: usize, from: usize, t: &mut StreamlineTangents) {
    let p = &level.params;
    t.sigma = p.sigma[row];
    if t.t.to_bits() != p.t[row].to_bits() {
        t.origin = model.scene.design.initial().point(p.t[row]);
        t.t = p.t[row];
    }
    t.changed_from = t.changed_from.min(from);
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn reblend(
    meter: Res<super::meter::CpuMeter>,
    mut commands: Commands,
    model: Res<Model>,
    mut dirty: ResMut<Dirty>,
    mut levels: Query<(Entity, &SubdivisionLevel, &mut LevelData)>,
    mut lines: Query<(Entity, &Streamline, &mut StreamlineTangents)>,
    mut stats: ResMut<Stats>,
    mut log: ResMut<EditLog>,
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    if dirty.is_clean() {
        return;
    }
    // interpolated control tangents depend on the whole net: any change of a
    // control tangent rebuilds everything from the interpolated net
    let interpolated = model.scene.interpolates_tangents();
    if interpolated && dirty.touches(0) {
        dirty.rebuild();
    }
    let (full, replace, mut sd) = dirty.take();
    if full {
        for (e, ..) in &levels {
            commands.entity(e).despawn();
        }
        for (e, ..) in &lines {
            commands.entity(e).despawn();
        }
        let scene = &model.scene;
        // mirrored: the doubled design (docs/math.md §9)
        let design = match scene.shown_design() {
            Ok(d) => d,
            Err(e) => {
                log.entries.push(Err(format!("rebuild failed: {e}")));
                return;
            }
        };
        let built = match build_levels(&design, &scene.details, scene.max_depth()) {
            Ok(b) => b,
            Err(e) => {
                log.entries.push(Err(format!("rebuild failed: {e}")));
                return;
            }
        };
        let display = &built[scene.display_depth as usize];
        let mut new_lines = Vec::with_capacity(display.shape().0);
        for row in 0..display.shape().0 {
            new_lines.push((
                Streamline { row },
                streamline_of(design.initial(), display, row),
                StreamlineAlpha::default(),
                StreamlinePoints::default(),
            ));
        }
        commands.spawn_batch(new_lines);
        stats.levels = built.iter().map(LevelState::shape).collect();
        stats.tangents_total = stats.levels.iter().map(|(r, c)| r * c).sum();
        stats.streamlines = display.shape().0;
        stats.last.full_rebuild = true;
        stats.last.tangents_reblended +=
            stats.levels[1..].iter().map(|(r, c)| r * c).sum::<usize>();
        for l in built {
            commands.spawn((SubdivisionLevel(l.level), LevelData(l)));
        }
        stats.last.us_blend += t0.elapsed().as_secs_f64() * 1e6;
        return;
    }
    if replace {
        // a new initial curve or anchor: every streamline starts elsewhere;
        // its tangents and `s` are as they were, and its `σ` is level 0's
        // taken down by the scheme's scalar step (the step a full build takes)
        let sigma = super::authoring::sigma_of_levels(&model.scene.design, &mut levels);
        let display = model.scene.display_depth as usize;
        let mut n = 0;
        for (_, line, mut t) in lines.iter_mut() {
            if let Some(&s) = sigma.get(display).and_then(|s| s.get(line.row)) {
                t.sigma = s;
            }
            t.origin = model.scene.design.initial().point(t.t);
            t.changed_from = 0;
            n += 1;
        }
        stats.last.streamlines_replaced += n;
    }
    if sd.iter().all(Option::is_none) {
        stats.last.us_blend += t0.elapsed().as_secs_f64() * 1e6;
        return;
    }
    let mut ls: Vec<_> = levels.iter_mut().map(|(_, l, d)| (l.0, d)).collect();
    ls.sort_by_key(|(l, _)| *l);
    let mut refs: Vec<&mut LevelState> = ls.iter_mut().map(|(_, d)| &mut d.0).collect();
    sd.resize(refs.len(), None);
    // mirrored: the levels are the doubled net's (docs/math.md §9)
    let doubled = match model.scene.mirror {
        true => match model.scene.shown_design() {
            Ok(d) => Some(d),
            Err(e) => {
                log.entries.push(Err(format!("rebuild failed: {e}")));
                return;
            }
        },
        false => None,
    };
    let design = doubled.as_ref().unwrap_or(&model.scene.design);
    let result = propagate(design, &model.scene.details, &mut refs, &sd);
    match result {
        Ok(p) => {
            stats.last.tangents_reblended += p.reblended;
            stats.last.details_reapplied += p.details;
            let display = model.scene.display_depth as usize;
            if let (Some(Some(w)), Some(level)) = (p.dirty.get(display), refs.get(display)) {
                let rows: Span = w.rows;
                // only tangents inside the window changed, unless parameters did
                let from = if p.params { 0 } else { w.cols.lo };
                for (_, line, mut t) in lines.iter_mut() {
                    if rows.lo <= line.row && line.row <= rows.hi {
                        refresh(&model, level, line.row, from, &mut t);
                    }
                }
            }
        }
        Err(e) => {
            log.entries.push(Err(format!(
                "incremental update refused ({e}); rebuilding in full"
            )));
            dirty.rebuild();
        }
    }
    stats.last.us_blend += t0.elapsed().as_secs_f64() * 1e6;
}
