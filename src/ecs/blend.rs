//! The blend stage: collects the cells that edits changed (`Changed<…>` on the
//! handles) and re-blends only the dirty window of each level
//! ([`streamline_kernel::levels::incremental::propagate`]); rows of the display depth
//! whose tangents changed get new [`StreamlineTangents`].

use super::components::*;
use super::resources::*;
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::levels::dirty_window::{DirtyWindow, Span};
use streamline_kernel::levels::incremental::{LevelState, build_levels, propagate};

/// Control handles whose direction or parameter changed.
type ChangedControls<'w, 's> =
    Query<'w, 's, &'static ControlHandle, Or<(Changed<Direction>, Changed<ArcParam>)>>;

pub(crate) fn collect_seeds(
    meter: Res<super::meter::CpuMeter>,
    model: Res<Model>,
    mut seeds: ResMut<Seeds>,
    controls: ChangedControls,
    details: Query<&DetailHandle, Changed<DetailLocal>>,
) {
    let _meter = meter.start();
    if model.full {
        return;
    }
    let mut add = |level: u32, w: DirtyWindow| {
        let l = level as usize;
        if seeds.0.len() <= l {
            seeds.0.resize(l + 1, None);
        }
        seeds.0[l] = Some(DirtyWindow::merge(seeds.0[l], w));
    };
    for h in &controls {
        add(0, DirtyWindow::cell(h.row, h.col));
    }
    for h in &details {
        add(h.level, DirtyWindow::cell(h.row, h.col));
    }
}

fn streamline_of(model: &Model, level: &LevelState, row: usize) -> StreamlineTangents {
    let p = &level.params;
    StreamlineTangents {
        sigma: p.sigma[row],
        origin: model.scene.design.initial.point(p.t[row]),
        t: p.t[row],
        changed_from: 0,
    }
}

/// [`streamline_of`] in place, which marks the row changed for the integrate
/// stage (the row's tangents and `s` are read from the level there, not
/// copied: copying them was 9 % of an interior edit on the car at depth 5).
/// Incremental edits never change the initial curve or the rows' `t` (those
/// rebuild in full), so the row's start point is kept unless its `t` moved
/// (evaluating the initial curve, a QI curve under Gauss quadrature, was
/// about 1.5 % of such an edit).
/// `from` is the first column whose tangent may have changed, `0` when the
/// parameters changed too.
fn refresh(model: &Model, level: &LevelState, row: usize, from: usize, t: &mut StreamlineTangents) {
    let p = &level.params;
    t.sigma = p.sigma[row];
    if t.t.to_bits() != p.t[row].to_bits() {
        t.origin = model.scene.design.initial.point(p.t[row]);
        t.t = p.t[row];
    }
    t.changed_from = t.changed_from.min(from);
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn reblend(
    meter: Res<super::meter::CpuMeter>,
    mut commands: Commands,
    mut model: ResMut<Model>,
    mut seeds: ResMut<Seeds>,
    mut levels: Query<(Entity, &SubdivisionLevel, &mut LevelData)>,
    mut lines: Query<(Entity, &Streamline, &mut StreamlineTangents)>,
    mut stats: ResMut<Stats>,
    mut log: ResMut<EditLog>,
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    // interpolated control tangents depend on the whole net: any change of a
    // control tangent rebuilds everything from the interpolated net
    let interpolated = model.scene.interpolates_tangents();
    if interpolated && seeds.0.first().is_some_and(Option::is_some) {
        model.full = true;
    }
    if model.full {
        model.full = false;
        seeds.0.clear();
        for (e, ..) in &levels {
            commands.entity(e).despawn();
        }
        for (e, ..) in &lines {
            commands.entity(e).despawn();
        }
        let scene = &model.scene;
        let design = scene.effective_design();
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
                streamline_of(&model, display, row),
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
    let mut sd = std::mem::take(&mut seeds.0);
    if sd.iter().all(Option::is_none) {
        return;
    }
    let mut ls: Vec<_> = levels.iter_mut().map(|(_, l, d)| (l.0, d)).collect();
    ls.sort_by_key(|(l, _)| *l);
    let mut refs: Vec<&mut LevelState> = ls.iter_mut().map(|(_, d)| &mut d.0).collect();
    sd.resize(refs.len(), None);
    let result = propagate(&model.scene.design, &model.scene.details, &mut refs, &sd);
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
            model.full = true;
        }
    }
    stats.last.us_blend += t0.elapsed().as_secs_f64() * 1e6;
}
