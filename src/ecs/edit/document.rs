//! The edits of the document: undo and redo, loading and replacing,
//! importing, patch edits, and the edits of a later patch or of a
//! detail of a G2 run's first patch (module documentation of [`super`]).

use crate::ecs::edit_error::EditError;
use crate::ecs::edit_state::DocState;
use crate::ecs::joined::patch_ops::{self, DocWork};
use crate::ecs::messages::Edit;
use crate::scene::{Scene, design::document_io};
use bevy::prelude::*;
use streamline_kernel::joins::merged::g2_detail_base;
use streamline_kernel::levels::multires::{self, Details};
use streamline_kernel::{DVec3, Tangent};

use super::surface::{apply, check_cell, rotation};
use super::{EditCtx, is_document_edit, is_handle_edit};

/// Applies one edit to the document (module documentation).
pub(super) fn apply_doc(
    ctx: &mut EditCtx,
    work: &mut DocWork,
    edit: &Edit,
) -> Result<String, EditError> {
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
        Edit::Author(a @ crate::scene::edits::edit::AuthorEdit::NewDesign { .. }) => {
            let (msg, effect) = crate::ecs::authoring::apply(&mut work.state.first, a)?;
            if let crate::ecs::authoring::Effect::NewScene(new) = effect {
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
        initial: crate::scene::files::format_v3::placeholder_initial(),
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
    let stacks = crate::scene::design::document_build::stacks(&doc, level)
        .map_err(|e| EditError::Patch(e.message))?;
    let levels = &stacks[i].levels;
    let (Some(prev), Some(cur)) = (levels.get(level as usize - 1), levels.get(level as usize))
    else {
        return Err(EditError::LevelNotBuilt { level });
    };
    // the frame: the merged level of a G2 chain, else the patch's own
    let head = crate::scene::design::document_build::g2_head(&doc, i);
    let run = crate::scene::design::document_build::g2_run_from(&doc, head);
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
            crate::ecs::edit_state::StartState::Edge {
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
        work.state = crate::ecs::edit_state::DocState::of_scene(scene.clone());
        work.active = 0;
        // the imported design is in no file yet: Save asks for one
        ctx.model.path = None;
        return Ok(format!("imported {} as a new design", scene.name));
    }
    let name = import_patch_name(&work.state, &scene.name);
    let before = work.state.clone();
    work.state.joined.push(crate::ecs::edit_state::JoinedState {
        name: name.clone(),
        start: crate::ecs::edit_state::StartState::Curve(scene.initial.clone()),
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
fn import_patch_name(state: &crate::ecs::edit_state::DocState, scene: &str) -> String {
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
