//! The edit stage: the only system that changes the model. The frame's
//! edits are applied one after another to the document's state, assembled
//! from its entities (the first patch's scene by
//! [`super::patch::scene_io`], the later patches by
//! [`super::joined::world_io`]); undo steps record the whole document;
//! then the state is written back into the components, value by value, so
//! that only what an edit really changed is marked changed. What to redo
//! follows from those changes alone ([`super::patch::track`],
//! [`super::joined::build`]).
//!
//! Handle edits (`SetDirection`, `Rotate`, `SetLength`, `RotateMany`),
//! `ClearDetail`, the fine-tuning edits and `SetInterpolateTangents` act on
//! the [`super::joined::ActivePatch`]: on a later patch they change its
//! control net, details, fine tuning or tangent interpolation
//! ([`joined_edit`]); the other edits of one surface (scheme, blend order,
//! initial curve) act on the first patch only. Patch edits
//! ([`crate::scene::patch_edit::PatchEdit`]) are applied by
//! [`super::joined::patch_ops`]. With several patches, an edit that would
//! make a design the file checks refuse (details, fine tuning or tangent
//! interpolation on a G2 chain, a net a join cannot take) is refused,
//! naming the patch.

use super::components::{LevelData, SubdivisionLevel};
use super::edit_error::EditError;
use super::edit_state::DocState;
use super::joined::patch_ops::{self, DocWork};
use super::joined::world_io::JoinedParts;
use super::messages::{Edit, EditMessage};
use super::patch::scene_io::PatchParts;
use super::resources::*;
use crate::scene::{Scene, document_io};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::joins::merged::g2_detail_base;
use streamline_kernel::levels::incremental::check_params;
use streamline_kernel::levels::multires::{self, Details};
use streamline_kernel::{DQuat, DVec3, Design, Tangent};

/// What the edit system reads and writes.
#[derive(SystemParam)]
pub(crate) struct EditCtx<'w, 's> {
    model: ResMut<'w, Model>,
    history: ResMut<'w, History>,
    config: Res<'w, ModelConfig>,
    levels: Query<'w, 's, (&'static SubdivisionLevel, &'static LevelData)>,
}

/// The document's entities, writable: the first patch and the later ones.
#[derive(SystemParam)]
pub(crate) struct DocParts<'w, 's> {
    first: PatchParts<'w, 's>,
    joined: JoinedParts<'w, 's>,
}

pub(crate) fn apply_edits(
    meter: Res<super::meter::CpuMeter>,
    mut reader: MessageReader<EditMessage>,
    mut ctx: EditCtx,
    mut parts: DocParts,
    mut log: ResMut<EditLog>,
    mut stats: ResMut<Stats>,
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    let mut labels = Vec::new();
    let mut work: Option<DocWork> = None;
    let mut changed = false;
    for msg in reader.read() {
        if labels.is_empty() {
            log.entries.clear();
            log.frame += 1;
        }
        labels.push(msg.edit.label());
        if matches!(msg.edit, Edit::Save(_) | Edit::Export(_)) {
            continue; // the output stage, after the mesh is up to date
        }
        let work = match &mut work {
            Some(w) => w,
            None => match parts.first.assemble() {
                Ok(s) => {
                    let (state, active) = parts.joined.read(s);
                    work.insert(DocWork { state, active })
                }
                Err(e) => {
                    log.entries.push(Err(EditError::Assemble(e)));
                    continue;
                }
            },
        };
        let undoable = msg.edit.is_undoable();
        let snapshot = undoable.then(|| work.state.clone());
        match apply_doc(&mut ctx, work, &msg.edit) {
            Ok(done) => {
                changed = true;
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
    if let (true, Some(w)) = (changed, &work) {
        parts.first.write(&w.state.first);
        parts.joined.write(&w.state, w.active);
    }
    if !labels.is_empty() {
        stats.last = EditStats {
            edit: labels.join("; "),
            us_edit: t0.elapsed().as_secs_f64() * 1e6,
            ..Default::default()
        };
        stats.collecting = true;
    }
}

/// A handle edit: one that acts on the active patch.
fn is_handle_edit(edit: &Edit) -> bool {
    matches!(
        edit,
        Edit::SetDirection { .. }
            | Edit::Rotate { .. }
            | Edit::SetLength { .. }
            | Edit::RotateMany { .. }
    )
}

/// An edit of the whole document, whichever patch is active.
fn is_document_edit(edit: &Edit) -> bool {
    matches!(
        edit,
        Edit::SetDisplayDepth(_)
            | Edit::SetEditDepth(_)
            | Edit::Undo
            | Edit::Redo
            | Edit::CancelGroup(_)
            | Edit::Load(_)
            | Edit::Replace(_)
            | Edit::Recover { .. }
            | Edit::Save(_)
            | Edit::Export(_)
            | Edit::Patch(_)
            | Edit::Import { .. }
            | Edit::SetReference(_)
            | Edit::Author(crate::scene::edit::AuthorEdit::NewDesign { .. })
    )
}

/// Applies one edit to the document (module documentation).
fn apply_doc(ctx: &mut EditCtx, work: &mut DocWork, edit: &Edit) -> Result<String, EditError> {
    match edit {
        Edit::Patch(p) => return patch_ops::apply(work, p).map_err(EditError::Patch),
        Edit::Undo | Edit::Redo => {
            let undo = matches!(edit, Edit::Undo);
            let cur = work.state.clone();
            let target = ctx.history.step(undo, cur).ok_or(if undo {
                EditError::NothingToUndo
            } else {
                EditError::NothingToRedo
            })?;
            set_state(work, target);
            ctx.model.unsaved = true;
            return Ok(if undo { "undone" } else { "redone" }.into());
        }
        Edit::CancelGroup(g) => {
            let (target, was_unsaved) = ctx
                .history
                .cancel(*g)
                .ok_or(EditError::NotLastDrag { group: *g })?;
            set_state(work, target);
            ctx.model.unsaved = was_unsaved;
            return Ok("drag cancelled".into());
        }
        Edit::Load(path) => {
            let loaded = document_io::load(path).map_err(EditError::Load)?;
            replace(ctx, work, DocState::of_document(&loaded));
            ctx.model.path = Some(path.clone());
            return Ok(format!("loaded {}", path.display()));
        }
        Edit::Replace(new) => {
            replace(ctx, work, DocState::of_scene((**new).clone()));
            ctx.model.path = None;
            // a design fitted to a reference exists in no file yet (a
            // built-in or a new empty scene is nothing to lose)
            ctx.model.unsaved = new.reference.is_some();
            return Ok(format!("opened {}", new.name));
        }
        Edit::Recover { document, origin } => {
            replace(ctx, work, DocState::of_document(document));
            ctx.model.path = origin.clone();
            ctx.model.unsaved = true;
            return Ok(format!("recovered {}", document.name));
        }
        Edit::Import { scene, as_patch } => return import(ctx, work, scene, *as_patch),
        Edit::SetReference(link) => {
            work.state.first.reference.clone_from(link);
            return Ok(match link {
                Some(l) => format!("reference {} face {}", l.path.display(), l.face),
                None => "reference detached".into(),
            });
        }
        Edit::Author(a @ crate::scene::edit::AuthorEdit::NewDesign { .. }) => {
            let (msg, effect) = super::authoring::apply(&mut work.state.first, a)?;
            if let super::authoring::Effect::NewScene(new) = effect {
                replace(ctx, work, DocState::of_scene(*new));
                ctx.model.path = None;
                ctx.model.unsaved = true;
            }
            return Ok(msg);
        }
        _ => {}
    }
    if work.active > 0 && is_joined_edit(edit) {
        return joined_edit(ctx, work, edit);
    }
    if work.active > 0 && !is_document_edit(edit) {
        return Err(EditError::Patch(format!(
            "`{}` acts on the first patch only; on `{}` use the handle edits (SetDirection, Rotate, SetLength, RotateMany), ClearDetail, the fine-tuning edits or SetInterpolateTangents, or SetPatch to the first patch before it",
            edit.label(),
            work.state.name(work.active)
        )));
    }
    // a detail of the first patch when it heads a G2 chain: in the frame of
    // the chain's merged level, the one drawn
    let level = work.state.first.edit_depth;
    if level > 0
        && is_handle_edit(edit)
        && !matches!(edit, Edit::SetLength { .. })
        && heads_g2(&work.state)
    {
        let before = work.state.clone();
        let mut details = work.state.first.details.clone();
        let done = detail_edit(&work.state, 0, level, &mut details, edit)?;
        work.state.first.details = details;
        if let Err(m) = patch_ops::check(&work.state) {
            work.state = before;
            return Err(EditError::Patch(format!("`{}` refused: {m}", edit.label())));
        }
        return Ok(done);
    }
    // an edit of the first patch; with several patches, checked as a file would be
    let level0 = is_handle_edit(edit) && level == 0;
    let before = (!work.state.joined.is_empty() && !level0).then(|| work.state.clone());
    let done = apply(ctx, &mut work.state.first, edit)?;
    work.state.sync_seams();
    if let Some(b) = before
        && let Err(m) = patch_ops::check(&work.state)
    {
        work.state = b;
        return Err(EditError::Patch(format!("`{}` refused: {m}", edit.label())));
    }
    Ok(done)
}

/// Restores a recorded document; the active patch stays when it is still there.
fn set_state(work: &mut DocWork, target: DocState) {
    if work.active >= target.len() {
        work.active = 0;
    }
    work.state = target;
}

/// An edit of the active later patch's own surface: its handles (its
/// control net at edit depth 0, its details above, docs/math.md §5), its
/// fine tuning, its tangent interpolation or a detail cleared. Applied to a
/// scene of the patch as the first patch's are ([`apply`]), its handles
/// above depth 0 read from the document built to the edit depth
/// ([`detail_edit`]); a seam column shared with the patch it starts on
/// is refused ([`patch_ops::check_joined_cell`]), and so is a result the
/// file's checks would refuse (the document is then as it was).
fn joined_edit(ctx: &mut EditCtx, work: &mut DocWork, edit: &Edit) -> Result<String, EditError> {
    let i = work.active;
    let name = work.state.name(i).to_string();
    let level = work.state.first.edit_depth;
    let cells = match edit {
        Edit::SetDirection { row, col, .. } | Edit::Rotate { row, col, .. } => vec![(*row, *col)],
        Edit::SetLength { row, col, .. } => vec![(*row, *col)],
        Edit::RotateMany { handles, .. } => handles.clone(),
        _ => Vec::new(),
    };
    let detail = level > 0 && is_handle_edit(edit) && !matches!(edit, Edit::SetLength { .. });
    for &(r, c) in &cells {
        match detail {
            true => patch_ops::check_joined_seam(&work.state, i, c).map_err(EditError::Patch)?,
            false => {
                patch_ops::check_joined_cell(&work.state, i, r, c).map_err(EditError::Patch)?
            }
        }
    }
    let first = &work.state.first;
    let j = &work.state.joined[i - 1];
    let mut scene = Scene {
        name: name.clone(),
        design: j.design.clone(),
        initial: crate::scene::format_v3::placeholder_initial(),
        details: j.details.clone(),
        display_depth: first.display_depth,
        edit_depth: level,
        view: first.view,
        tuning: j.tuning.clone(),
        interpolate_tangents: j.interpolate_tangents,
        mirror: false,
        reference: first.reference.clone(),
    };
    let done = match detail {
        true => detail_edit(&work.state, i, level, &mut scene.details, edit)?,
        false => apply(ctx, &mut scene, edit)?,
    };
    let before = work.state.clone();
    let j = &mut work.state.joined[i - 1];
    j.design = scene.design;
    j.details = scene.details;
    j.tuning = scene.tuning;
    j.interpolate_tangents = scene.interpolate_tangents;
    work.state.sync_seams();
    if let Err(m) = patch_ops::check(&work.state) {
        work.state = before;
        return Err(EditError::Patch(format!("`{}` refused: {m}", edit.label())));
    }
    Ok(format!("{done} on `{name}`"))
}

/// A handle edit of patch `i` at the edit depth `L > 0`: a detail of its
/// level `L` (docs/math.md §5), in the frame of that level as subdivided
/// from level `L − 1` of the document built to depth `L` (what its build
/// applies the detail to, before a join's G1 column, §11): for a patch of a
/// G2 chain, the chain's merged level ([`g2_detail_base`]), the level that
/// is drawn. The details are written into `details`.
fn detail_edit(
    state: &DocState,
    i: usize,
    level: u32,
    details: &mut Details,
    edit: &Edit,
) -> Result<String, EditError> {
    let doc = state.to_document();
    let stacks = crate::scene::document_build::stacks(&doc, level)
        .map_err(|e| EditError::Patch(e.message))?;
    let levels = &stacks[i].levels;
    let (Some(prev), Some(cur)) = (levels.get(level as usize - 1), levels.get(level as usize))
    else {
        return Err(EditError::LevelNotBuilt { level });
    };
    // the frame: the merged level of a G2 chain, else the patch's own
    let head = crate::scene::document_build::g2_head(&doc, i);
    let run = crate::scene::document_build::g2_run_from(&doc, head);
    let (base, offset) = if run.len() > 1 {
        let effective: Vec<_> = run
            .iter()
            .map(|&k| doc.patches[k].effective_design())
            .collect();
        let parts: Vec<_> = (run.iter().zip(&effective))
            .map(|(&k, d)| doc.patches[k].parts(d))
            .collect();
        let member = run.iter().position(|&k| k == i).unwrap_or(0);
        g2_detail_base(&parts, member, level).map_err(|e| EditError::Patch(e.to_string()))?
    } else {
        let d = doc.patches[i].effective_design();
        (d.refine(prev, level)?.tangents, 0)
    };
    // inside the level as built here and as the patch's own levels have it
    // (a G2 chain's cut and the patch alone differ at the cut for the
    // approximating schemes; a detail lives in both)
    let own = doc.patches[i].design.net();
    let (own_rows, own_cols) =
        doc.patches[i]
            .design
            .scheme()
            .check_depth(own.rows(), own.cols(), level)?;
    let rows = cur.tangents.rows().min(own_rows);
    let cols = cur.tangents.cols().min(own_cols);
    let mut turn = |row: usize, col: usize, dir: DVec3| -> Result<(), EditError> {
        check_cell(rows, cols, row, col, level)?;
        let dir = Tangent::new(dir)
            .map_err(|_| EditError::BadDirection { dir })?
            .get();
        let local = multires::to_local(&base, row, offset + col, dir);
        details.insert((level, row, col), local);
        Ok(())
    };
    let current = |row: usize, col: usize| -> Result<DVec3, EditError> {
        check_cell(rows, cols, row, col, level)?;
        Ok(cur.tangents.get(row, col))
    };
    match edit {
        Edit::SetDirection { row, col, dir } => {
            turn(*row, *col, *dir)?;
            Ok(format!("detail ({row}, {col}) at level {level}"))
        }
        Edit::Rotate {
            row,
            col,
            axis,
            radians,
        } => {
            let q = rotation(*axis, *radians)?;
            turn(*row, *col, q * current(*row, *col)?)?;
            Ok(format!("detail ({row}, {col}) at level {level}"))
        }
        Edit::RotateMany {
            handles,
            axis,
            radians,
        } => {
            let q = rotation(*axis, *radians)?;
            if handles.is_empty() {
                return Err(EditError::NoHandles);
            }
            let dirs = handles
                .iter()
                .map(|&(r, c)| current(r, c).map(|d| q * d))
                .collect::<Result<Vec<_>, _>>()?;
            for (&(r, c), d) in handles.iter().zip(dirs) {
                turn(r, c, d)?;
            }
            Ok(format!(
                "rotated {} handles by {:.3}° at level {level}",
                handles.len(),
                radians.to_degrees()
            ))
        }
        _ => Err(EditError::Patch(format!(
            "`{}` is not a handle edit",
            edit.label()
        ))),
    }
}

/// Whether the first patch heads a G2 chain (a patch G2-chained on its End).
fn heads_g2(state: &DocState) -> bool {
    state.joined.iter().any(|j| {
        matches!(
            j.start,
            super::edit_state::StartState::Edge {
                parent: 0,
                edge: streamline_kernel::joins::Edge::End,
                continuity: streamline_kernel::joins::Continuity::G2,
            }
        )
    })
}

/// The edits of one surface that act on a later patch (the rest act on
/// the first patch only).
fn is_joined_edit(edit: &Edit) -> bool {
    is_handle_edit(edit)
        || matches!(
            edit,
            Edit::ClearDetail { .. }
                | Edit::SetTuning(_)
                | Edit::SetTuningValue { .. }
                | Edit::SetTuningConstraint(_)
                | Edit::SetInterpolateTangents(_)
        )
}

fn apply(ctx: &mut EditCtx, scene: &mut Scene, edit: &Edit) -> Result<String, EditError> {
    match edit {
        Edit::SetDirection { row, col, dir } => set_direction(ctx, scene, *row, *col, *dir),
        Edit::Rotate {
            row,
            col,
            axis,
            radians,
        } => {
            let q = rotation(*axis, *radians)?;
            let cur = current_direction(ctx, scene, *row, *col)?;
            let dir = q * cur;
            set_direction(ctx, scene, *row, *col, dir)
        }
        Edit::SetLength {
            row,
            col,
            coefficient,
        } => set_length(scene, *row, *col, *coefficient),
        Edit::ClearDetail { row, col } => {
            let level = scene.edit_depth;
            let key = (level, *row, *col);
            if scene.details.remove(&key).is_none() {
                return Err(EditError::NoDetail {
                    row: *row,
                    col: *col,
                    level,
                });
            }
            Ok(format!("cleared detail ({row}, {col}) at level {level}"))
        }
        Edit::SetScheme(s) => {
            let s = s.validate()?;
            let mut d = scene.design.clone();
            d.set_scheme(s)?;
            check_design(&d, scene.max_depth(), scene.mirror)?;
            scene.design = d;
            let dropped = prune_details(scene);
            Ok(format!("scheme {}{dropped}", s.name()))
        }
        Edit::SetBlendOrder(o) => {
            scene.design.set_order(*o);
            Ok(format!("blend order {}", o.name()))
        }
        Edit::SetDisplayDepth(n) => {
            let depth = (*n).max(scene.edit_depth);
            check_design(&scene.design, depth, scene.mirror)?;
            scene.display_depth = *n;
            Ok(format!("display depth {n}"))
        }
        Edit::SetEditDepth(n) => {
            if *n > 0 && scene.mirror {
                return Err(EditError::MirrorDepth);
            }
            let depth = (*n).max(scene.display_depth);
            check_design(&scene.design, depth, scene.mirror)?;
            scene.edit_depth = *n;
            Ok(format!("edit depth {n}"))
        }
        Edit::SetTuning(t) => {
            scene.tuning = t.clone();
            Ok(if t.is_some() {
                "fine tuning on".into()
            } else {
                "fine tuning off".into()
            })
        }
        Edit::SetTuningValue { row, col, value } => {
            let tuning = scene.tuning.get_or_insert_with(SurfaceTuning::identity);
            tuning
                .function
                .set(*row, *col, *value)
                .map_err(EditError::TuningValue)?;
            Ok(format!("fine-tuning value ({row}, {col}) = {value}"))
        }
        Edit::SetTuningConstraint(c) => {
            scene
                .tuning
                .get_or_insert_with(SurfaceTuning::identity)
                .constraint = *c;
            Ok(format!("fine-tuning constraint {}", c.name()))
        }
        Edit::SetInterpolateTangents(on) => {
            scene.interpolate_tangents = *on;
            Ok(
                if *on
                    && !streamline_kernel::levels::tangent_interpolation::applies(
                        scene.design.scheme(),
                    )
                {
                    "interpolate control tangents on (Kobbelt interpolates them already)".into()
                } else {
                    format!("interpolate control tangents {on}")
                },
            )
        }
        Edit::Save(_) | Edit::Export(_) => Ok(String::new()),
        Edit::RotateMany {
            handles,
            axis,
            radians,
        } => {
            let q = rotation(*axis, *radians)?;
            if handles.is_empty() {
                return Err(EditError::NoHandles);
            }
            // every handle checked before any is turned: all or nothing
            let dirs = handles
                .iter()
                .map(|&(r, c)| current_direction(ctx, scene, r, c).map(|d| q * d))
                .collect::<Result<Vec<_>, _>>()?;
            for (&(r, c), d) in handles.iter().zip(dirs) {
                set_direction(ctx, scene, r, c, d)?;
            }
            Ok(format!(
                "rotated {} handles by {:.3}°",
                handles.len(),
                radians.to_degrees()
            ))
        }
        Edit::Author(a) => Ok(super::authoring::apply(scene, a)?.0),
        // the document's edits (apply_doc)
        Edit::Undo
        | Edit::Redo
        | Edit::CancelGroup(_)
        | Edit::Load(_)
        | Edit::Replace(_)
        | Edit::Recover { .. }
        | Edit::Import { .. }
        | Edit::SetReference(_)
        | Edit::Patch(_) => Ok(String::new()),
    }
}

/// `d` can be built to `depth`; mirrored, its doubled design too
/// (`docs/math.md §9`: the levels are the doubled net's).
fn check_design(d: &Design, depth: u32, mirror: bool) -> Result<(), EditError> {
    d.scheme()
        .check_depth(d.net().rows(), d.net().cols(), depth)?;
    check_params(d, depth)?;
    if mirror {
        let m = d.mirrored()?;
        m.scheme()
            .check_depth(m.net().rows(), m.net().cols(), depth)
            .and_then(|_| check_params(&m, depth))
            .map_err(EditError::MirroredSurface)?;
    }
    Ok(())
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

fn level_data<'a>(ctx: &'a EditCtx, level: u32) -> Result<&'a LevelData, EditError> {
    ctx.levels
        .iter()
        .find(|(l, _)| l.0 == level)
        .map(|(_, d)| d)
        .ok_or(EditError::LevelNotBuilt { level })
}

fn check_cell(
    rows: usize,
    cols: usize,
    row: usize,
    col: usize,
    level: u32,
) -> Result<(), EditError> {
    if row >= rows || col >= cols {
        return Err(EditError::OutsideLevel {
            row,
            col,
            level,
            rows,
            cols,
        });
    }
    Ok(())
}

fn current_direction(
    ctx: &EditCtx,
    scene: &Scene,
    row: usize,
    col: usize,
) -> Result<DVec3, EditError> {
    let level = scene.edit_depth;
    if level == 0 {
        let net = scene.design.net();
        check_cell(net.rows(), net.cols(), row, col, 0)?;
        return Ok(net.get(row, col));
    }
    let l = &level_data(ctx, level)?.0;
    let (rows, cols) = l.shape();
    check_cell(rows, cols, row, col, level)?;
    Ok(l.tangents.get(row, col))
}

fn set_direction(
    ctx: &mut EditCtx,
    scene: &mut Scene,
    row: usize,
    col: usize,
    dir: DVec3,
) -> Result<String, EditError> {
    let dir = Tangent::new(dir)
        .map_err(|_| EditError::BadDirection { dir })?
        .get();
    let level = scene.edit_depth;
    if scene.mirror && level > 0 {
        return Err(EditError::MirrorDepth);
    }
    if level == 0 {
        let net = scene.design.net();
        check_cell(net.rows(), net.cols(), row, col, 0)?;
        // mirrored: a seam (row 0) tangent stays in the mirror plane
        let dir = if scene.mirror && row == 0 {
            let plane = scene.design.mirror_plane();
            plane.project_dir(dir, col)?
        } else {
            dir
        };
        if net.get(row, col) != dir {
            scene.design.set_tangent(row, col, dir)?;
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
    scene.details.insert((level, row, col), local);
    Ok(format!("detail ({row}, {col}) at level {level}"))
}

/// The rotation of a `Rotate` or `RotateMany` edit, its axis and angle checked.
fn rotation(axis: DVec3, radians: f64) -> Result<DQuat, EditError> {
    let axis = Tangent::new(axis).map_err(|_| EditError::BadAxis)?.get();
    if !radians.is_finite() {
        return Err(EditError::BadAngle);
    }
    Ok(DQuat::from_axis_angle(axis, radians))
}

fn set_length(scene: &mut Scene, row: usize, col: usize, k: f64) -> Result<String, EditError> {
    if !(k.is_finite() && k > 0.0) {
        return Err(EditError::BadLength { k });
    }
    let net = scene.design.net();
    check_cell(net.rows(), net.cols(), row, col, 0)?;
    let mut d = scene.design.clone();
    let old = d.params().s.row(row).to_vec();
    let mut s = old.clone();
    for i in 1..s.len() {
        let f = if i == col || i == col + 1 { k } else { 1.0 };
        s[i] = s[i - 1] + (old[i] - old[i - 1]) * f;
    }
    if s.iter().any(|v| !v.is_finite()) {
        return Err(EditError::LengthOverflow { k });
    }
    let refused = |e: EditError| EditError::LengthRefused {
        k,
        row,
        col,
        reason: Box::new(e),
    };
    d.set_s_row(row, &s).map_err(|e| refused(e.into()))?;
    check_design(&d, scene.max_depth(), scene.mirror).map_err(refused)?;
    scene.design = d;
    Ok(format!("length coefficient {k} at ({row}, {col})"))
}

/// File ▸ Import surface… (`Edit::Import`, one undo step): `scene` as the
/// design, or its surface as a new patch on its own initial curve, named
/// after the scene (`-2`, `-3`… when taken), the design's reference kept
/// (the scene's when it has none). A patch the file's checks would refuse
/// is refused, the document as it was.
fn import(
    ctx: &mut EditCtx,
    work: &mut DocWork,
    scene: &Scene,
    as_patch: bool,
) -> Result<String, EditError> {
    if !as_patch {
        work.state = super::edit_state::DocState::of_scene(scene.clone());
        work.active = 0;
        // the imported design is in no file yet: Save asks for one
        ctx.model.path = None;
        return Ok(format!("imported {} as a new design", scene.name));
    }
    let name = import_patch_name(&work.state, &scene.name);
    let before = work.state.clone();
    work.state.joined.push(super::edit_state::JoinedState {
        name: name.clone(),
        start: super::edit_state::StartState::Curve(scene.initial.clone()),
        design: scene.design.clone(),
        details: scene.details.clone(),
        tuning: scene.tuning.clone(),
        interpolate_tangents: scene.interpolate_tangents,
        hidden: false,
    });
    if work.state.first.reference.is_none() {
        work.state.first.reference.clone_from(&scene.reference);
    }
    if let Err(m) = patch_ops::check(&work.state) {
        work.state = before;
        return Err(EditError::Patch(format!(
            "importing `{}` as a new patch refused: {m}",
            scene.name
        )));
    }
    Ok(format!("imported {} as patch `{name}`", scene.name))
}

/// A patch name for an imported scene named `scene`: its letters, digits,
/// `-` and `_` (32 at most; `imported` when none), with `-2`, `-3`… when
/// the document has a patch of that name.
fn import_patch_name(state: &super::edit_state::DocState, scene: &str) -> String {
    let mut base: String = scene
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .take(28)
        .collect();
    if base.is_empty() {
        base = "imported".into();
    }
    if state.index(&base).is_none() {
        return base;
    }
    (2..)
        .map(|k| format!("{base}-{k}"))
        .find(|n| state.index(n).is_none())
        .unwrap_or(base)
}

/// A document from elsewhere (a file, a new design, a recovery) replaces
/// the current one, and the history starts afresh. Written back like any
/// edit: what differs from the current document is what is rebuilt.
fn replace(ctx: &mut EditCtx, work: &mut DocWork, new: DocState) {
    work.state = new;
    work.active = 0;
    ctx.model.unsaved = false;
    ctx.history.clear();
}
