//! Work that may take long (reading a big OBJ, interpolating it, parsing a
//! long script) runs on its own thread, off the editor's frame: the frame
//! reads its [`Progress`] to draw a bar, can ask it to stop, and picks the
//! result up when it is there. Nothing here knows Bevy.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

/// How far a job is, and whether it was asked to stop; shared between the
/// worker and the frame.
#[derive(Debug, Default)]
pub struct Progress {
    done: AtomicU64,
    total: AtomicU64,
    cancel: AtomicBool,
    stage: Mutex<String>,
}

impl Progress {
    /// A fresh progress (nothing done, not cancelled).
    pub fn new() -> Arc<Self> {
        Arc::new(Progress::default())
    }

    /// Starts a stage of `total` units (bytes, lines, iterations).
    pub fn stage(&self, name: &str, total: u64) {
        if let Ok(mut s) = self.stage.lock() {
            s.clear();
            s.push_str(name);
        }
        self.done.store(0, Ordering::Relaxed);
        self.total.store(total, Ordering::Relaxed);
    }

    /// Sets the units done in this stage.
    pub fn set(&self, done: u64) {
        self.done.store(done, Ordering::Relaxed);
    }

    /// The stage's name.
    pub fn stage_name(&self) -> String {
        self.stage.lock().map(|s| s.clone()).unwrap_or_default()
    }

    /// Units done and total in this stage.
    pub fn counts(&self) -> (u64, u64) {
        (
            self.done.load(Ordering::Relaxed),
            self.total.load(Ordering::Relaxed),
        )
    }

    /// Fraction of this stage done, in `[0, 1]` (0 when the total is unknown).
    pub fn fraction(&self) -> f32 {
        let (d, t) = self.counts();
        if t == 0 {
            0.0
        } else {
            (d as f64 / t as f64).clamp(0.0, 1.0) as f32
        }
    }

    /// Asks the worker to stop.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// Whether the worker was asked to stop.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// A job on its own thread, with its progress and its result to come.
#[derive(Debug)]
pub struct Job<T> {
    /// What it is doing, for the panel.
    pub label: String,
    /// Shared with the worker.
    pub progress: Arc<Progress>,
    result: Arc<Mutex<Option<T>>>,
    thread: Option<JoinHandle<()>>,
}

/// What [`Job::poll`] found.
#[derive(Debug)]
pub enum Poll<T> {
    /// Still running.
    Running,
    /// Finished with this result.
    Done(T),
    /// The worker ended without a result (it panicked, or could not start).
    Lost,
}

impl<T: Send + 'static> Job<T> {
    /// Runs `work` on a new thread; it reads the progress to report and to stop.
    pub fn spawn(label: &str, work: impl FnOnce(&Progress) -> T + Send + 'static) -> Self {
        let progress = Progress::new();
        let result = Arc::new(Mutex::new(None));
        let (p, r) = (Arc::clone(&progress), Arc::clone(&result));
        let thread = std::thread::Builder::new()
            .name(format!("job: {label}"))
            .spawn(move || {
                let t = work(&p);
                if let Ok(mut slot) = r.lock() {
                    *slot = Some(t);
                }
            })
            .ok();
        Job {
            label: label.to_string(),
            progress,
            result,
            thread,
        }
    }

    fn take(&self) -> Option<T> {
        self.result.lock().ok().and_then(|mut s| s.take())
    }

    /// Whether the result is there (never blocks).
    pub fn poll(&self) -> Poll<T> {
        if let Some(t) = self.take() {
            return Poll::Done(t);
        }
        match &self.thread {
            Some(h) if !h.is_finished() => Poll::Running,
            // finished: the result may have landed since the first look
            _ => self.take().map_or(Poll::Lost, Poll::Done),
        }
    }

    /// Asks the worker to stop (it returns soon with its "cancelled" result).
    pub fn cancel(&self) {
        self.progress.cancel();
    }

    /// Waits for the result (tests and the headless command line).
    pub fn wait(mut self) -> Option<T> {
        if let Some(h) = self.thread.take() {
            let _ = h.join();
        }
        self.take()
    }
}
