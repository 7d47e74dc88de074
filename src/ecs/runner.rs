//! Scripts run inside a live app (the editor's File ▸ Run script): the file is
//! read and parsed on a worker thread, then its steps go out as edit messages
//! a batch per frame, the batch sized so the model's systems stay near
//! [`FRAME_BUDGET_MS`] a frame. Progress is shown and the run can be
//! cancelled at any step, so a million-step script never hangs the editor.
//! A `Fit` step's fit (docs/math.md §12, seconds on a large face) runs on a
//! worker thread too; the steps after it wait for its design.
//! Expectations are skipped here (`streamline-studio play` checks them).

use super::messages::EditMessage;
use super::resources::Stats;
use crate::scene::edits::script::{Script, step::Step};
use crate::scene::job::{Job, Poll};
use bevy::prelude::*;
use std::path::{Path, PathBuf};

/// What the model's systems may spend a frame on script steps (ms).
pub const FRAME_BUDGET_MS: f64 = 4.0;

/// The most steps sent in one frame.
pub const MAX_BATCH: usize = 256;

/// The state of the script run.
#[derive(Resource, Default)]
pub struct ScriptRun {
    /// What is happening.
    pub state: RunState,
    /// The path typed in the panel.
    pub input: String,
}

/// Where a run is.
#[derive(Default)]
pub enum RunState {
    /// No script.
    #[default]
    Idle,
    /// The file is being read and parsed off the frame.
    Parsing(PathBuf, Job<Result<Script, String>>),
    /// Steps are being sent.
    Running {
        /// The script file.
        path: PathBuf,
        /// Its steps.
        script: Script,
        /// The next step to send.
        next: usize,
        /// Steps sent per frame now.
        batch: usize,
        /// Edits sent.
        sent: usize,
        /// Expectations skipped.
        skipped: usize,
        /// Steps refused (a bad path…), with the first message.
        refused: (usize, Option<String>),
        /// A `Fit` step's fit, under way off the frame: its edit to come.
        fitting: Option<Job<Result<super::messages::Edit, String>>>,
    },
    /// Finished or stopped: a line for the panel.
    Done(String),
}

impl ScriptRun {
    /// Starts reading `path`; a run in progress is stopped.
    pub fn start(&mut self, path: PathBuf) {
        self.cancel();
        let label = format!("reading {}", path.display());
        let file = path.clone();
        self.state = RunState::Parsing(
            path,
            Job::spawn(&label, move |p| {
                p.stage("reading and parsing", 0);
                Script::load(&file).map_err(|e| e.to_string())
            }),
        );
    }

    /// Stops the run where it is (steps already applied stay, and undo takes them back).
    pub fn cancel(&mut self) {
        let line = match &self.state {
            RunState::Parsing(_, job) => {
                job.cancel();
                Some("cancelled while reading; nothing was run".to_string())
            }
            RunState::Running {
                next, script, path, ..
            } => Some(format!(
                "{}: cancelled after step {next} of {}; undo takes the steps back",
                path.display(),
                script.steps.len()
            )),
            _ => None,
        };
        if let Some(l) = line {
            self.state = RunState::Done(l);
        }
    }

    /// Whether a script is being read or run.
    pub fn busy(&self) -> bool {
        matches!(self.state, RunState::Parsing(..) | RunState::Running { .. })
    }

    /// `(steps done, steps in all)` while running.
    pub fn progress(&self) -> Option<(usize, usize)> {
        match &self.state {
            RunState::Running { next, script, .. } => Some((*next, script.steps.len())),
            _ => None,
        }
    }
}

/// Runs scripts in a live app.
pub struct ScriptRunPlugin;

impl Plugin for ScriptRunPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ScriptRun>()
            .add_systems(Update, drive.before(super::ModelSet::Edit));
    }
}

/// Polls the parse, then sends the next batch of steps.
fn drive(mut run: ResMut<ScriptRun>, mut edits: MessageWriter<EditMessage>, stats: Res<Stats>) {
    if let RunState::Parsing(path, job) = &run.state {
        run.state = match job.poll() {
            Poll::Running => return,
            Poll::Done(Ok(script)) => RunState::Running {
                path: path.clone(),
                script,
                next: 0,
                batch: 1,
                sent: 0,
                skipped: 0,
                refused: (0, None),
                fitting: None,
            },
            Poll::Done(Err(e)) => RunState::Done(e),
            Poll::Lost => RunState::Done("the reader stopped without a result (a bug)".into()),
        };
        return;
    }
    let RunState::Running {
        path,
        script,
        next,
        batch,
        sent,
        skipped,
        refused,
        fitting,
    } = &mut run.state
    else {
        return;
    };
    if let Some(job) = fitting {
        let done = match job.poll() {
            Poll::Running => return,
            Poll::Done(r) => r,
            Poll::Lost => Err("the fit stopped without a result (a bug)".into()),
        };
        match done {
            Ok(edit) => {
                edits.write(EditMessage::from(edit));
                *sent += 1;
            }
            Err(m) => {
                refused.0 += 1;
                refused.1.get_or_insert(m);
            }
        }
        *fitting = None;
    }
    // size the batch by what the last frame's edits cost
    let spent_ms = stats.last.us_total() / 1e3;
    if *sent > 0 {
        if spent_ms > FRAME_BUDGET_MS {
            *batch = (*batch / 2).max(1);
        } else if spent_ms < FRAME_BUDGET_MS / 2.0 {
            *batch = (*batch * 2).min(MAX_BATCH);
        }
    }
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let end = (*next + *batch).min(script.steps.len());
    let mut at = *next;
    while at < end {
        let step = &script.steps[at];
        at += 1;
        if step.is_expectation() {
            *skipped += 1;
            continue;
        }
        if let Step::Fit(_) = step {
            let (step, dir) = (step.clone(), dir.clone());
            let label = format!("{} step {at}: fitting", path.display());
            *fitting = Some(Job::spawn(&label, move |_| {
                super::playback::to_edit(&step, &dir)
            }));
            break;
        }
        match super::playback::to_edit(step, &dir) {
            Ok(edit) => {
                edits.write(EditMessage::from(edit));
                *sent += 1;
            }
            Err(m) => {
                refused.0 += 1;
                refused.1.get_or_insert(m);
            }
        }
    }
    *next = at;
    if *next >= script.steps.len() && fitting.is_none() {
        let mut line = format!(
            "{}: ran {} steps ({} edits; {} expectations skipped: `streamline-studio play` checks them)",
            path.display(),
            script.steps.len(),
            sent,
            skipped
        );
        if let (n, Some(m)) = refused {
            line.push_str(&format!("; {n} refused, the first: {m}"));
        }
        run.state = RunState::Done(line);
    }
}
