//! The faces of a file read, as the dialogs on it list them (File ▸ Import
//! surface…, `import.rs`; File ▸ Reference…, `reference.rs`): which can be
//! chosen and why not ([`faces_of`]), the grid they are chosen in
//! ([`face_grid`]), and the dialogs' shared frame: their window
//! ([`file_window`]) and its head ([`file_head`]).

use bevy_egui::egui;
use std::path::Path;
use std::sync::Arc;
use streamline_reference::{FaceInfo, ReferenceFile};

/// A face of the file read, as the dialog lists it.
#[derive(Debug, Clone)]
pub struct FaceRow {
    /// What the reader says about it.
    pub info: FaceInfo,
    /// Why it cannot be fitted (`None`: a B-spline surface, it can).
    pub refused: Option<String>,
}

/// What a dialog shows of a file it reads: the file, its faces
/// ([`faces_of`]), the first face that can be chosen, and why it could not
/// be read.
pub(super) type FileRead = (
    Option<Arc<ReferenceFile>>,
    Vec<FaceRow>,
    Option<usize>,
    Option<String>,
);

/// Reads `path` for a dialog ([`FileRead`]; `meshes`: as [`faces_of`]).
pub(super) fn read_faces(path: &Path, meshes: bool) -> FileRead {
    match streamline_reference::read(path) {
        Ok(file) => {
            let faces = faces_of(&file, meshes);
            let face = faces.iter().position(|f| f.refused.is_none());
            (Some(Arc::new(file)), faces, face, None)
        }
        Err(e) => (None, Vec::new(), None, Some(e.to_string())),
    }
}

/// The faces of `file` as the dialogs list them: a face that is not a
/// B-spline surface is refused with the reader's reason, unless it is a
/// triangle mesh and `meshes` are wanted (a reference is measured against
/// a mesh, not fitted to it).
fn faces_of(file: &ReferenceFile, meshes: bool) -> Vec<FaceRow> {
    file.faces
        .iter()
        .enumerate()
        .map(|(i, f)| FaceRow {
            info: f.info.clone(),
            refused: if meshes && matches!(file.mesh(i), Ok(Some(_))) {
                None
            } else {
                file.surface(i).err().map(|e| e.to_string())
            },
        })
        .collect()
}

/// A dialog on a file read (File ▸ Import surface…, File ▸ Reference…):
/// its window, closed with its ×, in `open`, at `anchor` of the screen.
pub(super) fn file_window<'a>(
    title: &str,
    id: &str,
    open: &'a mut bool,
    anchor: (egui::Align2, [f32; 2]),
) -> egui::Window<'a> {
    egui::Window::new(title)
        .id(egui::Id::new(id))
        .collapsible(false)
        .resizable(false)
        .open(open)
        .anchor(anchor.0, anchor.1)
}

/// The head of a dialog on a file read: the file's name, then why it could
/// not be read (`error`, and `unchanged`: what stays as it was) or how many
/// faces it has and its unit. Returns whether it was read.
pub(super) fn file_head(
    ui: &mut egui::Ui,
    path: Option<&Path>,
    file: Option<&ReferenceFile>,
    faces: usize,
    error: Option<&str>,
    unchanged: &str,
) -> bool {
    if let Some(p) = path {
        let name = p
            .file_name()
            .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into());
        ui.label(egui::RichText::new(name).strong())
            .on_hover_text(p.display().to_string());
    }
    if let Some(e) = error {
        ui.colored_label(egui::Color32::LIGHT_RED, e);
        ui.label(egui::RichText::new(unchanged).weak());
        return false;
    }
    if let Some(file) = file {
        ui.label(format!(
            "{} face{}, lengths in {} (shown in metres)",
            faces,
            if faces == 1 { "" } else { "s" },
            file.unit
        ));
    }
    true
}

/// The faces as a grid: one row each, a B-spline face selectable.
pub(super) fn face_grid(
    ui: &mut egui::Ui,
    faces: &[FaceRow],
    chosen: &mut Option<usize>,
    enabled: bool,
) {
    egui::ScrollArea::vertical()
        .max_height(180.0)
        .show(ui, |ui| {
            egui::Grid::new("import_faces")
                .num_columns(7)
                .spacing([12.0, 4.0])
                .striped(true)
                .show(ui, |ui| {
                    for h in [
                        "Face", "Kind", "Degrees", "Poles", "Trimmed", "Area", "Size",
                    ] {
                        ui.label(egui::RichText::new(h).strong());
                    }
                    ui.end_row();
                    for f in faces {
                        let i = &f.info;
                        let ok = f.refused.is_none() && enabled;
                        let r = ui.add_enabled(
                            ok,
                            egui::Button::selectable(
                                *chosen == Some(i.index),
                                format!("{}", i.index),
                            ),
                        );
                        let r = match &f.refused {
                            Some(why) => r.on_disabled_hover_text(why),
                            None => {
                                r.on_hover_text(format!("Choose face {} ({})", i.index, i.entity))
                            }
                        };
                        if r.clicked() {
                            *chosen = Some(i.index);
                        }
                        let cell = |ui: &mut egui::Ui, t: String| {
                            if f.refused.is_some() {
                                ui.label(egui::RichText::new(t).weak());
                            } else {
                                ui.label(t);
                            }
                        };
                        cell(ui, kind_of(i));
                        cell(
                            ui,
                            i.degrees.map_or("—".into(), |[p, q]| format!("{p} × {q}")),
                        );
                        cell(
                            ui,
                            i.poles.map_or("—".into(), |[m, n]| format!("{m} × {n}")),
                        );
                        cell(ui, if i.trimmed { "yes" } else { "no" }.into());
                        cell(
                            ui,
                            if i.area > 0.0 {
                                format!("{:.4} m²", i.area)
                            } else {
                                "—".into()
                            },
                        );
                        cell(ui, size_of(i));
                        ui.end_row();
                    }
                });
        });
}

/// A face's size: its bounding box's sides, in metres.
fn size_of(info: &FaceInfo) -> String {
    match info.bbox {
        Some([lo, hi]) => format!(
            "{:.3} × {:.3} × {:.3} m",
            hi[0] - lo[0],
            hi[1] - lo[1],
            hi[2] - lo[2]
        ),
        None => "—".into(),
    }
}

/// A face's kind, as the `faces` command names it.
fn kind_of(info: &FaceInfo) -> String {
    serde_json::to_value(info.kind)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}
