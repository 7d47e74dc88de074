//! The fit of File ▸ Import surface… (`import.rs`) as a job: the kernel's
//! `fit_reference_with` on a thread of its own, its progress in an atomic
//! the dialog reads each frame, Cancel an atomic flag its progress hook
//! answers (`false` stops the fit at its next net: `docs/math.md §12`). What
//! it ends with: the fitted scene, named after the file and keeping the file
//! and face as its `reference`, with the kernel's figures; or why not.

use crate::scene::Scene;
use crate::scene::files::reference_link::ReferenceLink;
use crate::scene::fit::reference::{fitted_name, fitted_scene};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::thread::JoinHandle;
use streamline_kernel::fit::{
    ReferenceFit, ReferenceFitError, ReferenceFitOptions, fit_reference_with,
};
use streamline_reference::ReferenceFile;

/// A fit that ended: its scene (named after the file, keeping the file and
/// face as its reference) and its figures.
#[derive(Debug, Clone)]
pub struct Fitted {
    /// The scene to open.
    pub scene: Arc<Scene>,
    /// The kernel's figures (net, deviations, tolerance, seconds, why).
    pub fit: ReferenceFit,
}

/// How the last fit ended.
#[derive(Debug, Clone)]
pub enum JobEnd {
    /// A design came out (within the tolerance or not: `fit.within`).
    Fitted(Box<Fitted>),
    /// The fit refused the face, or the thread failed.
    Failed(String),
    /// Cancel was pressed; nothing was changed.
    Cancelled,
}

/// A fit running on its own thread.
#[derive(Debug)]
pub struct FitJob {
    /// The fraction done, an `f64`'s bits.
    progress: Arc<AtomicU64>,
    /// Set by Cancel; the kernel's progress hook returns `false` then.
    cancel: Arc<AtomicBool>,
    thread: JoinHandle<JobEnd>,
}

impl FitJob {
    /// Fits face `face` of `file` with `opts` on a new thread.
    pub(super) fn start(file: Arc<ReferenceFile>, face: usize, opts: ReferenceFitOptions) -> Self {
        let progress = Arc::new(AtomicU64::new(0f64.to_bits()));
        let cancel = Arc::new(AtomicBool::new(false));
        let (p, c) = (progress.clone(), cancel.clone());
        let thread = std::thread::Builder::new()
            .name("import-fit".into())
            .spawn(move || run_fit(&file, face, &opts, &p, &c))
            .expect("a thread for the fit");
        FitJob {
            progress,
            cancel,
            thread,
        }
    }

    /// The fraction done, in `[0, 1]` (rough: the kernel's estimate).
    pub fn progress(&self) -> f64 {
        f64::from_bits(self.progress.load(Ordering::Relaxed))
    }

    /// Asks the fit to stop at its next net.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// Whether the thread has ended.
    pub fn is_finished(&self) -> bool {
        self.thread.is_finished()
    }

    /// Waits for the thread's answer.
    pub(super) fn join(self) -> JobEnd {
        self.thread
            .join()
            .unwrap_or_else(|_| JobEnd::Failed("the fit stopped unexpectedly".into()))
    }
}

/// The fit itself (on the job's thread).
fn run_fit(
    file: &ReferenceFile,
    face: usize,
    opts: &ReferenceFitOptions,
    progress: &AtomicU64,
    cancel: &AtomicBool,
) -> JobEnd {
    let surface = match file.surface(face) {
        Ok(s) => s,
        Err(e) => return JobEnd::Failed(e.to_string()),
    };
    let mut hook = |f: f64| {
        progress.store(f.clamp(0.0, 1.0).to_bits(), Ordering::Relaxed);
        !cancel.load(Ordering::Relaxed)
    };
    let where_ = || format!("{}: face {face}", file.path.display());
    match fit_reference_with(surface, opts, &mut hook) {
        Ok(fit) => {
            let path = std::path::absolute(&file.path).unwrap_or_else(|_| file.path.clone());
            let link = ReferenceLink {
                path: path.clone(),
                face,
            };
            match fitted_scene(&fit, &fitted_name(&path), link) {
                Ok(scene) => JobEnd::Fitted(Box::new(Fitted {
                    scene: Arc::new(scene),
                    fit,
                })),
                Err(e) => JobEnd::Failed(format!("{}: {e}", where_())),
            }
        }
        Err(ReferenceFitError::Cancelled) => JobEnd::Cancelled,
        Err(e) => JobEnd::Failed(format!("{}: {e}", where_())),
    }
}
