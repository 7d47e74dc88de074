//! Files: new, open, save, save as, export OBJ/STL, recent files, the
//! unsaved-changes prompt (before new, open and quit), and a dialog for edits
//! that failed (a failed open keeps the current scene: the model refuses it).
//! Files are picked in the editor's own file browser (`file_browser.rs`: no
//! native file dialog, which would need GTK or a desktop portal on Linux);
//! this file asks it for one with [`browse`].

use crate::ecs::patch::PatchRef;
use crate::ecs::{Edit, EditLog, EditMessage, Model};
use crate::scene::builtin;
use crate::scene::export::Format;
use bevy::prelude::*;
use bevy::window::WindowCloseRequested;
use bevy_egui::input::egui_wants_any_keyboard_input;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use std::path::{Path, PathBuf};

/// Where the editor keeps its own files: `recent.json` and the recovery file.
#[derive(Resource, Debug, Clone)]
pub struct EditorDirs {
    /// The folder.
    pub home: PathBuf,
}

impl EditorDirs {
    /// `$STREAMLINE_STUDIO_HOME`, else `$XDG_STATE_HOME/streamline-studio`,
    /// else `~/.local/state/streamline-studio`, else a folder in the temp dir.
    pub fn from_env() -> Self {
        let env = |k: &str| {
            std::env::var_os(k)
                .filter(|v| !v.is_empty())
                .map(PathBuf::from)
        };
        let home = env("STREAMLINE_STUDIO_HOME")
            .or_else(|| env("XDG_STATE_HOME").map(|p| p.join("streamline-studio")))
            .or_else(|| env("HOME").map(|p| p.join(".local/state/streamline-studio")))
            .unwrap_or_else(|| std::env::temp_dir().join("streamline-studio"));
        EditorDirs { home }
    }

    /// The recent-files list.
    pub fn recent_file(&self) -> PathBuf {
        self.home.join("recent.json")
    }

    /// The recovery scene written by autosave.
    pub fn recovery_file(&self) -> PathBuf {
        self.home.join("recovery.ron")
    }

    /// Where the recovery scene came from (its path, if it had one).
    pub fn recovery_meta(&self) -> PathBuf {
        self.home.join("recovery.json")
    }
}

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

/// What a file is picked for (in the file browser, `file_browser.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathAction {
    /// Open a scene.
    Open,
    /// Save the scene under a new name.
    SaveAs,
    /// Export the surface (`Edit::Export`; the extension picks the format).
    Export(Format),
    /// Play a script's edits into the scene.
    RunScript,
    /// Open a triangle mesh in the Loop mesh panel.
    OpenMesh,
    /// Write the Loop mesh panel's surface (OBJ).
    ExportMeshSurface,
    /// Write the Loop mesh panel's control mesh (OBJ).
    ExportMeshControl,
    /// Write the Loop mesh panel's control mesh as USD.
    ExportMeshUsd,
    /// Fit a design to a face of a STEP or IGES file or an OBJ grid of
    /// points (File ▸ Import surface…).
    ImportSurface,
    /// Attach a reference to the design without fitting (File ▸
    /// Reference…, `reference.rs`).
    AttachReference,
}

impl PathAction {
    /// The browser's title.
    pub fn title(self) -> String {
        match self {
            PathAction::Open => "Open scene".into(),
            PathAction::SaveAs => "Save scene as".into(),
            PathAction::Export(f) => format!("Export {}", f.name()),
            PathAction::RunScript => "Run script".into(),
            PathAction::OpenMesh => "Open a triangle mesh (Loop mesh)".into(),
            PathAction::ExportMeshSurface => "Export the Loop surface (OBJ)".into(),
            PathAction::ExportMeshControl => "Export the Loop control mesh (OBJ)".into(),
            PathAction::ExportMeshUsd => "Export the Loop control mesh (USD)".into(),
            PathAction::ImportSurface => "Import a surface (STEP, IGES or a grid of points)".into(),
            PathAction::AttachReference => {
                "Reference (STEP, IGES or a grid of points), to compare the design with".into()
            }
        }
    }

    /// The file filter's name and the extensions it shows (the first one is
    /// what a save adds).
    pub fn filter(self) -> (&'static str, &'static [&'static str]) {
        match self {
            PathAction::Open | PathAction::SaveAs | PathAction::RunScript => {
                ("RON files (.ron)", &["ron"])
            }
            PathAction::Export(Format::Obj)
            | PathAction::OpenMesh
            | PathAction::ExportMeshSurface
            | PathAction::ExportMeshControl => ("OBJ meshes (.obj)", &["obj"]),
            PathAction::Export(Format::Stl) => ("STL meshes (.stl)", &["stl"]),
            PathAction::Export(Format::Glb) => ("binary glTF (.glb)", &["glb"]),
            PathAction::Export(Format::Step) => ("STEP (.step, .stp)", &["step", "stp"]),
            PathAction::Export(Format::Iges) => ("IGES (.igs, .iges)", &["igs", "iges"]),
            PathAction::ExportMeshUsd => ("USD text (.usda)", &["usda"]),
            PathAction::ImportSurface => (
                "Surfaces (.step, .stp, .p21, .igs, .iges, .obj)",
                &["step", "stp", "p21", "igs", "iges", "obj"],
            ),
            PathAction::AttachReference => (
                "Surfaces and meshes (.step, .stp, .p21, .igs, .iges, .obj, .stl)",
                &["step", "stp", "p21", "igs", "iges", "obj", "stl"],
            ),
        }
    }

    /// Whether it picks an existing file (else it names one to write).
    pub fn opens(self) -> bool {
        matches!(
            self,
            PathAction::Open
                | PathAction::RunScript
                | PathAction::OpenMesh
                | PathAction::ImportSurface
                | PathAction::AttachReference
        )
    }
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
    after_save: Option<Pending>,
    /// The user chose to discard changes on quit (no recovery file then).
    pub discarded: bool,
    /// The last edit-log frame looked at.
    log_frame: u64,
    /// The model path last seen (for the recent list).
    seen_path: Option<PathBuf>,
}

/// The most recent files kept.
pub const RECENT_MAX: usize = 8;

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
            )
            .add_systems(EguiPrimaryContextPass, dialogs);
    }
}

fn load_recent(dirs: Res<EditorDirs>, mut ui: ResMut<FileUi>) {
    ui.recent = std::fs::read_to_string(dirs.recent_file())
        .ok()
        .and_then(|t| serde_json::from_str::<Vec<PathBuf>>(&t).ok())
        .unwrap_or_default();
    ui.recent.truncate(RECENT_MAX);
}

fn save_recent(dirs: &EditorDirs, recent: &[PathBuf]) {
    let _ = std::fs::create_dir_all(&dirs.home);
    if let Ok(text) = serde_json::to_string_pretty(recent) {
        // a lost recent list is no loss of work; still written atomically
        let _ = crate::scene::io::write_atomic(&dirs.recent_file(), text.as_bytes(), |_| Ok(()));
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

fn run_pending(
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
pub fn recover(
    dirs: &EditorDirs,
    origin: Option<PathBuf>,
    edits: &mut MessageWriter<EditMessage>,
    ui: &mut FileUi,
) {
    match crate::scene::document_io::load(&dirs.recovery_file()) {
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
