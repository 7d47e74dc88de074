//! File → CAD export (docs/math.md §10, docs/cad.md): the surface as one B-spline
//! face in STEP or IGES, or the mesh as binary glTF, with the fit's
//! tolerance and degree, and what the last fit reached. The export itself is
//! an `Edit::Export` like any other (atomic, verified; a refusal keeps the
//! old file and shows its message in the status line).

use super::PanelCtx;
use crate::ecs::Edit;
use crate::editor::files::open_save::{self, FileUi, PathAction};
use crate::scene::export::format::Format;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;
use streamline_kernel::nurbs::{FitOptions, Tolerance};

/// The section's own resources: the export settings it writes, the last
/// export's outcome it shows.
#[derive(SystemParam)]
pub struct CadExportSection<'w> {
    pub export: ResMut<'w, crate::ecs::exchange::ExportSettings>,
    pub last_export: Res<'w, crate::ecs::exchange::LastExport>,
}

/// The section's own fields, kept in egui's memory.
#[derive(Clone, Debug)]
struct Fields {
    format: Format,
    /// The tolerance as a fraction of the bounding box's diagonal.
    relative: f64,
    degree: usize,
    path: String,
}

/// `files_ui`: the File feature's state, through which the file browser is asked.
pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx, s: &mut CadExportSection, files_ui: &mut FileUi) {
    let id = ui.id().with("cad-export");
    let mut f = ui
        .data(|d| d.get_temp::<Fields>(id))
        .unwrap_or_else(|| Fields {
            format: Format::Step,
            relative: 1e-4,
            degree: 3,
            path: open_save::suggested(&p.model, p.patch.name(), "step"),
        });
    egui::CollapsingHeader::new("CAD export")
        .default_open(true)
        .show(ui, |ui| {
            ui.horizontal(|ui| {
                for (format, ext, tip) in [
                    (Format::Step, "step", "One B-spline face (AP214), fitted to the surface"),
                    (Format::Iges, "igs", "One B-spline surface (IGES 5.3 entity 128)"),
                    (Format::Glb, "glb", "The triangle mesh with normals (binary glTF)"),
                ] {
                    if ui
                        .selectable_label(f.format == format, format.name())
                        .on_hover_text(tip)
                        .clicked()
                    {
                        f.format = format;
                        f.path = open_save::suggested(&p.model, p.patch.name(), ext);
                    }
                }
            });
            let cad = f.format.is_cad();
            ui.add_enabled_ui(cad, |ui| {
                ui.horizontal(|ui| {
                    ui.add(
                        egui::DragValue::new(&mut f.relative)
                            .range(1e-7..=1e-2)
                            .speed(1e-6)
                            .custom_formatter(|v, _| format!("{v:.1e}")),
                    )
                    .on_hover_text("The largest allowed deviation, as a fraction of the bounding box's diagonal (default 1e-4)");
                    ui.label("tolerance");
                    ui.add(egui::DragValue::new(&mut f.degree).range(2..=5))
                        .on_hover_text("B-spline degree in both directions (3: C2 like the streamlines)");
                    ui.label("degree");
                });
            });
            ui.horizontal(|ui| {
                ui.add(egui::TextEdit::singleline(&mut f.path).desired_width(160.0))
                    .on_hover_text("The file to write (the extension picks the format)");
                let fit = FitOptions {
                    degree: (f.degree, f.degree),
                    tolerance: Tolerance::Relative(f.relative),
                };
                if ui
                    .button("Export")
                    .on_hover_text("Fit (STEP, IGES) and write; atomic and verified, a refusal keeps the old file")
                    .clicked()
                {
                    s.export.fit = fit;
                    p.send(Edit::Export(std::path::PathBuf::from(f.path.trim())));
                }
                if ui
                    .button("…")
                    .on_hover_text("Pick the folder and name in the file browser, then fit and write")
                    .clicked()
                {
                    s.export.fit = fit;
                    open_save::browse(files_ui, PathAction::Export(f.format), f.path.trim(), None);
                }
            });
            if let Some((path, out)) = &s.last_export.written {
                let file = path.file_name().map(|n| n.to_string_lossy()).unwrap_or_default();
                let mut text = format!("{}: {file}", out.format.name());
                if !out.faces.is_empty() {
                    text += &format!(" — sampled at depth {}, {:.1} ms", out.depth, out.seconds * 1e3);
                }
                // one line per face (a design of one patch writes one)
                for line in out.face_lines() {
                    text += &format!("\n{line}");
                }
                ui.label(egui::RichText::new(text).small()).on_hover_text(
                    "The last export: for STEP and IGES the depth the surface was sampled at (the display depth, or deeper when the tolerance needed more points) and the fit's time, then each face's net size, degree and largest deviation one depth finer, within the tolerance",
                );
            }
        });
    ui.data_mut(|d| d.insert_temp(id, f));
}
