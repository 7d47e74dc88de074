//! The state of File ▸ Import surface… (`import.rs`): the file read and
//! its faces, the fit's fields, the fit running on its own thread
//! (`fit_job.rs`) and how it ended ([`ImportForm`]), and the edit that
//! imports its design ([`import_edit`]).

use super::fit_job::{FitJob, JobEnd};
use crate::ecs::Edit;
use crate::scene::Scene;
use bevy::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;
use streamline_kernel::fit::options::{DEFAULT_DEPTH, DEFAULT_RELATIVE_TOLERANCE, MAX_FIT_DEPTH};
use streamline_kernel::fit::{Along, ReferenceFit, ReferenceFitOptions, Tolerance};
use streamline_reference::ReferenceFile;

use super::face_list::{FaceRow, read_faces};

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
        (self.file, self.faces, self.face, self.error) = read_faces(&path, false);
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
    pub(super) fn problem_with(
        &self,
        face: Option<usize>,
        relative: f64,
        depth: u32,
    ) -> Option<String> {
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
