//! The File feature's dialogs: edits that failed ("Something went
//! wrong"), the unsaved-changes question (before new, open and quit) and
//! the offer to recover autosaved work ([`recover`]).

use super::editor_dirs::EditorDirs;
use super::open_save::{Dialog, FileUi, PathAction, Pending, browse, run_pending, suggested_path};
use crate::ecs::patch::PatchRef;
use crate::ecs::{Edit, EditMessage, Model};
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use std::path::PathBuf;

pub struct DialogsPlugin;

impl Plugin for DialogsPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(EguiPrimaryContextPass, dialogs);
    }
}

/// Shows the edits that failed and the dialog on screen, and does what
/// its buttons say.
fn dialogs(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    (model, patch): (Res<Model>, PatchRef),
    dirs: Res<EditorDirs>,
    mut ui: ResMut<FileUi>,
    mut edits: MessageWriter<EditMessage>,
    mut exit: MessageWriter<AppExit>,
) -> Result {
    let _meter = meter.start();
    let ctx = contexts.ctx_mut()?.clone();
    if !ui.errors.is_empty() {
        let mut open = true;
        egui::Window::new("Something went wrong")
            .collapsible(false)
            .anchor(egui::Align2::CENTER_TOP, egui::vec2(0.0, 40.0))
            .open(&mut open)
            .show(&ctx, |w| {
                for e in &ui.errors {
                    w.colored_label(egui::Color32::from_rgb(255, 170, 160), e);
                }
                w.label(egui::RichText::new("The current scene is unchanged.").weak());
                if w.button("OK").on_hover_text("Close this message").clicked() {
                    ui.errors.clear();
                }
            });
        if !open {
            ui.errors.clear();
        }
    }
    let Some(dialog) = ui.dialog.clone() else {
        return Ok(());
    };
    let mut close = false;
    let modal =
        egui::Modal::new(egui::Id::new("file_dialog")).show(&ctx, |m| match dialog.clone() {
            Dialog::Unsaved(p) => {
                m.heading("Unsaved changes");
                m.label(format!(
                    "“{}” has changes that are not saved. Save them first?",
                    patch.name()
                ));
                m.horizontal(|h| {
                    if h.button("Save").on_hover_text("Save, then go on").clicked() {
                        match &model.path {
                            Some(path) => {
                                edits.write(EditMessage::from(Edit::Save(path.clone())));
                                ui.after_save = Some(p.clone());
                                close = true;
                            }
                            None => {
                                browse(
                                    &mut ui,
                                    PathAction::SaveAs,
                                    suggested_path(&model, patch.name(), "ron"),
                                    Some(p.clone()),
                                );
                                close = true;
                            }
                        }
                    }
                    if h.button("Discard")
                        .on_hover_text("Lose the changes and go on")
                        .clicked()
                    {
                        close = true;
                        if p == Pending::Quit {
                            ui.discarded = true;
                            let _ = std::fs::remove_file(dirs.recovery_file());
                        }
                        run_pending(p.clone(), &mut ui, &mut edits, &mut exit);
                    }
                    if h.button("Cancel").on_hover_text("Keep editing").clicked() {
                        close = true;
                    }
                });
            }
            Dialog::Recover { when, origin } => {
                m.heading("Recover unsaved work?");
                m.label(format!(
                    "An autosave from {when} of {} is newer than the scene.",
                    origin
                        .as_ref()
                        .map(|p| p.display().to_string())
                        .unwrap_or_else(|| "an unsaved scene".into())
                ));
                m.horizontal(|h| {
                    if h.button("Recover")
                        .on_hover_text("Open the autosaved scene")
                        .clicked()
                    {
                        recover(&dirs, origin.clone(), &mut edits, &mut ui);
                        close = true;
                    }
                    if h.button("Discard")
                        .on_hover_text("Delete the autosave and keep the scene")
                        .clicked()
                    {
                        let _ = std::fs::remove_file(dirs.recovery_file());
                        let _ = std::fs::remove_file(dirs.recovery_meta());
                        close = true;
                    }
                });
            }
        });
    // a branch that moved on to another dialog keeps that one
    if close {
        if ui.dialog.as_ref() == Some(&dialog) {
            ui.dialog = None;
        }
    } else if modal.should_close() {
        ui.dialog = None;
    }
    Ok(())
}

/// Opens the recovery file (every patch) as the current (unsaved) design.
pub(super) fn recover(
    dirs: &EditorDirs,
    origin: Option<PathBuf>,
    edits: &mut MessageWriter<EditMessage>,
    ui: &mut FileUi,
) {
    match crate::scene::design::document_io::load(&dirs.recovery_file()) {
        Ok(document) => {
            edits.write(EditMessage::from(Edit::Recover {
                document: Box::new(document),
                origin,
            }));
        }
        Err(e) => ui
            .errors
            .push(format!("the autosave cannot be recovered: {e}")),
    }
}
