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
//! `fit_job.rs`). Importing is one edit, `Edit::Import`, and one undo step
//! either way: Undo brings back the design as it was. As a new design its
//! `reference` names the file and the face; as a new patch the design
//! keeps its reference, or takes the imported face when it has none.

pub use super::fit_job::{FitJob, Fitted, JobEnd};
use crate::ecs::{Edit, EditMessage};
use crate::scene::Scene;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use std::path::PathBuf;
use std::sync::Arc;
use streamline_kernel::fit::options::{DEFAULT_DEPTH, DEFAULT_RELATIVE_TOLERANCE, MAX_FIT_DEPTH};
use streamline_kernel::fit::{Along, ReferenceFit, ReferenceFitOptions, Tolerance};
use streamline_reference::{FaceInfo, ReferenceFile};

/// A face of the file read, as the dialog lists it.
#[derive(Debug, Clone)]
pub struct FaceRow {
    /// What the reader says about it.
    pub info: FaceInfo,
    /// Why it cannot be fitted (`None`: a B-spline surface, it can).
    pub refused: Option<String>,
}

/// The dialog's state: the file read, the fields, the job and how it ended.
#[derive(Resource, Debug)]
pub struct ImportForm {
    /// Shown.
    pub open: bool,
    /// The file picked.
    pub path: Option<PathBuf>,
    /// The file read (shared with the job's thread).
    pub file: Option<Arc<ReferenceFile>>,
    /// Its faces.
    pub faces: Vec<FaceRow>,
    /// The face chosen.
    pub face: Option<usize>,
    /// Which parameter of the face the streamlines follow.
    pub along: Along,
    /// The tolerance as a fraction of the face's bounding box's diagonal.
    pub relative: f64,
    /// The fit depth (1–7).
    pub depth: u32,
    /// Why the file could not be read.
    pub error: Option<String>,
    /// The fit running.
    pub job: Option<FitJob>,
    /// How the last fit ended.
    pub last: Option<JobEnd>,
    /// Whether the last fit's design was sent to be opened.
    pub opened: bool,
    /// Import as a new patch of the current design (else as a new design).
    pub as_patch: bool,
}

impl Default for ImportForm {
    fn default() -> Self {
        ImportForm {
            open: false,
            path: None,
            file: None,
            faces: Vec::new(),
            face: None,
            along: Along::U,
            relative: DEFAULT_RELATIVE_TOLERANCE,
            depth: DEFAULT_DEPTH,
            error: None,
            job: None,
            last: None,
            opened: false,
            as_patch: false,
        }
    }
}

impl ImportForm {
    /// Reads `path` and shows the dialog: its faces, the first B-spline one
    /// chosen; or, when it cannot be read, why (nothing else changes). A
    /// fit still running is cancelled.
    pub fn read(&mut self, path: PathBuf) {
        if let Some(job) = self.job.take() {
            job.cancel();
        }
        self.open = true;
        self.last = None;
        self.opened = false;
        self.faces.clear();
        self.face = None;
        self.file = None;
        match streamline_reference::read(&path) {
            Ok(file) => {
                self.error = None;
                self.faces = file
                    .faces
                    .iter()
                    .enumerate()
                    .map(|(i, f)| FaceRow {
                        info: f.info.clone(),
                        refused: file.surface(i).err().map(|e| e.to_string()),
                    })
                    .collect();
                self.face = self.faces.iter().position(|f| f.refused.is_none());
                self.file = Some(Arc::new(file));
            }
            Err(e) => self.error = Some(e.to_string()),
        }
        self.path = Some(path);
    }

    /// The kernel's options of the fields.
    pub fn options(&self) -> ReferenceFitOptions {
        ReferenceFitOptions {
            along: self.along,
            tolerance: Tolerance::Relative(self.relative),
            depth: self.depth,
            ..ReferenceFitOptions::default()
        }
    }

    /// Why Fit cannot start, if it cannot (the button stays off and says so).
    pub fn problem(&self) -> Option<String> {
        self.problem_with(self.face, self.relative, self.depth)
    }

    /// [`Self::problem`] with these fields (the dialog's, being edited).
    fn problem_with(&self, face: Option<usize>, relative: f64, depth: u32) -> Option<String> {
        if self.file.is_none() {
            return Some("no file was read".into());
        }
        let Some(face) = face else {
            return Some("the file has no B-spline face to fit".into());
        };
        if let Some(why) = self.faces.get(face).and_then(|f| f.refused.clone()) {
            return Some(why);
        }
        if !(relative.is_finite() && relative > 0.0 && relative < 1.0) {
            return Some("the tolerance must lie strictly between 0 and 1".into());
        }
        if !(1..=MAX_FIT_DEPTH).contains(&depth) {
            return Some(format!("the depth must be 1 to {MAX_FIT_DEPTH}"));
        }
        if self.job.is_some() {
            return Some("a fit is running".into());
        }
        None
    }

    /// Starts the fit on its own thread; `false` when [`Self::problem`] says no.
    pub fn start(&mut self) -> bool {
        if self.problem().is_some() {
            return false;
        }
        let (Some(file), Some(face)) = (self.file.clone(), self.face) else {
            return false;
        };
        self.last = None;
        self.opened = false;
        self.job = Some(FitJob::start(file, face, self.options()));
        true
    }

    /// Cancels the fit running, if any (it ends at its next net).
    pub fn cancel(&mut self) {
        if let Some(job) = &self.job {
            job.cancel();
        }
    }

    /// Whether a fit is running.
    pub fn busy(&self) -> bool {
        self.job.is_some()
    }

    /// Collects a fit that ended: the scene to open when it came within the
    /// tolerance (else it waits for "Import the best design").
    pub fn poll(&mut self) -> Option<Arc<Scene>> {
        if !self.job.as_ref().is_some_and(FitJob::is_finished) {
            return None;
        }
        let end = self.job.take()?.join();
        let open = match &end {
            JobEnd::Fitted(f) if f.fit.within => Some(f.scene.clone()),
            _ => None,
        };
        self.opened = open.is_some();
        self.last = Some(end);
        open
    }

    /// The last fit's design, to open although it is not within the tolerance.
    pub fn best(&mut self) -> Option<Arc<Scene>> {
        match &self.last {
            Some(JobEnd::Fitted(f)) if !self.opened => {
                self.opened = true;
                Some(f.scene.clone())
            }
            _ => None,
        }
    }
}

/// The figures of a fit, in one line.
pub fn summary(fit: &ReferenceFit) -> String {
    format!(
        "{} × {} net at depth {}: to the face max {:.2e} m, from the face max {:.2e} m \
         (tolerance {:.2e} m); {:.2} s",
        fit.net.0,
        fit.net.1,
        fit.depth,
        fit.to_reference.max,
        fit.from_reference.max,
        fit.tolerance,
        fit.seconds
    )
}

/// The edit that imports a fitted `scene` as the form says (a new design
/// or a new patch).
pub fn import_edit(scene: &Scene, as_patch: bool) -> Edit {
    Edit::Import {
        scene: Box::new(scene.clone()),
        as_patch,
    }
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

fn dialog(
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
    egui::Window::new("Import surface")
        .id(egui::Id::new("import_surface"))
        .collapsible(false)
        .resizable(false)
        .open(&mut open)
        .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
        .show(ctx, |ui| {
            if let Some(p) = &form.path {
                let name = p
                    .file_name()
                    .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into());
                ui.label(egui::RichText::new(name).strong())
                    .on_hover_text(p.display().to_string());
            }
            if let Some(e) = &form.error {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
                ui.label(egui::RichText::new("The current design is unchanged.").weak());
                ui.separator();
                if ui.button("Close").clicked() {
                    close = true;
                }
                return;
            }
            if let Some(file) = &form.file {
                ui.label(format!(
                    "{} face{}, lengths in {} (shown in metres)",
                    form.faces.len(),
                    if form.faces.len() == 1 { "" } else { "s" },
                    file.unit
                ));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_form_refuses_what_the_fit_refuses() {
        let mut f = ImportForm::default();
        assert!(f.problem().is_some(), "no file yet");
        assert!(!f.start());
        let hood = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.step");
        f.read(hood);
        assert_eq!(f.error, None);
        assert_eq!(f.face, Some(0));
        assert_eq!(f.problem(), None);
        f.relative = 0.0;
        assert!(f.problem().is_some());
        f.relative = DEFAULT_RELATIVE_TOLERANCE;
        f.depth = MAX_FIT_DEPTH + 1;
        assert!(f.problem().is_some());
        f.read(PathBuf::from("/no/such/file.step"));
        assert!(f.error.is_some() && f.file.is_none() && f.faces.is_empty());
    }
}
