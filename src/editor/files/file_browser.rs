//! The file browser: one `egui_file_dialog::FileDialog` for every file the
//! editor opens or writes (Open, Save as, every export, Run script, the Loop
//! mesh's Open and exports). It shows folders, the places of the recent
//! files, the home folders and drives, filters by extension for what the file
//! is for, and still takes a typed path: a full path in the name field of a
//! save, or in the path field (the pen button, or `/`) of an open.
//!
//! A feature asks for a file with [`open_save::browse`]; this plugin opens the
//! browser and hands the file picked to the feature: a scene to the model
//! (after the unsaved-changes question; a failed open keeps the current
//! scene), a script to the script runner, a mesh to the Loop mesh view, a
//! STEP, IGES or OBJ surface to the Import surface dialog.

use super::super::loop_mesh::MeshView;
use super::import::ImportForm;
use super::open_save::{self, Browse, FileUi, PathAction, Pending};
use crate::ecs::runner::ScriptRun;
use crate::ecs::{Edit, EditMessage, Model};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use egui_file_dialog::{FileDialog, FileDialogStorage, OpeningMode};
use std::path::{Path, PathBuf};

/// The browser on screen, and what it is for.
#[derive(Resource, Default)]
pub struct FileBrowser {
    /// The dialog, while it is open.
    dialog: Option<FileDialog>,
    /// What the file is for.
    request: Option<Browse>,
    /// What the dialog keeps between openings (pinned folders, hidden files).
    storage: Option<FileDialogStorage>,
}

pub struct FileBrowserPlugin;

impl Plugin for FileBrowserPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<FileBrowser>()
            .add_systems(EguiPrimaryContextPass, browse);
    }
}

/// The folders of the recent files, newest first, each once.
fn recent_places(recent: &[PathBuf]) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = Vec::new();
    for dir in recent.iter().filter_map(|p| p.parent()) {
        if dir.is_dir() && !out.iter().any(|d| d == dir) {
            out.push(dir.to_path_buf());
        }
    }
    out
}

/// The folder to show first and, for a save, the name to propose.
fn start_of(start: &Path) -> (PathBuf, Option<String>) {
    if start.is_dir() {
        return (start.to_path_buf(), None);
    }
    let folder = start
        .parent()
        .filter(|p| !p.as_os_str().is_empty() && p.is_dir())
        .map(Path::to_path_buf)
        .or_else(|| std::env::current_dir().ok())
        .unwrap_or_default();
    let name = start.file_name().map(|n| n.to_string_lossy().into_owned());
    (folder, name)
}

/// A browser set up for `req`.
fn dialog_for(req: &Browse, recent: &[PathBuf], storage: Option<FileDialogStorage>) -> FileDialog {
    let (folder, name) = start_of(&req.start);
    let (filter, extensions) = req.action.filter();
    let places = recent_places(recent);
    let mut d = FileDialog::new()
        .id("file_browser")
        .title(&req.action.title())
        .initial_directory(folder)
        .default_size([640.0, 380.0])
        .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
        .add_file_filter_extensions(filter, extensions.to_vec())
        .default_file_filter(filter)
        .add_save_extension(filter, extensions[0])
        .default_save_extension(filter);
    if !places.is_empty() {
        d = d.add_quick_access("Recent places", |q| {
            for dir in &places {
                let label = dir.file_name().map_or_else(
                    || dir.display().to_string(),
                    |n| n.to_string_lossy().into_owned(),
                );
                q.add_path(&format!("🕓  {label}"), dir.clone());
            }
        });
    }
    if let Some(s) = storage {
        d = d.storage(s);
    }
    if let Some(n) = name {
        d = d.default_file_name(&n);
    }
    // always where the request says (the scene's folder), not the last one
    d.config_mut().opening_mode = OpeningMode::AlwaysInitialDir;
    // a folder is listed in the frame it is opened: the editor draws only
    // when something happens, and a listing finished on another thread
    // would wait for the next input to be shown
    d.config_mut().load_via_thread = false;
    if req.action.opens() {
        d.pick_file();
    } else {
        d.save_file();
    }
    d
}

/// What a picked file goes to.
#[derive(SystemParam)]
struct Receivers<'w> {
    model: Res<'w, Model>,
    files_ui: ResMut<'w, FileUi>,
    edits: MessageWriter<'w, EditMessage>,
    exit: MessageWriter<'w, AppExit>,
    script: ResMut<'w, ScriptRun>,
    mesh: ResMut<'w, MeshView>,
    import: ResMut<'w, ImportForm>,
    reference: ResMut<'w, super::reference::ReferenceForm>,
}

impl Receivers<'_> {
    /// Hands `path` to what it was picked for.
    fn deliver(&mut self, req: Browse, path: PathBuf) {
        let (model, ui, edits) = (&self.model, &mut *self.files_ui, &mut self.edits);
        match req.action {
            PathAction::Open => {
                open_save::request(Pending::Open(path), model, ui, edits, &mut self.exit)
            }
            PathAction::SaveAs => open_save::save_as(path, req.then, ui, edits),
            PathAction::Export(_) => {
                edits.write(EditMessage::from(Edit::Export(path)));
            }
            PathAction::RunScript => {
                self.script.input = path.display().to_string();
                self.script.start(path);
            }
            PathAction::OpenMesh => {
                self.mesh.text.input = path.display().to_string();
                self.mesh.open(path);
            }
            PathAction::ExportMeshSurface => self.mesh.export(path, false),
            PathAction::ExportMeshControl => self.mesh.export(path, true),
            PathAction::ExportMeshUsd => self.mesh.export_usd(path),
            PathAction::ImportSurface => self.import.read(path),
            PathAction::AttachReference => self.reference.read(path),
        }
    }
}

fn browse(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    mut browser: ResMut<FileBrowser>,
    mut to: Receivers,
) -> Result {
    let _meter = meter.start();
    if let Some(req) = to.files_ui.browse.take() {
        let storage = browser
            .dialog
            .take()
            .map(|mut d| d.storage_mut().clone())
            .or_else(|| browser.storage.take());
        let d = dialog_for(&req, &to.files_ui.recent, storage);
        browser.dialog = Some(d);
        browser.request = Some(req);
    }
    let open = browser.dialog.is_some();
    if to.files_ui.browsing != open {
        to.files_ui.browsing = open;
    }
    let Some(d) = browser.dialog.as_mut() else {
        return Ok(());
    };
    let ctx = contexts.ctx_mut()?.clone();
    d.update(&ctx);
    let picked = d.take_picked();
    let closed = *d.state() != egui_file_dialog::DialogState::Open;
    if !closed && picked.is_none() {
        return Ok(());
    }
    browser.storage = browser.dialog.take().map(|mut d| d.storage_mut().clone());
    to.files_ui.browsing = false;
    if let (Some(path), Some(req)) = (picked, browser.request.take()) {
        to.deliver(req, path);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_save_starts_in_the_files_folder_with_its_name() {
        let dir = std::env::temp_dir();
        let (folder, name) = start_of(&dir.join("car.obj"));
        assert_eq!(folder, dir);
        assert_eq!(name.as_deref(), Some("car.obj"));
        let (folder, name) = start_of(&dir);
        assert_eq!((folder, name), (dir, None));
    }

    #[test]
    fn recent_places_are_the_folders_of_the_recent_files_once() {
        let dir = std::env::temp_dir();
        let places = recent_places(&[
            dir.join("a.ron"),
            dir.join("b.ron"),
            PathBuf::from("/no/such/folder/c.ron"),
        ]);
        assert_eq!(places, vec![dir]);
    }
}
