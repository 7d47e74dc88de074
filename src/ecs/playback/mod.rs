//! Scripted playback: each step of a [`Script`] is an edit message sent to a
//! headless app (one update per step; the patch steps too, applied by the
//! edit stage as the editor's are) or an expectation checked against it
//! (`playback/expect.rs`, `playback/seam.rs`). A `Fit` step fits its design
//! before it is sent, as the design that replaces the current one
//! (`playback/fit.rs`).

mod expect;
mod fit;
mod seam;

use super::edit_error::EditError;
use super::messages::Edit;
use super::resources::*;
use super::warnings::BuildWarnings;
use super::{headless_app, send};
use crate::scene::edits::script::{Script, expect::Expect, step::Step};
use crate::scene::{Scene, design::builtin};
use bevy::prelude::*;
use std::path::{Path, PathBuf};

/// The outcome of a script.
#[derive(Debug, Clone, Default)]
pub struct PlayReport {
    /// One line per step.
    pub lines: Vec<String>,
    /// Steps that failed.
    pub failures: usize,
}

impl PlayReport {
    /// Every step held.
    pub fn passed(&self) -> bool {
        self.failures == 0
    }
}

/// Runs `script`, whose relative paths are resolved against `dir`, starting
/// from `scene`.
pub fn play(script: &Script, dir: &Path, scene: Scene) -> PlayReport {
    let mut app = headless_app(scene);
    let mut report = PlayReport::default();
    let mut marks = expect::Marks::new();
    let mut pending: Option<(usize, String)> = None;
    let mut warned = warn_new(&app, 0, &[], &mut report);
    for (i, step) in script.steps.iter().enumerate() {
        let n = i + 1;
        if !matches!(step, Step::Expect(Expect::ExpectError(_)))
            && let Some((at, err)) = pending.take()
        {
            report.failures += 1;
            report
                .lines
                .push(format!("step {at:>3}: FAIL unexpected error: {err}"));
        }
        if let Step::Expect(x) = step
            && !matches!(
                x,
                Expect::ExpectSeam { .. } | Expect::ExpectReferenceDeviation { .. }
            )
        {
            let res = expect::check(&app, x, &mut marks, &mut pending);
            let label = short(step);
            match res {
                Ok(m) => report.lines.push(format!("step {n:>3} {label}: ok {m}")),
                Err(m) => {
                    report.failures += 1;
                    report.lines.push(format!("step {n:>3} {label}: FAIL {m}"));
                }
            }
            continue;
        }
        if let Step::Expect(x) = step {
            let label = short(step);
            let outcome = match x {
                Expect::ExpectReferenceDeviation { max, min } => {
                    expect::reference_deviation(&app, max, min)
                }
                _ => seam::expect_seam(&mut app, x),
            };
            match outcome {
                Ok(seam::Outcome::Done(m)) => {
                    report.lines.push(format!("step {n:>3} {label}: ok ({m})"));
                }
                Ok(seam::Outcome::Failed(m)) => {
                    report.failures += 1;
                    report.lines.push(format!("step {n:>3} {label}: FAIL {m}"));
                }
                Err(m) => {
                    pending = Some((n, m.clone()));
                    report.lines.push(format!("step {n:>3} {label}: error {m}"));
                }
            }
            continue;
        }
        let (edit, note) = match prepare(step, dir) {
            Ok(e) => e,
            Err(m) => {
                pending = Some((n, m.clone()));
                report
                    .lines
                    .push(format!("step {n:>3} {}: error {m}", short(step)));
                continue;
            }
        };
        let label = edit.label();
        send(&mut app, edit);
        app.update();
        let w = app.world();
        let log = w.resource::<EditLog>();
        let stats = &w.resource::<Stats>().last;
        let errors: Vec<&EditError> = log
            .entries
            .iter()
            .filter_map(|e| e.as_ref().err())
            .collect();
        if let Some(e) = errors.first() {
            pending = Some((n, e.to_string()));
            report.lines.push(format!("step {n:>3} {label}: error {e}"));
        } else {
            report.lines.push(format!(
                "step {n:>3} {label}: ok ({}re-blended {}, re-integrated {}{}, {:.0} µs{})",
                note.map(|m| m + "; ").unwrap_or_default(),
                stats.tangents_reblended,
                stats.streamlines_reintegrated,
                if stats.streamlines_replaced > 0 {
                    format!(", {} placed again", stats.streamlines_replaced)
                } else {
                    String::new()
                },
                stats.us_total(),
                if stats.full_rebuild {
                    ", full rebuild"
                } else {
                    ""
                }
            ));
        }
        warned = warn_new(&app, n, &warned, &mut report);
    }
    if let Some((at, err)) = pending {
        report.failures += 1;
        report
            .lines
            .push(format!("step {at:>3}: FAIL unexpected error: {err}"));
    }
    report
}

/// Adds a `warning:` line for each build warning ([`BuildWarnings`]) of
/// `app` after step `n` that `before` did not have; returns them all.
fn warn_new(app: &App, n: usize, before: &[String], report: &mut PlayReport) -> Vec<String> {
    let now = &app.world().resource::<BuildWarnings>().lines;
    for w in now.iter().filter(|w| !before.contains(w)) {
        report.lines.push(format!("step {n:>3} warning: {w}"));
    }
    now.clone()
}

fn short(step: &Step) -> String {
    let s = format!("{step:?}");
    let head: String = s.chars().take(60).collect();
    if s.chars().count() > 60 {
        head + "…"
    } else {
        head
    }
}

fn resolve(dir: &Path, p: &str) -> PathBuf {
    dir.join(p)
}

/// An output path of a script, its folder created: inside the script's
/// folder, links resolved ([`crate::scene::edits::script::output::output_path`], [`crate::scene::edits::script::output::confine`]).
fn output(dir: &Path, p: &str) -> Result<PathBuf, String> {
    let path = crate::scene::edits::script::output::output_path(dir, p)?;
    crate::scene::edits::script::output::confine(dir, &path)?;
    Ok(path)
}

/// The edit a step sends: file names resolved against the script's folder
/// `dir` (outputs confined to it), a fine-tuning function checked, a `Fit`
/// step's design fitted ([`fit::fitted`]), any other edit as it is.
pub(crate) fn to_edit(step: &Step, dir: &Path) -> Result<Edit, String> {
    prepare(step, dir).map(|(e, _)| e)
}

/// [`to_edit`], with what the step's line adds when it holds (a fit's
/// figures).
fn prepare(step: &Step, dir: &Path) -> Result<(Edit, Option<String>), String> {
    if let Step::Fit(f) = step {
        let (edit, note) = fit::fitted(f, dir)?;
        return Ok((edit, Some(note)));
    }
    let edit = match step {
        Step::Load(p) => match p.strip_prefix("builtin:") {
            Some(name) => Edit::Replace(Box::new(builtin::scene(name).map_err(|e| e.to_string())?)),
            None => Edit::Load(resolve(dir, p)),
        },
        Step::Save(p) => Edit::Save(output(dir, p)?),
        Step::Export(p) => Edit::Export(output(dir, p)?),
        Step::SetTuning(t) => Edit::SetTuning(t.as_ref().map(|t| t.to_kernel()).transpose()?),
        Step::Edit(e) => e.clone(),
        Step::Fit(_) | Step::Expect(_) => return Err("not an edit".into()),
    };
    Ok((edit, None))
}
