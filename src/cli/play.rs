//! `play SCRIPT.ron`: scripted playback through the ECS, headless.

use super::input::{CliError, scene_arg};
use crate::ecs::playback;
use crate::scene::edits::script::Script;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `play`.
#[derive(Debug, Args)]
pub struct PlayArgs {
    /// The script (RON list of steps); its relative paths are resolved from its folder.
    script: PathBuf,
    /// The scene to start from (a .ron file or a built-in name) before the script's own Load steps.
    #[arg(long, default_value = "car1")]
    scene: String,
}

/// Runs a script; exit 0 only if every step held.
pub fn play(a: PlayArgs) -> Result<(), CliError> {
    let script = Script::load(&a.script)?;
    let scene = scene_arg(&a.scene)?;
    let dir = a
        .script
        .parent()
        // a bare file name's parent is the empty path: the current folder
        .filter(|p| !p.as_os_str().is_empty())
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("."));
    let report = playback::play(&script, &dir, scene);
    for l in &report.lines {
        println!("{l}");
    }
    if report.passed() {
        println!(
            "{}: {} steps, all passed",
            a.script.display(),
            script.steps.len()
        );
        Ok(())
    } else {
        Err(CliError::Failed(format!(
            "{}: {} of {} steps failed",
            a.script.display(),
            report.failures,
            script.steps.len()
        )))
    }
}
