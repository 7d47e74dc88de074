//! Change detection drives the pipeline: [`track_handles`] is the one system
//! that decides what the blend stage redoes. It reads which handle and patch
//! components changed since it last ran (`Changed`, `Added`,
//! `RemovedComponents`) and turns them into the patch's [`Dirty`] record:
//! * a changed [`PatchStructure`] (net size, scheme, depth, mirror, a new
//!   patch): everything is built afresh;
//! * a changed [`PatchPlacement`] or initial-curve handle: every streamline
//!   is placed again and no tangent re-blended (Eq. 1), or built afresh when
//!   mirrored (the mirror plane follows the curve);
//! * a changed [`Direction`] or [`ArcParam`] of a net handle: its level-0
//!   cell; a changed, added or removed detail: its cell at its level.
//!
//! It also keeps the derived [`PatchKernel`] (the kernel's design and
//! details) equal to the handles, writing only what changed. A value set to
//! what it already is changes nothing (`set_if_neq`), so it re-blends nothing.

use super::components::*;
use super::dirty::Dirty;
use crate::ecs::edit_error::EditError;
use crate::ecs::resources::EditLog;
use bevy::prelude::*;
use std::collections::HashMap;
use streamline_kernel::{DVec3, Design, Grid};

/// The net handles whose value changed since the last run.
type ChangedNet<'w, 's> = Query<
    'w,
    's,
    (
        &'static SurfaceHandle,
        &'static Direction,
        &'static ArcParam,
    ),
    (
        Or<(Changed<Direction>, Changed<ArcParam>)>,
        Without<JoinedHandle>,
    ),
>;

/// The patch's components `track_handles` reads and writes.
type PatchWork = (
    Ref<'static, PatchStructure>,
    Ref<'static, PatchPlacement>,
    &'static PatchIndex,
    &'static mut PatchKernel,
    &'static mut Dirty,
);

/// Turns the changes of the patch's and its handles' components into dirty
/// windows ([`Dirty`]) and brings [`PatchKernel`] up to date.
#[allow(clippy::too_many_arguments)]
pub(crate) fn track_handles(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut patches: Query<PatchWork, With<Patch>>,
    net_changed: ChangedNet,
    net: Query<(&Direction, &ArcParam), With<SurfaceHandle>>,
    initial_changed: Query<(), (With<InitialHandle>, Changed<Direction>)>,
    initial: Query<&Direction, With<InitialHandle>>,
    details_changed: Query<(Entity, &DetailHandle), Changed<DetailRotation>>,
    details: Query<(&DetailHandle, &DetailRotation)>,
    mut removed_details: RemovedComponents<DetailHandle>,
    mut removed_initial: RemovedComponents<InitialHandle>,
    mut known_details: Local<HashMap<Entity, (u32, usize, usize)>>,
    mut log: ResMut<EditLog>,
) {
    let _meter = meter.start();
    let removed_initial = removed_initial.read().count() > 0;
    let mut detail_cells = Vec::new();
    for (e, h) in &details_changed {
        known_details.insert(e, h.key());
        detail_cells.push(h.key());
    }
    for e in removed_details.read() {
        if let Some(k) = known_details.remove(&e) {
            detail_cells.push(k);
        }
    }
    let Ok((st, pl, index, mut kernel, mut dirty)) = patches.single_mut() else {
        return;
    };
    let structural = st.is_changed();
    let placed = pl.is_changed() || !initial_changed.is_empty() || removed_initial;
    let cells: Vec<(usize, usize)> = net_changed.iter().map(|(h, ..)| (h.row, h.col)).collect();
    if !structural && !placed && cells.is_empty() && detail_cells.is_empty() {
        return;
    }
    // the derived kernel design: made afresh on a new shape or curve, else
    // only the changed cells (and the `s` rows they are in) written
    let fresh = structural || placed;
    let updated = if fresh {
        fresh_design(&st, &pl, index, &net, &initial, &kernel.design)
    } else {
        update_cells(&kernel.design, index, &net, &net_changed)
    };
    match updated {
        Ok(Some(d)) => kernel.design = d,
        Ok(None) => {}
        Err(e) => {
            log.entries.push(Err(EditError::NoDesign(e)));
            return;
        }
    }
    if !detail_cells.is_empty() || structural {
        kernel.details = details.iter().map(|(h, r)| (h.key(), r.0)).collect();
    }
    if structural {
        dirty.rebuild();
        return;
    }
    if placed {
        if st.mirror {
            dirty.rebuild();
            return;
        }
        dirty.replace_streamlines();
    }
    if !cells.is_empty()
        && crate::scene::design::model::interpolates(&kernel.design, st.interpolate_tangents)
    {
        // interpolated control tangents depend on the whole net
        dirty.rebuild();
        return;
    }
    for &(r, c) in &cells {
        dirty.cell(0, r, c);
    }
    for &(level, r, c) in &detail_cells {
        dirty.cell(level, r, c);
    }
    if st.mirror && !cells.is_empty() {
        // both halves come from the doubled net (docs/math.md §9)
        dirty.mirror_rows(st.rows);
    }
}

/// The design of the handles, made afresh (a new shape or initial curve);
/// the old design's initial curve is kept when the handles still describe it.
fn fresh_design(
    st: &PatchStructure,
    pl: &PatchPlacement,
    index: &PatchIndex,
    net: &Query<(&Direction, &ArcParam), With<SurfaceHandle>>,
    initial: &Query<&Direction, With<InitialHandle>>,
    old: &Design,
) -> Result<Option<Design>, String> {
    let (rows, cols) = (index.surface.rows(), index.surface.cols());
    let mut dirs = Grid::filled(rows, cols, DVec3::X);
    let mut s = Grid::filled(rows, cols, 0.0);
    for r in 0..rows {
        for c in 0..cols {
            let (d, a) = net
                .get(index.surface.get(r, c))
                .map_err(|_| "a net handle is missing".to_string())?;
            dirs.set(r, c, d.0);
            s.set(r, c, a.0);
        }
    }
    let tangents = (index.initial.iter())
        .map(|&e| initial.get(e).map(|d| d.0))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|_| "an initial-curve handle is missing".to_string())?;
    let curve = super::scene_io::initial_curve(pl, &tangents, Some(old.initial()))?;
    Design::new(
        &dirs,
        s,
        st.t.clone(),
        pl.anchor,
        st.scheme,
        st.order,
        curve,
    )
    .map(Some)
    .map_err(|e| e.to_string())
}

/// `old` with the changed net cells written: each direction, and each row
/// whose `s` changed as a whole (its `σ` follows, Eq. 2). `None`: nothing differs.
fn update_cells(
    old: &Design,
    index: &PatchIndex,
    net: &Query<(&Direction, &ArcParam), With<SurfaceHandle>>,
    changed: &ChangedNet,
) -> Result<Option<Design>, String> {
    let mut d = old.clone();
    let mut rows = Vec::new();
    for (h, dir, a) in changed.iter() {
        if d.net().get(h.row, h.col) != dir.0 {
            d.set_tangent(h.row, h.col, dir.0)
                .map_err(|e| e.to_string())?;
        }
        if d.params().s.get(h.row, h.col).to_bits() != a.0.to_bits() && !rows.contains(&h.row) {
            rows.push(h.row);
        }
    }
    for r in rows {
        let s = (0..index.surface.cols())
            .map(|c| net.get(index.surface.get(r, c)).map(|(_, a)| a.0))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|_| "a net handle is missing".to_string())?;
        d.set_s_row(r, &s).map_err(|e| e.to_string())?;
    }
    Ok(Some(d))
}
