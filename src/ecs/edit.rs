//! The edit stage: the only system that changes the model. It applies each
//! [`EditMessage`] to the scene, records undo steps, and marks in [`Dirty`]
//! what the blend stage must redo: the cells an edit changed (only when a
//! value really changed), or a full rebuild for edits that change the shape
//! of the levels.

use super::components::{LevelData, SubdivisionLevel};
use super::messages::{Edit, EditMessage};
use super::resources::*;
use crate::scene::{Scene, io};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::levels::incremental::check_params;
use streamline_kernel::levels::multires;
use streamline_kernel::{DQuat, DVec3, Design, Tangent};

/// What the edit system reads and writes.
#[derive(SystemParam)]
pub(crate) struct EditCtx<'w, 's> {
    model: ResMut<'w, Model>,
    history: ResMut<'w, History>,
    config: Res<'w, ModelConfig>,
    dirty: ResMut<'w, Dirty>,
    levels: Query<'w, 's, (&'static SubdivisionLevel, &'static LevelData)>,
}

pub(crate) fn apply_edits(
    meter: Res<super::meter::CpuMeter>,
    mut reader: MessageReader<EditMessage>,
    mut ctx: EditCtx,
    mut log: ResMut<EditLog>,
    mut stats: ResMut<Stats>,
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    let mut labels = Vec::new();
    let mut any = false;
    let mut mirrored_edit = false;
    for msg in reader.read() {
        if !any {
            log.entries.clear();
            log.frame += 1;
            any = true;
        }
        labels.push(msg.edit.label());
        if matches!(msg.edit, Edit::Save(_) | Edit::Export(_)) {
            continue; // the output stage, after the mesh is up to date
        }
        let before_undoable = msg.edit.is_undoable();
        let snapshot = before_undoable.then(|| ctx.model.scene.clone());
        match apply(&mut ctx, &msg.edit) {
            Ok(done) => {
                mirrored_edit |= ctx.model.scene.mirror && before_undoable;
                if let Some(s) = snapshot {
                    let limit = ctx.config.history_limit;
                    let was = ctx.model.unsaved;
                    ctx.history.record(&s, msg.group, limit, was);
                    ctx.model.unsaved = true;
                }
                log.entries.push(Ok(done));
            }
            Err(e) => log.entries.push(Err(e)),
        }
    }
    if mirrored_edit && ctx.model.scene.mirror {
        // both halves come from the doubled net (docs/math.md §9): the cells
        // the frame's edits marked are dirty in both copies (once a frame:
        // the windows are in half rows until here)
        let m = ctx.model.scene.design.net().rows();
        ctx.dirty.mirror_rows(m);
    }
    if any {
        stats.last = EditStats {
            edit: labels.join("; "),
            us_edit: t0.elapsed().as_secs_f64() * 1e6,
            ..Default::default()
        };
        stats.collecting = true;
    }
}

fn apply(ctx: &mut EditCtx, edit: &Edit) -> Result<String, String> {
    match edit {
        Edit::SetDirection { row, col, dir } => set_direction(ctx, *row, *col, *dir),
        Edit::Rotate {
            row,
            col,
            axis,
            radians,
        } => {
            let q = rotation(*axis, *radians)?;
            let cur = current_direction(ctx, *row, *col)?;
            let dir = q * cur;
            set_direction(ctx, *row, *col, dir)
        }
        Edit::SetLength {
            row,
            col,
            coefficient,
        } => set_length(ctx, *row, *col, *coefficient),
        Edit::ClearDetail { row, col } => {
            let level = ctx.model.scene.edit_depth;
            let key = (level, *row, *col);
            if ctx.model.scene.details.remove(&key).is_none() {
                return Err(format!(
                    "handle ({row}, {col}) at edit depth {level} has no detail to clear"
                ));
            }
            ctx.dirty.cell(level, *row, *col);
            Ok(format!("cleared detail ({row}, {col}) at level {level}"))
        }
        Edit::SetScheme(s) => {
            let s = s.validate().map_err(|e| e.to_string())?;
            let mut d = ctx.model.scene.design.clone();
            d.set_scheme(s).map_err(|e| e.to_string())?;
            check_design(&d, ctx.model.scene.max_depth(), ctx.model.scene.mirror)?;
            ctx.model.scene.design = d;
            let dropped = prune_details(&mut ctx.model.scene);
            full(ctx);
            Ok(format!("scheme {}{dropped}", s.name()))
        }
        Edit::SetBlendOrder(o) => {
            ctx.model.scene.design.set_order(*o);
            full(ctx);
            Ok(format!("blend order {}", o.name()))
        }
        Edit::SetDisplayDepth(n) => {
            let depth = (*n).max(ctx.model.scene.edit_depth);
            check_design(&ctx.model.scene.design, depth, ctx.model.scene.mirror)?;
            ctx.model.scene.display_depth = *n;
            full(ctx);
            Ok(format!("display depth {n}"))
        }
        Edit::SetEditDepth(n) => {
            if *n > 0 && ctx.model.scene.mirror {
                return Err(super::authoring::mirror_depth_msg());
            }
            let depth = (*n).max(ctx.model.scene.display_depth);
            check_design(&ctx.model.scene.design, depth, ctx.model.scene.mirror)?;
            ctx.model.scene.edit_depth = *n;
            full(ctx);
            Ok(format!("edit depth {n}"))
        }
        Edit::Undo | Edit::Redo => {
            let undo = matches!(edit, Edit::Undo);
            let cur = ctx.model.scene.clone();
            let target = ctx.history.step(undo, cur).ok_or(if undo {
                "nothing to undo"
            } else {
                "nothing to redo"
            })?;
            restore(ctx, target);
            ctx.model.unsaved = true;
            Ok(if undo { "undone" } else { "redone" }.into())
        }
        Edit::SetTuning(t) => {
            ctx.model.scene.tuning = t.clone();
            Ok(if t.is_some() {
                "fine tuning on".into()
            } else {
                "fine tuning off".into()
            })
        }
        Edit::SetTuningValue { row, col, value } => {
            let tuning = ctx
                .model
                .scene
                .tuning
                .get_or_insert_with(SurfaceTuning::identity);
            tuning
                .function
                .set(*row, *col, *value)
                .map_err(|e| format!("{e}; the fine-tuning values are unchanged"))?;
            Ok(format!("fine-tuning value ({row}, {col}) = {value}"))
        }
        Edit::SetTuningConstraint(c) => {
            ctx.model
                .scene
                .tuning
                .get_or_insert_with(SurfaceTuning::identity)
                .constraint = *c;
            Ok(format!("fine-tuning constraint {}", c.name()))
        }
        Edit::SetInterpolateTangents(on) => {
            ctx.model.scene.interpolate_tangents = *on;
            full(ctx);
            Ok(
                if *on
                    && !streamline_kernel::levels::tangent_interpolation::applies(
                        ctx.model.scene.design.scheme(),
                    )
                {
                    "interpolate control tangents on (Kobbelt interpolates them already)".into()
                } else {
                    format!("interpolate control tangents {on}")
                },
            )
        }
        Edit::CancelGroup(g) => {
            let (target, was_unsaved) = ctx
                .history
                .cancel(*g)
                .ok_or_else(|| format!("drag {g} is not the last edit; nothing to cancel"))?;
            restore(ctx, target);
            ctx.model.unsaved = was_unsaved;
            Ok("drag cancelled".into())
        }
        Edit::Load(path) => {
            let scene = io::load(path).map_err(|e| format!("{e} (the current scene is kept)"))?;
            replace(ctx, scene);
            ctx.model.path = Some(path.clone());
            Ok(format!("loaded {}", path.display()))
        }
        Edit::Replace(scene) => {
            replace(ctx, (**scene).clone());
            ctx.model.path = None;
            Ok(format!("opened {}", scene.name))
        }
        Edit::Recover { scene, origin } => {
            replace(ctx, (**scene).clone());
            ctx.model.path = origin.clone();
            ctx.model.unsaved = true;
            Ok(format!("recovered {}", scene.name))
        }
        Edit::Save(_) | Edit::Export(_) => Ok(String::new()),
        Edit::RotateMany {
            handles,
            axis,
            radians,
        } => {
            let q = rotation(*axis, *radians)?;
            if handles.is_empty() {
                return Err("no handles to rotate; give at least one (row, col)".into());
            }
            // every handle checked before any is turned: all or nothing
            let dirs = handles
                .iter()
                .map(|&(r, c)| current_direction(ctx, r, c).map(|d| q * d))
                .collect::<Result<Vec<_>, _>>()?;
            for (&(r, c), d) in handles.iter().zip(dirs) {
                set_direction(ctx, r, c, d)?;
            }
            Ok(format!(
                "rotated {} handles by {:.3}°",
                handles.len(),
                radians.to_degrees()
            ))
        }
        Edit::Author(a) => author(ctx, a),
    }
}

/// An authoring edit ([`super::authoring`]): the scene changes there; here
/// the handles and the pipeline follow.
fn author(ctx: &mut EditCtx, a: &super::authoring::AuthorEdit) -> Result<String, String> {
    use super::authoring::Effect;
    let (msg, effect) = super::authoring::apply(&mut ctx.model.scene, a)?;
    match effect {
        Effect::NewScene(scene) => {
            replace(ctx, *scene);
            ctx.model.path = None;
            ctx.model.unsaved = true;
        }
        Effect::Full => full(ctx),
        Effect::Place => ctx.dirty.replace_streamlines(),
        Effect::Row(row) => {
            for col in 0..ctx.model.scene.design.net().cols() {
                ctx.dirty.cell(0, row, col);
            }
        }
    }
    Ok(msg)
}

/// `d` can be built to `depth`; mirrored, its doubled design too
/// (`docs/math.md §9`: the levels are the doubled net's).
fn check_design(d: &Design, depth: u32, mirror: bool) -> Result<(), String> {
    d.scheme()
        .check_depth(d.net().rows(), d.net().cols(), depth)
        .map_err(|e| e.to_string())?;
    check_params(d, depth).map_err(|e| e.to_string())?;
    if mirror {
        let m = d.mirrored().map_err(|e| e.to_string())?;
        m.scheme()
            .check_depth(m.net().rows(), m.net().cols(), depth)
            .and_then(|_| check_params(&m, depth))
            .map_err(|e| format!("the mirrored surface: {e}"))?;
    }
    Ok(())
}

/// Asks for a full rebuild (the levels' shapes may change).
fn full(ctx: &mut EditCtx) {
    ctx.dirty.rebuild();
}

/// Drops details that no longer fit their level (after a scheme change).
fn prune_details(scene: &mut Scene) -> String {
    let d = &scene.design;
    let c = d.scheme().curve();
    let before = scene.details.len();
    let shape = |level: u32| {
        let (mut r, mut k) = (d.net().rows(), d.net().cols());
        for _ in 0..level {
            r = c.refined_len(r);
            k = c.refined_len(k);
        }
        (r, k)
    };
    scene.details.retain(|&(l, r, k), _| {
        let (rows, cols) = shape(l);
        r < rows && k < cols
    });
    let dropped = before - scene.details.len();
    if dropped > 0 {
        format!(" ({dropped} details outside the new levels were dropped)")
    } else {
        String::new()
    }
}

fn level_data<'a>(ctx: &'a EditCtx, level: u32) -> Result<&'a LevelData, String> {
    ctx.levels
        .iter()
        .find(|(l, _)| l.0 == level)
        .map(|(_, d)| d)
        .ok_or_else(|| format!("level {level} is not built yet; try again after the next update"))
}

fn check_cell(rows: usize, cols: usize, row: usize, col: usize, level: u32) -> Result<(), String> {
    if row >= rows || col >= cols {
        return Err(format!(
            "handle ({row}, {col}) is outside level {level}, which has {rows} rows of {cols} tangents; use row 0..{} and column 0..{}",
            rows - 1,
            cols - 1
        ));
    }
    Ok(())
}

fn current_direction(ctx: &EditCtx, row: usize, col: usize) -> Result<DVec3, String> {
    let level = ctx.model.scene.edit_depth;
    if level == 0 {
        let net = ctx.model.scene.design.net();
        check_cell(net.rows(), net.cols(), row, col, 0)?;
        return Ok(net.get(row, col));
    }
    let l = &level_data(ctx, level)?.0;
    let (rows, cols) = l.shape();
    check_cell(rows, cols, row, col, level)?;
    Ok(l.tangents.get(row, col))
}

fn set_direction(ctx: &mut EditCtx, row: usize, col: usize, dir: DVec3) -> Result<String, String> {
    let dir = Tangent::new(dir)
        .map_err(|_| {
            format!(
                "direction ({}, {}, {}) is zero or not finite; give a non-zero direction",
                dir.x, dir.y, dir.z
            )
        })?
        .get();
    let level = ctx.model.scene.edit_depth;
    if ctx.model.scene.mirror && level > 0 {
        return Err(super::authoring::mirror_depth_msg());
    }
    if level == 0 {
        let net = ctx.model.scene.design.net();
        check_cell(net.rows(), net.cols(), row, col, 0)?;
        // mirrored: a seam (row 0) tangent stays in the mirror plane
        let dir = if ctx.model.scene.mirror && row == 0 {
            let plane = ctx.model.scene.design.mirror_plane();
            plane.project_dir(dir, col).map_err(|e| e.to_string())?
        } else {
            dir
        };
        if net.get(row, col) != dir {
            ctx.model
                .scene
                .design
                .set_tangent(row, col, dir)
                .map_err(|e| e.to_string())?;
            ctx.dirty.cell(0, row, col);
        }
        return Ok(format!(
            "control ({row}, {col}) set to ({:.4}, {:.4}, {:.4})",
            dir.x, dir.y, dir.z
        ));
    }
    let l = &level_data(ctx, level)?.0;
    let (rows, cols) = l.shape();
    check_cell(rows, cols, row, col, level)?;
    let local = multires::to_local(l.base(), row, col, dir);
    if ctx.model.scene.details.insert((level, row, col), local) != Some(local) {
        ctx.dirty.cell(level, row, col);
    }
    Ok(format!("detail ({row}, {col}) at level {level}"))
}

/// The rotation of a `Rotate` or `RotateMany` edit, its axis and angle checked.
fn rotation(axis: DVec3, radians: f64) -> Result<DQuat, String> {
    let axis = Tangent::new(axis)
        .map_err(|_| "the rotation axis is zero or not finite; give a non-zero axis".to_string())?
        .get();
    if !radians.is_finite() {
        return Err("the rotation angle is not finite; give a number of degrees".into());
    }
    Ok(DQuat::from_axis_angle(axis, radians))
}

fn set_length(ctx: &mut EditCtx, row: usize, col: usize, k: f64) -> Result<String, String> {
    if !(k.is_finite() && k > 0.0) {
        return Err(format!(
            "length coefficient {k} must be a positive finite number (1 keeps the length)"
        ));
    }
    let net = ctx.model.scene.design.net();
    check_cell(net.rows(), net.cols(), row, col, 0)?;
    let mut d = ctx.model.scene.design.clone();
    let old = d.params().s.row(row).to_vec();
    let mut s = old.clone();
    for i in 1..s.len() {
        let f = if i == col || i == col + 1 { k } else { 1.0 };
        s[i] = s[i - 1] + (old[i] - old[i - 1]) * f;
    }
    if s.iter().any(|v| !v.is_finite()) {
        return Err(format!(
            "length coefficient {k} makes s overflow; use a smaller one"
        ));
    }
    d.set_s_row(row, &s)
        .map_err(|e| format!("length coefficient {k} at ({row}, {col}) refused: {e}"))?;
    check_design(&d, ctx.model.scene.max_depth(), ctx.model.scene.mirror)
        .map_err(|e| format!("length coefficient {k} at ({row}, {col}) refused: {e}"))?;
    for (c, (a, b)) in old.iter().zip(d.params().s.row(row)).enumerate() {
        if a != b {
            ctx.dirty.cell(0, row, c);
        }
    }
    ctx.model.scene.design = d;
    Ok(format!("length coefficient {k} at ({row}, {col})"))
}

fn replace(ctx: &mut EditCtx, scene: Scene) {
    ctx.model.scene = scene;
    ctx.model.unsaved = false;
    ctx.history.clear();
    full(ctx);
}

/// Restores a scene from history: cells that differ are marked dirty (so
/// only they are rebuilt); a different shape or setting rebuilds everything.
fn restore(ctx: &mut EditCtx, target: Scene) {
    let cur = &ctx.model.scene;
    let (a, b) = (&cur.design, &target.design);
    let same = a.net().rows() == b.net().rows()
        && a.net().cols() == b.net().cols()
        && a.scheme() == b.scheme()
        && a.order() == b.order()
        && a.anchor() == b.anchor()
        && a.params().t == b.params().t
        && cur.interpolate_tangents == target.interpolate_tangents
        && !cur.mirror
        && !target.mirror
        && cur.initial == target.initial
        && cur.display_depth == target.display_depth
        && cur.edit_depth == target.edit_depth;
    if !same {
        ctx.model.scene = target;
        full(ctx);
        return;
    }
    for row in 0..a.net().rows() {
        for col in 0..a.net().cols() {
            if a.net().get(row, col) != b.net().get(row, col)
                || a.params().s.get(row, col) != b.params().s.get(row, col)
            {
                ctx.dirty.cell(0, row, col);
            }
        }
    }
    let (old, new) = (&cur.details, &target.details);
    for key in old.keys().chain(new.keys()) {
        if old.get(key) != new.get(key) {
            let &(level, row, col) = key;
            ctx.dirty.cell(level, row, col);
        }
    }
    ctx.model.scene = target;
}
