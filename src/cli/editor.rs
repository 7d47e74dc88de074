//! Opening the editor from the command line, and `screenshot`.

use super::input::CliError;
use crate::editor::{self, EditorOptions, ScreenshotRequest};
use clap::Args;
use std::path::PathBuf;
use streamline_kernel::{Design, presets};

/// The built-in scenes by name.
pub fn builtin(name: &str) -> Result<Design, CliError> {
    Ok(match name {
        "car1" => presets::car1(),
        "car2" => presets::car2(),
        "qi-down" => presets::qi_demo(0),
        "qi-side" => presets::qi_demo(1),
        "qi-up" => presets::qi_demo(2),
        "minimal" => presets::minimal(),
        other => {
            return Err(CliError::Usage(format!(
                "unknown built-in scene '{other}'; choose car1, car2, qi-down, qi-side, qi-up or minimal"
            )));
        }
    })
}

/// Opens the editor on a built-in scene.
pub fn open(scene: &str) -> Result<(), CliError> {
    let design = builtin(scene)?;
    editor::run(EditorOptions {
        design,
        name: scene.to_string(),
        depth: 3,
        size: (1280, 800),
        screenshot: None,
    })
    .map_err(|e| CliError::Usage(e.to_string()))
}

/// Arguments of `screenshot`.
#[derive(Debug, Args)]
pub struct ScreenshotArgs {
    /// The built-in scene to show.
    #[arg(long, default_value = "car1")]
    scene: String,
    /// Where to write the PNG.
    #[arg(long)]
    out: PathBuf,
    /// Window size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x800")]
    size: String,
    /// Display depth.
    #[arg(long, default_value_t = 3)]
    depth: u32,
}

/// `screenshot`.
pub fn screenshot(a: ScreenshotArgs) -> Result<(), CliError> {
    let design = builtin(&a.scene)?;
    let size = a
        .size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)))
        .filter(|&(w, h)| (64..=8192).contains(&w) && (64..=8192).contains(&h))
        .ok_or_else(|| {
            CliError::Usage(format!(
                "--size '{}' is not WIDTHxHEIGHT with sides 64 to 8192, e.g. 1280x800",
                a.size
            ))
        })?;
    if a.out.extension().and_then(|e| e.to_str()) != Some("png") {
        return Err(CliError::Usage(format!(
            "--out {}: the screenshot is a PNG; give a path ending in .png",
            a.out.display()
        )));
    }
    let _ = std::fs::remove_file(&a.out);
    let req = ScreenshotRequest {
        path: a.out.clone(),
        frames: 30,
    };
    editor::run(EditorOptions {
        design,
        name: a.scene.clone(),
        depth: a.depth,
        size,
        screenshot: Some(req),
    })
    .map_err(|e| CliError::Usage(e.to_string()))?;
    if !a.out.is_file() {
        return Err(CliError::Usage(format!(
            "no screenshot was written to {}; see the log above",
            a.out.display()
        )));
    }
    Ok(())
}
