//! Files: new, open, save, save as, export OBJ/STL and recent files, with
//! the unsaved-changes question before new, open and quit (the dialogs,
//! with their own plugin, are `dialogs.rs`; a failed open keeps the current scene: the model refuses
//! it). Files are picked in the editor's own file browser (`file_browser.rs`:
//! no native file dialog, which would need GTK or a desktop portal on
//! Linux); this file asks it for one with [`browse`] (what for:
//! `path_action.rs`). Where the editor keeps its own files, the recent list
//! among them, is `editor_dirs.rs`.

use crate::ecs::patch::PatchRef;
use crate::ecs::{Edit, EditLog, EditMessage, Model};
use crate::scene::design::builtin;
use bevy::prelude::*;
use bevy::window::WindowCloseRequested;
use bevy_egui::input::egui_wants_any_keyboard_input;
use std::path::{Path, PathBuf};

pub use super::editor_dirs::{EditorDirs, RECENT_MAX};
use super::editor_dirs::{read_recent, save_recent};
pub use super::path_action::PathAction;

/// What waits for the unsaved-changes answer.
#[derive(Debug, Clone, PartialEq)]
pub enum Pending {
    /// Replace the scene with a built-in one.
    New(String),
    /// Replace the scene with a new design (File ▸ New ▸ New design…).
    NewDesign(Box<crate::ecs::authoring::AuthorEdit>),
    /// Open a file.
    Open(PathBuf),
    /// Quit the editor.
    Quit,
}

/// A request for the file browser.
#[derive(Debug, Clone, PartialEq)]
pub struct Browse {
    /// What for.
    pub action: PathAction,
    /// Where it starts: a file (its folder is shown and, for a save, its
    /// name proposed) or a folder.
    pub start: PathBuf,
    /// What to do after a save-as (from the unsaved prompt).
    pub then: Option<Pending>,
}

/// A dialog on screen.
#[derive(Debug, Clone, PartialEq)]
pub enum Dialog {
    /// Unsaved changes: save, discard or cancel before `then`.
    Unsaved(Pending),
    /// Offer to recover autosaved work.
    Recover {
        /// When it was written.
        when: String,
        /// Where it came from.
        origin: Option<PathBuf>,
    },
}

/// The File feature's state.
#[derive(Resource, Debug, Default)]
pub struct FileUi {
    /// The dialog shown.
    pub dialog: Option<Dialog>,
    /// A file to pick, for the file browser to open (`file_browser.rs`).
    pub browse: Option<Browse>,
    /// Whether the file browser is on screen (the shortcuts wait).
    pub browsing: bool,
    /// Error messages to show (failed open, save, export, refused edits).
    pub errors: Vec<String>,
    /// Recently opened or saved files, newest first.
    pub recent: Vec<PathBuf>,
    /// To do once the save in flight has succeeded.
    pub(super) after_save: Option<Pending>,
    /// The user chose to discard changes on quit (no recovery file then).
    pub discarded: bool,
    /// The last edit-log frame looked at.
    log_frame: u64,
    /// The model path last seen (for the recent list).
    seen_path: Option<PathBuf>,
}

/// Reads the recent-files list at the start.
fn load_recent(dirs: Res<EditorDirs>, mut ui: ResMut<FileUi>) {
    ui.recent = read_recent(&dirs);
}

pub struct FilesPlugin;

impl Plugin for FilesPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<FileUi>()
            .add_systems(Startup, load_recent)
            .add_systems(
                Update,
                (
                    shortcuts.run_if(not(egui_wants_any_keyboard_input)),
                    close_requested,
                    watch_outcomes,
                    continue_after_save,
                ),
            );
    }
}

/// Whether no file dialog (the unsaved-changes question, recovery) and no
/// file browser is on screen: the editor's keys (framing, structure) wait
/// while one is, as the file shortcuts do.
pub fn no_file_dialog(ui: Option<Res<FileUi>>) -> bool {
    ui.is_none_or(|u| u.dialog.is_none() && !u.browsing)
}

/// Starts `p`, or asks about unsaved changes first.
pub fn request(
    p: Pending,
    model: &Model,
    ui: &mut FileUi,
    edits: &mut MessageWriter<EditMessage>,
    exit: &mut MessageWriter<AppExit>,
) {
    if model.unsaved {
        ui.dialog = Some(Dialog::Unsaved(p));
    } else {
        run_pending(p, ui, edits, exit);
    }
}

pub(super) fn run_pending(
    p: Pending,
    ui: &mut FileUi,
    edits: &mut MessageWriter<EditMessage>,
    exit: &mut MessageWriter<AppExit>,
) {
    match p {
        Pending::New(name) => match builtin::scene(&name) {
            Ok(s) => {
                edits.write(EditMessage::from(Edit::Replace(Box::new(s))));
            }
            Err(e) => ui.errors.push(e.to_string()),
        },
        Pending::NewDesign(e) => {
            edits.write(EditMessage::from(Edit::Author(*e)));
        }
        Pending::Open(path) => {
            edits.write(EditMessage::from(Edit::Load(path)));
        }
        Pending::Quit => {
            exit.write(AppExit::Success);
        }
    }
}

/// Saves to the scene's file, or asks for one (named after `name`).
pub fn save(model: &Model, name: &str, ui: &mut FileUi, edits: &mut MessageWriter<EditMessage>) {
    match &model.path {
        Some(p) => {
            edits.write(EditMessage::from(Edit::Save(p.clone())));
        }
        None => browse(ui, PathAction::SaveAs, suggested(model, name, "ron"), None),
    }
}

/// Asks the file browser for a file to `action`, starting at `start`.
pub fn browse(
    ui: &mut FileUi,
    action: PathAction,
    start: impl Into<PathBuf>,
    then: Option<Pending>,
) {
    ui.browse = Some(Browse {
        action,
        start: start.into(),
        then,
    });
}

/// Saves to `path` (a file picked in the browser), then goes on with `then`.
pub fn save_as(
    path: PathBuf,
    then: Option<Pending>,
    ui: &mut FileUi,
    edits: &mut MessageWriter<EditMessage>,
) {
    edits.write(EditMessage::from(Edit::Save(path)));
    ui.after_save = then;
}

/// A path for a new file: next to the scene, named after it (`name`).
pub fn suggested(model: &Model, name: &str, ext: &str) -> String {
    suggested_path(model, name, ext).display().to_string()
}

/// [`suggested`] as a path.
pub fn suggested_path(model: &Model, name: &str, ext: &str) -> PathBuf {
    let dir = model
        .path
        .as_ref()
        .and_then(|p| p.parent())
        .map(Path::to_path_buf)
        .or_else(|| std::env::current_dir().ok())
        .unwrap_or_default();
    let stem: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    dir.join(format!("{stem}.{ext}"))
}

/// Where a file to open is looked for first: the scene's folder, else the
/// working folder.
pub fn scene_folder(model: &Model) -> PathBuf {
    model
        .path
        .as_ref()
        .and_then(|p| p.parent())
        .filter(|p| !p.as_os_str().is_empty())
        .map(Path::to_path_buf)
        .or_else(|| std::env::current_dir().ok())
        .unwrap_or_default()
}

fn shortcuts(
    meter: Res<crate::ecs::meter::CpuMeter>,
    keys: Res<ButtonInput<KeyCode>>,
    model: Res<Model>,
    patch: PatchRef,
    mut ui: ResMut<FileUi>,
    mut edits: MessageWriter<EditMessage>,
    mut exit: MessageWriter<AppExit>,
) {
    let _meter = meter.start();
    // a modifier pressed and let go within one frame (a fast tap, or a
    // synthetic key event) still counts
    let held = |k: [KeyCode; 2]| keys.any_pressed(k) || keys.any_just_pressed(k);
    let ctrl = held([KeyCode::ControlLeft, KeyCode::ControlRight]);
    let shift = held([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
    if !ctrl || ui.dialog.is_some() || ui.browsing {
        return;
    }
    if keys.just_pressed(KeyCode::KeyZ) {
        edits.write(EditMessage::from(if shift {
            Edit::Redo
        } else {
            Edit::Undo
        }));
    } else if keys.just_pressed(KeyCode::KeyY) {
        edits.write(EditMessage::from(Edit::Redo));
    } else if keys.just_pressed(KeyCode::KeyS) {
        if shift {
            browse(
                &mut ui,
                PathAction::SaveAs,
                suggested_path(&model, patch.name(), "ron"),
                None,
            );
        } else {
            save(&model, patch.name(), &mut ui, &mut edits);
        }
    } else if keys.just_pressed(KeyCode::KeyO) {
        browse(&mut ui, PathAction::Open, scene_folder(&model), None);
    } else if keys.just_pressed(KeyCode::KeyQ) {
        request(Pending::Quit, &model, &mut ui, &mut edits, &mut exit);
    }
}

fn close_requested(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut closes: MessageReader<WindowCloseRequested>,
    model: Res<Model>,
    mut ui: ResMut<FileUi>,
    mut edits: MessageWriter<EditMessage>,
    mut exit: MessageWriter<AppExit>,
) {
    let _meter = meter.start();
    if closes.read().count() > 0 {
        request(Pending::Quit, &model, &mut ui, &mut edits, &mut exit);
    }
}

/// Errors of the last edits go to the error dialog; opened and saved files to
/// the recent list.
fn watch_outcomes(
    meter: Res<crate::ecs::meter::CpuMeter>,
    log: Res<EditLog>,
    model: Res<Model>,
    dirs: Res<EditorDirs>,
    mut ui: ResMut<FileUi>,
) {
    let _meter = meter.start();
    if log.frame != ui.log_frame {
        ui.log_frame = log.frame;
        for e in log.entries.iter().filter_map(|e| e.as_ref().err()) {
            ui.errors.push(e.to_string());
            ui.after_save = None; // a failed save stops what waited on it
        }
        if ui.errors.len() > 5 {
            let n = ui.errors.len() - 5;
            ui.errors.drain(..n);
        }
    }
    if model.path != ui.seen_path {
        ui.seen_path = model.path.clone();
        if let Some(p) = &model.path {
            let p = std::path::absolute(p).unwrap_or(p.clone());
            ui.recent.retain(|q| q != &p);
            ui.recent.insert(0, p);
            ui.recent.truncate(RECENT_MAX);
            save_recent(&dirs, &ui.recent);
        }
    }
}

fn continue_after_save(
    meter: Res<crate::ecs::meter::CpuMeter>,
    model: Res<Model>,
    mut ui: ResMut<FileUi>,
    mut edits: MessageWriter<EditMessage>,
    mut exit: MessageWriter<AppExit>,
) {
    let _meter = meter.start();
    if !model.unsaved
        && let Some(p) = ui.after_save.take()
    {
        run_pending(p, &mut ui, &mut edits, &mut exit);
    }
}
