//! File: new (a new design, or a built-in scene), open, import a surface,
//! save, save as, export, recent files; the design's reference (attach,
//! detach, View ▸ Reference's ghost and why it cannot be drawn).

use super::PanelCtx;
use crate::ecs::runner::ScriptRun;
use crate::editor::files::new_design::NewDesignForm;
use crate::editor::files::open_save::{self, FileUi, PathAction, Pending};
use crate::editor::surface::reference_ghost::ReferenceGhost;
use crate::scene::design::builtin;
use crate::scene::export::format::Format;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;
use std::path::PathBuf;

/// What only the File section touches.
#[derive(SystemParam)]
pub struct FileSection<'w> {
    pub files: ResMut<'w, FileUi>,
    pub exit: MessageWriter<'w, AppExit>,
    pub script: ResMut<'w, ScriptRun>,
    pub new_design: ResMut<'w, NewDesignForm>,
    /// The reference's ghost (absent in an editor without it).
    pub ghost: Option<ResMut<'w, ReferenceGhost>>,
}

pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx, s: &mut FileSection) {
    let path = p
        .model
        .path
        .as_ref()
        .map(|x| x.display().to_string())
        .unwrap_or_else(|| "(built-in, not saved yet)".into());
    ui.label(egui::RichText::new(path).weak().small())
        .on_hover_text("The file the scene was opened from or saved to");
    ui.horizontal_wrapped(|ui| {
        ui.menu_button("New…", |ui| {
            if ui
                .button("New design…")
                .on_hover_text(
                    "A design from nothing: rows × columns, a Flat or Cylinder template, \
                     the streamline length and the scheme",
                )
                .clicked()
            {
                s.new_design.open = true;
                ui.close();
            }
            if ui
                .button("Import surface…")
                .on_hover_text(
                    "A design fitted to a face of a STEP or IGES file, or to an OBJ grid of points",
                )
                .clicked()
            {
                let folder = open_save::scene_folder(&p.model);
                open_save::browse(&mut s.files, PathAction::ImportSurface, folder, None);
                ui.close();
            }
            ui.separator();
            ui.label(egui::RichText::new("Built-in scenes").weak().small());
            for (name, _) in builtin::SCENES {
                if ui
                    .button(name)
                    .on_hover_text(format!("Start from the built-in scene {name}"))
                    .clicked()
                {
                    let (model, ui_state) = (&p.model, &mut *s.files);
                    open_save::request(
                        Pending::New(name.into()),
                        model,
                        ui_state,
                        &mut p.edits,
                        &mut s.exit,
                    );
                    ui.close();
                }
            }
        })
        .response
        .on_hover_text("Start a new design, or from a built-in scene");
        if ui
            .button("Open…")
            .on_hover_text("Open a scene file (.ron), Ctrl+O")
            .clicked()
        {
            let folder = open_save::scene_folder(&p.model);
            open_save::browse(&mut s.files, PathAction::Open, folder, None);
        }
        if ui
            .button("Save")
            .on_hover_text("Save to the scene's file (Ctrl+S); atomic and verified")
            .clicked()
        {
            open_save::save(&p.model, p.patch.name(), &mut s.files, &mut p.edits);
        }
        if ui
            .button("Save as…")
            .on_hover_text("Save under a new name (Ctrl+Shift+S)")
            .clicked()
        {
            let start = open_save::suggested_path(&p.model, p.patch.name(), "ron");
            open_save::browse(&mut s.files, PathAction::SaveAs, start, None);
        }
    });
    ui.horizontal(|ui| {
        for (label, format, ext, tip) in [
            (
                "Export OBJ…",
                Format::Obj,
                "obj",
                "Write the surface mesh as Wavefront OBJ (positions, normals, faces)",
            ),
            (
                "Export STL…",
                Format::Stl,
                "stl",
                "Write the surface mesh as binary STL",
            ),
        ] {
            if ui.button(label).on_hover_text(tip).clicked() {
                let start = open_save::suggested_path(&p.model, p.patch.name(), ext);
                open_save::browse(&mut s.files, PathAction::Export(format), start, None);
            }
        }
    });
    if !s.files.recent.is_empty() {
        ui.label("Recent:");
        for r in s.files.recent.clone() {
            let name = r
                .file_name()
                .map(|n| n.to_string_lossy().to_string())
                .unwrap_or_default();
            if ui
                .selectable_label(p.model.path.as_ref() == Some(&r), name)
                .on_hover_text(format!("Open {}", r.display()))
                .clicked()
            {
                let (model, ui_state) = (&p.model, &mut *s.files);
                open_save::request(Pending::Open(r), model, ui_state, &mut p.edits, &mut s.exit);
            }
        }
    }
    reference(ui, p, s);
    ui.separator();
    let folder = open_save::scene_folder(&p.model);
    script(ui, &mut s.script, &mut s.files, folder);
}

/// The design's reference: its file and face, Reference… and Detach, the
/// ghost's switch and why it cannot be drawn.
fn reference(ui: &mut egui::Ui, p: &mut PanelCtx, s: &mut FileSection) {
    let link = p.patch.reference().cloned();
    ui.horizontal_wrapped(|ui| {
        match &link {
            Some(l) => {
                let name = l.path.file_name().map_or_else(
                    || l.path.display().to_string(),
                    |n| n.to_string_lossy().into(),
                );
                ui.label(format!("Reference: {name}, face {}", l.face))
                    .on_hover_text(l.path.display().to_string());
            }
            None => {
                ui.label(egui::RichText::new("No reference").weak());
            }
        }
        if ui
            .button("Reference…")
            .on_hover_text("Attach a face of a STEP or IGES file or an OBJ grid, without fitting")
            .clicked()
        {
            let folder = open_save::scene_folder(&p.model);
            open_save::browse(&mut s.files, PathAction::AttachReference, folder, None);
        }
        if link.is_some()
            && ui
                .button("Detach")
                .on_hover_text("The design keeps no reference (one undo step)")
                .clicked()
        {
            p.send(crate::ecs::Edit::SetReference(None));
        }
    });
    if let Some(g) = &mut s.ghost {
        ghost_switch(ui, g, link.is_some());
    }
}

/// View ▸ Reference: the ghost's switch, and why the face cannot be drawn.
pub(super) fn ghost_switch(ui: &mut egui::Ui, ghost: &mut ReferenceGhost, has_reference: bool) {
    let mut shown = ghost.shown;
    ui.add_enabled(has_reference, egui::Checkbox::new(&mut shown, "Reference"))
        .on_hover_text("Draw the reference as a translucent ghost over the design")
        .on_disabled_hover_text(
            "The design has no reference: Reference… in the File menu attaches one",
        );
    if shown != ghost.shown {
        ghost.shown = shown;
    }
    if let Some(e) = &ghost.error {
        ui.colored_label(egui::Color32::LIGHT_RED, e);
    }
}

/// Run script: a script's edits played into the open scene, off the frame's
/// budget (a batch of steps a frame), with progress and Cancel.
fn script(ui: &mut egui::Ui, run: &mut ResMut<ScriptRun>, files_ui: &mut FileUi, folder: PathBuf) {
    use crate::ecs::runner::RunState;
    let busy = run.busy();
    ui.horizontal(|ui| {
        // typed on a copy: the run is marked changed only when the text is
        let mut input = run.input.clone();
        ui.add_enabled(
            !busy,
            egui::TextEdit::singleline(&mut input)
                .hint_text("script.ron")
                .desired_width(150.0),
        )
        .on_hover_text("A script file (RON steps, see tests/scripts); its paths are relative to it");
        if input != run.input {
            run.input = input;
        }
        if ui
            .add_enabled(!busy, egui::Button::new("Run script"))
            .on_hover_text("Play the script's edits into this scene (one undo step each); expectations are skipped")
            .clicked()
        {
            let path = PathBuf::from(run.input.trim());
            run.start(path);
        }
        if ui
            .add_enabled(!busy, egui::Button::new("…"))
            .on_hover_text("Pick the script in the file browser and run it")
            .clicked()
        {
            open_save::browse(files_ui, PathAction::RunScript, folder, None);
        }
    });
    let mut cancel = false;
    match &run.state {
        RunState::Idle => {}
        RunState::Parsing(path, _) => {
            ui.add(
                egui::ProgressBar::new(0.0)
                    .animate(true)
                    .text(format!("reading {}", path.display())),
            )
            .on_hover_text("The file is read and parsed off the frame");
            cancel = ui
                .button("Cancel")
                .on_hover_text("Stop; nothing is run")
                .clicked();
            ui.ctx().request_repaint();
        }
        RunState::Running { .. } => {
            let (done, all) = run.progress().unwrap_or((0, 1));
            ui.add(
                egui::ProgressBar::new(done as f32 / all.max(1) as f32)
                    .text(format!("step {done} of {all}")),
            )
            .on_hover_text("Steps go out a batch a frame, sized to keep the frame light");
            cancel = ui
                .button("Cancel")
                .on_hover_text("Stop after the steps already sent; undo takes them back")
                .clicked();
            ui.ctx().request_repaint();
        }
        RunState::Done(line) => {
            ui.label(egui::RichText::new(line).small())
                .on_hover_text("How the last script run ended");
        }
    }
    if cancel {
        run.cancel();
    }
}
