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
//! ([`crate::scene::edits::patch_edit::PatchEdit`]) are applied by
//! [`super::joined::patch_ops`]. With several patches, an edit that would
//! make a design the file checks refuse (details, fine tuning or tangent
//! interpolation on a G2 chain, a net a join cannot take) is refused,
//! naming the patch. The document's edits are in [`document`], the first
//! patch's own surface's in [`surface`].

mod document;
mod surface;

use document::apply_doc;

use super::components::{LevelData, SubdivisionLevel};
use super::edit_error::EditError;
use super::joined::patch_ops::DocWork;
use super::joined::world_io::JoinedParts;
use super::messages::{Edit, EditMessage};
use super::patch::scene_io::PatchParts;
use super::resources::*;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use std::time::Instant;

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
            | Edit::Author(crate::scene::edits::edit::AuthorEdit::NewDesign { .. })
    )
}
