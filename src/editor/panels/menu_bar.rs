//! The menu bar: File, Edit, View and Help, each entry with its shortcut
//! beside it. An entry does what the panel's button for it does (the same
//! calls: `open_save::request`, `open_save::save`, `open_save::browse`, `Edit::Undo`, a
//! frame request…); the keys stay where they are handled (`files.rs`,
//! `camera.rs`, `structure.rs`), and [`KEYS`] lists them all for Help ▸ Keys.

use super::{PanelCtx, Sections};
use crate::ecs::Edit;
use crate::editor::files::open_save::{self, PathAction, Pending};
use crate::editor::handles::structure::{self, StructureAction};
use crate::editor::surface::analysis_display::SurfaceMode;
use crate::scene::design::builtin;
use crate::scene::export::format::Format;
use bevy::prelude::*;
use bevy_egui::egui;

/// The Help windows on screen.
#[derive(Resource, Debug, Default)]
pub struct HelpWindows {
    /// Help ▸ Keys.
    pub keys: bool,
    /// Help ▸ About.
    pub about: bool,
}

/// Every key and mouse binding of the editor, in groups, for Help ▸ Keys.
pub const KEYS: &[(&str, &[(&str, &str)])] = &[
    (
        "Files",
        &[
            ("Ctrl+O", "Open a scene (file browser)"),
            ("Ctrl+S", "Save (asks for a name the first time)"),
            ("Ctrl+Shift+S", "Save as… (file browser)"),
            ("Ctrl+Q", "Quit (asks about unsaved changes)"),
        ],
    ),
    (
        "Editing",
        &[
            ("Ctrl+Z", "Undo"),
            ("Ctrl+Shift+Z, Ctrl+Y", "Redo"),
            ("Esc", "Cancel a drag (the arrow goes back); close a menu"),
            ("R / Shift+R", "Insert a row after / before the selection"),
            ("C / Shift+C", "Insert a column after / before it"),
            ("Delete / Shift+Delete", "Delete its row / column"),
        ],
    ),
    (
        "View",
        &[("A, Home", "Frame all"), ("F", "Frame the selection")],
    ),
    (
        "Mouse in the 3D view",
        &[
            ("Left click", "Select an arrow"),
            (
                "Left drag on an arrow",
                "Turn it on a trackball (one undo step)",
            ),
            (
                "Left drag on the sphere inset",
                "Turn a tangent on the Gaussian sphere",
            ),
            ("Left drag on a cyan arrow", "Turn an initial-curve tangent"),
            (
                "Shift+click, Shift+drag",
                "Select several (a box); a drag turns all",
            ),
            (
                "Right click on an arrow",
                "Insert or delete rows and columns there",
            ),
            ("Right drag, middle drag", "Orbit, pan"),
            ("Wheel", "Zoom"),
        ],
    ),
    (
        "File browser",
        &[
            ("/", "Type a path (a folder, or a file to pick)"),
            ("Enter", "Open the folder or pick the file"),
            ("Up / Down", "Select the entry above / below"),
            ("Alt+Up", "The parent folder"),
            ("Backspace, Alt+Left", "Back"),
            ("Ctrl+N, F5", "New folder; read the folder again"),
            ("Esc", "Close without picking"),
        ],
    ),
];

const OPEN: &str = "Ctrl+O";
const SAVE: &str = "Ctrl+S";
const SAVE_AS: &str = "Ctrl+Shift+S";
const QUIT: &str = "Ctrl+Q";
const UNDO: &str = "Ctrl+Z";
const REDO: &str = "Ctrl+Shift+Z";
const FRAME_ALL: &str = "A";
const FRAME_SELECTION: &str = "F";

/// A menu entry with its shortcut beside it.
fn entry(ui: &mut egui::Ui, label: &str, shortcut: &str, enabled: bool) -> bool {
    ui.add_enabled(enabled, egui::Button::new(label).shortcut_text(shortcut))
        .clicked()
}

/// The menu bar, at the top of the window.
pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx, s: &mut Sections) {
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| file_menu(ui, p, s));
        ui.menu_button("Edit", |ui| edit_menu(ui, p, s));
        ui.menu_button("View", |ui| view_menu(ui, p, s));
        ui.menu_button("Help", |ui| {
            if entry(ui, "Keys…", "", true) {
                s.help.keys = true;
            }
            if entry(ui, "About Streamline Studio…", "", true) {
                s.help.about = true;
            }
        });
    });
    help_windows(ui.ctx(), &mut s.help);
}

fn file_menu(ui: &mut egui::Ui, p: &mut PanelCtx, s: &mut Sections) {
    let f = &mut s.file;
    if entry(ui, "New design…", "", true) {
        f.new_design.open = true;
    }
    ui.menu_button("New from a built-in scene", |ui| {
        for (name, _) in builtin::SCENES {
            if ui.button(name).clicked() {
                let pending = Pending::New(name.into());
                open_save::request(pending, &p.model, &mut f.files, &mut p.edits, &mut f.exit);
            }
        }
    });
    ui.separator();
    if entry(ui, "Open…", OPEN, true) {
        let folder = open_save::scene_folder(&p.model);
        open_save::browse(&mut f.files, PathAction::Open, folder, None);
    }
    let recent = f.files.recent.clone();
    ui.add_enabled_ui(!recent.is_empty(), |ui| {
        ui.menu_button("Open recent", |ui| {
            for r in recent {
                if ui
                    .button(r.display().to_string())
                    .on_hover_text("Open this file")
                    .clicked()
                {
                    let pending = Pending::Open(r);
                    open_save::request(pending, &p.model, &mut f.files, &mut p.edits, &mut f.exit);
                }
            }
        });
    });
    ui.separator();
    if entry(ui, "Save", SAVE, true) {
        open_save::save(&p.model, p.patch.name(), &mut f.files, &mut p.edits);
    }
    if entry(ui, "Save as…", SAVE_AS, true) {
        let start = open_save::suggested_path(&p.model, p.patch.name(), "ron");
        open_save::browse(&mut f.files, PathAction::SaveAs, start, None);
    }
    ui.menu_button("Export", |ui| {
        for (format, ext, what) in [
            (Format::Obj, "obj", "OBJ mesh…"),
            (Format::Stl, "stl", "STL mesh…"),
            (Format::Glb, "glb", "glTF mesh (.glb)…"),
            (Format::Step, "step", "STEP B-spline surface…"),
            (Format::Iges, "igs", "IGES B-spline surface…"),
        ] {
            if entry(ui, what, "", true) {
                let start = open_save::suggested_path(&p.model, p.patch.name(), ext);
                open_save::browse(&mut f.files, PathAction::Export(format), start, None);
            }
        }
    });
    ui.separator();
    if entry(ui, "Run script…", "", !f.script.busy()) {
        let folder = open_save::scene_folder(&p.model);
        open_save::browse(&mut f.files, PathAction::RunScript, folder, None);
    }
    if entry(ui, "Open mesh (Loop)…", "", true) {
        let folder = std::env::current_dir().unwrap_or_default();
        open_save::browse(&mut f.files, PathAction::OpenMesh, folder, None);
    }
    if entry(ui, "Import surface…", "", true) {
        let folder = open_save::scene_folder(&p.model);
        open_save::browse(&mut f.files, PathAction::ImportSurface, folder, None);
    }
    if entry(ui, "Reference…", "", true) {
        let folder = open_save::scene_folder(&p.model);
        open_save::browse(&mut f.files, PathAction::AttachReference, folder, None);
    }
    if entry(ui, "Detach reference", "", p.patch.reference().is_some()) {
        p.send(Edit::SetReference(None));
    }
    ui.separator();
    if entry(ui, "Quit", QUIT, true) {
        open_save::request(
            Pending::Quit,
            &p.model,
            &mut f.files,
            &mut p.edits,
            &mut f.exit,
        );
    }
}

fn edit_menu(ui: &mut egui::Ui, p: &mut PanelCtx, s: &mut Sections) {
    if entry(ui, "Undo", UNDO, s.bar.history.undo_len() > 0) {
        p.send(Edit::Undo);
    }
    if entry(ui, "Redo", REDO, s.bar.history.redo_len() > 0) {
        p.send(Edit::Redo);
    }
    ui.separator();
    let (rows, cols) = {
        let net = p.patch.design().net();
        (net.rows(), net.cols())
    };
    let cell = p.selection.primary().and_then(structure::control_cell);
    for a in StructureAction::ALL {
        let refused = a.refused((rows, cols));
        let label = format!("{} (at the selected arrow)", a.label());
        let enabled = cell.is_some() && refused.is_none();
        let response = ui.add_enabled(enabled, egui::Button::new(label).shortcut_text(a.key()));
        let response = match (cell, refused) {
            (None, _) => response.on_disabled_hover_text("Select a control arrow first"),
            (_, Some(why)) => response.on_disabled_hover_text(why),
            _ => response,
        };
        if response.clicked()
            && let Some(cell) = cell
        {
            let (edit, next) = a.edit(cell, (rows, cols));
            p.send(Edit::Author(edit));
            p.select_cell(next);
        }
    }
}

fn view_menu(ui: &mut egui::Ui, p: &mut PanelCtx, s: &mut Sections) {
    let bar = &mut s.bar;
    if entry(ui, "Frame all", FRAME_ALL, true) {
        bar.frame.0 = Some(bar.bounds.all());
    }
    let sel = p.selected_arrow();
    if entry(ui, "Frame selection", FRAME_SELECTION, sel.is_some())
        && let Some(a) = sel
    {
        bar.frame.0 = Some(a.framing(bar.bounds.size()));
    }
    ui.separator();
    ui.label(egui::RichText::new("Surface").weak().small());
    let mut a = s.analysis.settings.clone();
    for (m, title) in [
        (SurfaceMode::Shaded, "Shaded"),
        (SurfaceMode::Gaussian, "Gaussian curvature"),
        (SurfaceMode::Mean, "Mean curvature"),
        (SurfaceMode::Zebra, "Zebra stripes"),
        (SurfaceMode::Deviation, "Deviation from the CAD fit"),
    ] {
        ui.radio_value(&mut a.mode, m, title);
    }
    super::analysis_section::reference_radio(ui, &mut a, s.analysis.reference.has_reference);
    ui.checkbox(&mut a.comb, "Curvature comb");
    s.analysis.settings.set_if_neq(a);
    ui.separator();
    let d = &mut s.display;
    let mut h = d.handles.clone();
    let mut o = d.overlay.clone();
    let mut sp = d.sphere.clone();
    ui.checkbox(&mut h.controls, "Control arrows");
    ui.checkbox(&mut h.labels, "Index labels");
    ui.checkbox(&mut o.streamlines, "Streamlines");
    ui.checkbox(&mut o.axes_and_grid, "Axes and ground grid");
    ui.checkbox(&mut sp.show, "Gaussian sphere view");
    if let Some(g) = &mut s.file.ghost {
        super::file::ghost_switch(ui, g, p.patch.reference().is_some());
    }
    d.handles.set_if_neq(h);
    d.overlay.set_if_neq(o);
    d.sphere.set_if_neq(sp);
}

/// Groups of bindings as a grid: the group's name, then key and what it does.
fn key_grid(ui: &mut egui::Ui, id: &str, groups: &[(&str, &[(&str, &str)])]) {
    egui::Grid::new(id)
        .num_columns(2)
        .spacing([14.0, 3.0])
        .striped(true)
        .show(ui, |ui| {
            for (group, rows) in groups {
                ui.label(egui::RichText::new(*group).strong().underline());
                ui.end_row();
                for (key, what) in *rows {
                    ui.label(egui::RichText::new(*key).strong());
                    ui.label(*what);
                    ui.end_row();
                }
            }
        });
}

fn help_windows(ctx: &egui::Context, help: &mut HelpWindows) {
    let mut keys = help.keys;
    egui::Window::new("Keys and mouse")
        .open(&mut keys)
        .collapsible(false)
        .resizable(false)
        .pivot(egui::Align2::CENTER_TOP)
        .default_pos([ctx.viewport_rect().center().x, 30.0])
        .show(ctx, |ui| {
            let tall = (ctx.viewport_rect().height() - 90.0).max(120.0);
            egui::ScrollArea::vertical()
                .max_height(tall)
                .show(ui, |ui| {
                    ui.horizontal_top(|ui| {
                        let (left, right) = KEYS.split_at(3);
                        key_grid(ui, "help_keys_left", left);
                        ui.add_space(12.0);
                        key_grid(ui, "help_keys_right", right);
                    });
                });
        });
    if keys != help.keys {
        help.keys = keys;
    }
    let mut about = help.about;
    egui::Window::new("About Streamline Studio")
        .open(&mut about)
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
        .show(ctx, |ui| {
            ui.heading(format!("Streamline Studio {}", env!("CARGO_PKG_VERSION")));
            ui.label(env!("CARGO_PKG_DESCRIPTION"));
            ui.label(
                "Streamline modeling after Miura, Wang and Cheng, CAD 33 (2001); fine tuning \
                 and Loop interpolation after papers 002 and 003 (see docs/).",
            );
            ui.label(egui::RichText::new(format!("License: {}", env!("CARGO_PKG_LICENSE"))).weak());
        });
    if about != help.about {
        help.about = about;
    }
}
