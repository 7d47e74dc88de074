//! File ▸ Reference…: attach a reference to the current design without
//! fitting (`docs/math.md §12`): the file picked in the browser is read at
//! once, the "Reference" window lists its faces as File ▸ Import surface…
//! does (the chosen one drawn as a ghost, `surface/reference_ghost.rs`),
//! and **Attach** sends `Edit::SetReference` with the file (absolute in
//! memory; saved relative to the scene file) and the face: one undo step,
//! the design marked unsaved. A design with a reference offers **Detach
//! reference** too (here and in the File menu). A file that cannot be read
//! is named in the window; the design stays as it was.

use super::super::interaction::EditorSet;
use super::super::surface::reference_ghost::{GhostBuild, GhostPreview};
use super::face_list::{FaceRow, face_grid, file_head, file_window, read_faces};
use super::import::ImportForm;
use crate::ecs::{Edit, EditMessage};
use crate::scene::files::reference_link::ReferenceLink;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use std::path::PathBuf;
use std::sync::Arc;
use streamline_reference::ReferenceFile;

/// The dialog's state: the file read, its faces and the face chosen.
#[derive(Resource, Debug, Default)]
pub struct ReferenceForm {
    /// Shown.
    pub open: bool,
    /// The file picked.
    pub path: Option<PathBuf>,
    /// The file read.
    pub file: Option<Arc<ReferenceFile>>,
    /// Its faces.
    pub faces: Vec<FaceRow>,
    /// The face chosen.
    pub face: Option<usize>,
    /// Why the file could not be read.
    pub error: Option<String>,
}

impl ReferenceForm {
    /// Reads `path` and shows the dialog: its faces, the first one that
    /// can be drawn chosen; or, when it cannot be read, why.
    pub fn read(&mut self, path: PathBuf) {
        self.open = true;
        (self.file, self.faces, self.face, self.error) = read_faces(&path, true);
        self.path = Some(path);
    }

    /// Why Attach cannot be pressed, if it cannot.
    pub fn problem(&self) -> Option<String> {
        problem_with(self, self.face)
    }

    /// The link Attach sets: the file, absolute, and the face chosen.
    pub fn link(&self) -> Option<ReferenceLink> {
        if self.problem().is_some() {
            return None;
        }
        let path = self.path.as_ref()?;
        Some(ReferenceLink {
            path: std::path::absolute(path).unwrap_or_else(|_| path.clone()),
            face: self.face?,
        })
    }

    /// The edit Attach sends (`None` while [`Self::problem`] says no).
    pub fn attach(&self) -> Option<Edit> {
        self.link().map(|l| Edit::SetReference(Some(l)))
    }
}

fn problem_with(form: &ReferenceForm, face: Option<usize>) -> Option<String> {
    if form.file.is_none() {
        return Some("no file was read".into());
    }
    let Some(face) = face else {
        return Some("the file has no B-spline face or mesh to attach".into());
    };
    form.faces.get(face).and_then(|f| f.refused.clone())
}

pub struct ReferencePlugin;

impl Plugin for ReferencePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ReferenceForm>()
            .init_resource::<GhostPreview>()
            .add_systems(EguiPrimaryContextPass, dialog)
            .add_systems(
                Update,
                preview_chosen_face
                    .in_set(EditorSet::Present)
                    .before(GhostBuild),
            );
    }
}

/// Keeps the ghost's [`GhostPreview`] with the face chosen in an open
/// dialog (Reference… first, then Import surface…), or none.
fn preview_chosen_face(
    import: Option<Res<ImportForm>>,
    attach: Option<Res<ReferenceForm>>,
    mut preview: ResMut<GhostPreview>,
) {
    let chosen = |open: bool,
                  path: &Option<PathBuf>,
                  file: &Option<Arc<ReferenceFile>>,
                  face: Option<usize>| match (open, path, file, face) {
        (true, Some(p), Some(f), Some(face)) => Some((p.clone(), face, Arc::clone(f))),
        _ => None,
    };
    let want = attach
        .as_deref()
        .and_then(|a| chosen(a.open, &a.path, &a.file, a.face))
        .or_else(|| {
            import
                .as_deref()
                .and_then(|f| chosen(f.open, &f.path, &f.file, f.face))
        });
    let same = match (&preview.0, &want) {
        (None, None) => true,
        (Some((p, i, f)), Some((q, j, g))) => p == q && i == j && Arc::ptr_eq(f, g),
        _ => false,
    };
    if !same {
        preview.0 = want;
    }
}

fn dialog(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    mut form: ResMut<ReferenceForm>,
    patch: crate::ecs::patch::PatchRef,
    mut edits: MessageWriter<EditMessage>,
) -> Result {
    let _meter = meter.start();
    if !form.open {
        return Ok(());
    }
    let ctx = contexts.ctx_mut()?;
    let current = patch.reference().cloned();
    let mut face = form.face;
    let (mut attach, mut detach, mut close) = (false, false, false);
    let mut open = true;
    let anchor = (egui::Align2::CENTER_TOP, [0.0, 36.0]);
    file_window("Reference", "attach_reference", &mut open, anchor).show(ctx, |ui| {
        ui.label(
            egui::RichText::new(
                "A face to compare the design with (View, Reference; the deviation map); \
                     the design is not fitted to it.",
            )
            .weak(),
        );
        match &current {
            Some(l) => ui.label(format!(
                "Now: {}, face {}",
                l.path.file_name().map_or_else(
                    || l.path.display().to_string(),
                    |n| n.to_string_lossy().into()
                ),
                l.face
            )),
            None => ui.label("Now: no reference"),
        };
        ui.separator();
        let unchanged = "The reference is unchanged.";
        let (path, file) = (form.path.as_deref(), form.file.as_deref());
        let faces = form.faces.len();
        if file_head(ui, path, file, faces, form.error.as_deref(), unchanged) {
            face_grid(ui, &form.faces, &mut face, true);
        }
        ui.separator();
        let problem = problem_with(&form, face);
        ui.horizontal(|ui| {
            attach = ui
                .add_enabled(problem.is_none(), egui::Button::new("Attach"))
                .on_hover_text(
                    "Keep this face as the design's reference (saved with it, relative to \
                         the scene file); one undo step",
                )
                .on_disabled_hover_text(problem.clone().unwrap_or_default())
                .clicked();
            if current.is_some() {
                detach = ui
                    .button("Detach reference")
                    .on_hover_text("The design keeps no reference; one undo step")
                    .clicked();
            }
            close = ui.button("Close").clicked();
        });
        if let (Some(p), None) = (problem, &form.error) {
            ui.label(egui::RichText::new(p).color(egui::Color32::LIGHT_RED));
        }
    });
    if face != form.face {
        form.face = face;
    }
    if attach && let Some(edit) = form.attach() {
        edits.write(EditMessage::from(edit));
        close = true;
    }
    if detach {
        edits.write(EditMessage::from(Edit::SetReference(None)));
        close = true;
    }
    if !open || close {
        form.open = false;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attach_names_the_file_and_the_face() {
        let mut f = ReferenceForm::default();
        assert!(f.attach().is_none(), "no file yet");
        let hood = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.step");
        f.read(hood.clone());
        assert_eq!(f.error, None);
        let Some(Edit::SetReference(Some(link))) = f.attach() else {
            panic!("Attach is on");
        };
        assert_eq!(link.face, 0);
        assert!(link.path.is_absolute());
        f.read(PathBuf::from("/no/such/file.step"));
        assert!(f.error.is_some() && f.attach().is_none());
    }
}
