//! File ▸ Import surface…: a streamline design fitted to a face of a STEP or
//! IGES file, or to an OBJ grid of points (`docs/fit.md`, `docs/math.md
//! §12`). The file picked in the browser is read at once (a file that
//! cannot be read is named in the dialog; the current design stays); the
//! "Import surface" window lists its faces (a B-spline face can be chosen,
//! the others are greyed with the reason; the chosen one is drawn as a
//! ghost, `surface/reference_ghost.rs`), where the result goes (as a new
//! design, or as a new patch of the current design), the streamline
//! direction, the tolerance relative to the face's diagonal and the fit
//! depth. **Fit** runs the kernel's fit on a thread of its own, with a
//! progress bar and **Cancel** (the window and the 3D view stay live). A
//! design within the tolerance is imported at once; one that is not shows
//! why and offers "Import the best design" (the job itself is
//! `fit_job.rs`, the form's state `import_form.rs`). Importing is one edit, `Edit::Import`, and one undo step
//! either way: Undo brings back the design as it was. As a new design its
//! `reference` names the file and the face; as a new patch the design
//! keeps its reference, or takes the imported face when it has none.

use super::face_list::{face_grid, file_head, file_window};
pub use super::fit_job::{FitJob, Fitted, JobEnd};
pub use super::import_form::{ImportForm, import_edit, summary};
use crate::ecs::EditMessage;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use streamline_kernel::fit::Along;
use streamline_kernel::fit::options::MAX_FIT_DEPTH;

pub struct ImportPlugin;

impl Plugin for ImportPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ImportForm>()
            .add_systems(Update, finish_fits)
            .add_systems(EguiPrimaryContextPass, dialog);
    }
}

/// A fit that ended: within the tolerance, its design is imported.
fn finish_fits(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut form: ResMut<ImportForm>,
    mut edits: MessageWriter<EditMessage>,
) {
    let _meter = meter.start();
    if !form.job.as_ref().is_some_and(FitJob::is_finished) {
        return;
    }
    if let Some(scene) = form.poll() {
        edits.write(EditMessage::from(import_edit(&scene, form.as_patch)));
    }
}

/// Shows the window while the form is open, and does what its buttons say.
pub(super) fn dialog(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    mut form: ResMut<ImportForm>,
    patch: crate::ecs::patch::PatchRef,
    mut edits: MessageWriter<EditMessage>,
) -> Result {
    let _meter = meter.start();
    if !form.open {
        return Ok(());
    }
    let ctx = contexts.ctx_mut()?;
    // edited on a copy of the fields: the resource is marked changed only
    // when something is
    let (mut face, mut along, mut relative, mut depth, mut as_patch) = (
        form.face,
        form.along,
        form.relative,
        form.depth,
        form.as_patch,
    );
    let has_reference = patch.reference().is_some();
    let busy = form.busy();
    let (mut fit, mut cancel, mut best, mut close) = (false, false, false, false);
    let mut open = true;
    let anchor = (egui::Align2::CENTER_CENTER, [0.0, 0.0]);
    file_window("Import surface", "import_surface", &mut open, anchor).show(ctx, |ui| {
            let unchanged = "The current design is unchanged.";
            let (path, file) = (form.path.as_deref(), form.file.as_deref());
            let faces = form.faces.len();
            if !file_head(ui, path, file, faces, form.error.as_deref(), unchanged) {
                ui.separator();
                if ui.button("Close").clicked() {
                    close = true;
                }
                return;
            }
            face_grid(ui, &form.faces, &mut face, !busy);
            ui.separator();
            egui::Grid::new("import_grid")
                .num_columns(2)
                .spacing([12.0, 6.0])
                .show(ui, |ui| {
                    ui.label("Streamlines");
                    ui.add_enabled_ui(!busy, |ui| {
                        ui.horizontal(|ui| {
                            ui.radio_value(&mut along, Along::U, "along u")
                                .on_hover_text("Rows are the face's iso-curves v = const");
                            ui.radio_value(&mut along, Along::V, "along v")
                                .on_hover_text("Rows are the face's iso-curves u = const");
                        });
                    });
                    ui.end_row();
                    ui.label("Tolerance");
                    ui.add_enabled(
                        !busy,
                        egui::DragValue::new(&mut relative)
                            .speed(1e-5)
                            .range(1e-7..=0.1)
                            .custom_formatter(|v, _| format!("{v:.1e}"))
                            .suffix(" × diagonal"),
                    )
                    .on_hover_text(
                        "The largest allowed deviation, as a fraction of the face's bounding box's diagonal",
                    );
                    ui.end_row();
                    ui.label("Fit depth");
                    ui.add_enabled(
                        !busy,
                        egui::DragValue::new(&mut depth).range(1..=MAX_FIT_DEPTH),
                    )
                    .on_hover_text(
                        "Where the design is measured, shown and exported (1–7)",
                    );
                    ui.end_row();
                });
            ui.separator();
            if let Some(job) = &form.job {
                ui.add(
                    egui::ProgressBar::new(job.progress() as f32)
                        .show_percentage()
                        .animate(true),
                )
                .on_hover_text("The net grows until the design is within the tolerance");
                cancel = ui
                    .button("Cancel")
                    .on_hover_text("Stop the fit; the current design is unchanged")
                    .clicked();
                ui.ctx()
                    .request_repaint_after(std::time::Duration::from_millis(100));
                return;
            }
            let problem = form.problem_with(face, relative, depth);
            match &form.last {
                Some(JobEnd::Fitted(f)) if f.fit.within => {
                    ui.label(format!("Fitted: {}", summary(&f.fit)));
                }
                Some(JobEnd::Fitted(f)) => {
                    ui.colored_label(
                        egui::Color32::from_rgb(255, 200, 120),
                        format!(
                            "Not within the tolerance: {}",
                            f.fit.why.as_deref().unwrap_or("the net reached its cap")
                        ),
                    );
                    ui.label(summary(&f.fit));
                    best = ui
                        .add_enabled(!form.opened, egui::Button::new("Import the best design"))
                        .on_hover_text("Import the closest design reached (one undo step)")
                        .clicked();
                }
                Some(JobEnd::Failed(e)) => {
                    ui.colored_label(egui::Color32::LIGHT_RED, e);
                }
                Some(JobEnd::Cancelled) => {
                    ui.label(
                        egui::RichText::new("Cancelled; the current design is unchanged.").weak(),
                    );
                }
                None => {}
            }
            ui.horizontal(|ui| {
                fit = ui
                    .add_enabled(problem.is_none(), egui::Button::new("Fit"))
                    .on_hover_text("Fit a streamline design to the face, then import it")
                    .on_disabled_hover_text(problem.clone().unwrap_or_default())
                    .clicked();
                if ui.button("Close").clicked() {
                    close = true;
                }
                ui.separator();
                ui.add_enabled_ui(!busy, |ui| {
                    ui.radio_value(&mut as_patch, false, "as a new design")
                        .on_hover_text(
                            "The fitted design replaces the current one; its reference is this \
                             face. One undo step brings the current design back",
                        );
                    ui.radio_value(&mut as_patch, true, "as a new patch")
                        .on_hover_text(
                            "The fitted surface is added to the current design as a patch of its \
                             own, joined to none; the design keeps its reference (this face when \
                             it has none). One undo step",
                        );
                });
            });
            if as_patch {
                ui.label(
                    egui::RichText::new(if has_reference {
                        "A new patch, joined to none; the design keeps its reference."
                    } else {
                        "A new patch, joined to none; the design has no reference: it takes this face."
                    })
                    .weak(),
                );
            }
            if let Some(p) = problem {
                ui.label(egui::RichText::new(p).color(egui::Color32::LIGHT_RED));
            }
        });
    if (face, along, relative, depth, as_patch)
        != (
            form.face,
            form.along,
            form.relative,
            form.depth,
            form.as_patch,
        )
    {
        form.as_patch = as_patch;
        form.face = face;
        form.along = along;
        form.relative = relative;
        form.depth = depth;
    }
    if cancel {
        form.cancel();
    }
    if fit {
        form.start();
        ctx.request_repaint();
    }
    if best && let Some(scene) = form.best() {
        edits.write(EditMessage::from(import_edit(&scene, form.as_patch)));
    }
    if !open || close {
        form.cancel();
        form.open = false;
    }
    Ok(())
}
