//! Opening the editor from the command line, and `screenshot`.

use super::input::{CliError, document_arg};
use crate::editor::{self, EditorDirs, EditorOptions, PanelName, ScreenshotRequest, SurfaceMode};
use crate::scene::Document;
use clap::Args;
use std::path::PathBuf;

/// A scene argument: a `.ron` file of any version (with its path) or a
/// built-in scene's name. Returns the document, of one patch or several
/// (docs/math.md §11), and the path.
fn open_document(arg: &str) -> Result<(Document, Option<PathBuf>), CliError> {
    let document = document_arg(arg)?;
    let p = PathBuf::from(arg);
    let path = (arg.ends_with(".ron") || p.is_file()).then_some(p);
    Ok((document, path))
}

/// Opens the editor on a scene file or a built-in scene, with `msaa` samples
/// in the 3D views (`None`: chosen for the graphics adapter).
pub fn open(scene: &str, msaa: Option<u32>) -> Result<(), CliError> {
    let (document, path) = open_document(scene)?;
    editor::run(EditorOptions {
        document,
        path,
        size: (1280, 800),
        screenshot: None,
        dirs: EditorDirs::from_env(),
        msaa,
    })
    .map_err(|e| CliError::Usage(e.to_string()))
}

/// Arguments of `screenshot`.
#[derive(Debug, Args)]
pub struct ScreenshotArgs {
    /// A scene file (.ron) or a built-in scene's name.
    #[arg(default_value = "car1")]
    scene: String,
    /// The same, as an option (kept for older scripts).
    #[arg(long = "scene", hide = true)]
    scene_opt: Option<String>,
    /// Where to write the PNG.
    #[arg(long)]
    out: PathBuf,
    /// Window size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x800")]
    size: String,
    /// Open only this panel section: file, patches, subdivision, structure, selection, display, tuning, analysis, mesh, stats, initial, curvature.
    #[arg(long)]
    panel: Option<String>,
    /// Surface display: shaded, gaussian, mean, zebra, deviation (from the fitted B-spline surface), reference (distance to the design's reference).
    #[arg(long)]
    analysis: Option<String>,
    /// Draw curvature combs.
    #[arg(long)]
    comb: bool,
    /// Select handle ROW,COL of the edit depth, or iK: the initial curve's tangent K.
    #[arg(long)]
    select: Option<String>,
    /// For GUI tests: write a JSON report here on exit.
    #[arg(long, hide = true)]
    report: Option<PathBuf>,
    /// Open this triangle mesh (OBJ) in mesh mode: its interpolating Loop surface.
    #[arg(long)]
    mesh: Option<PathBuf>,
    /// The Loop surface's boundary rules for --mesh: paper (002), edge-only or
    /// edge-and-corner (OpenSubdiv's; USD's default) [default: edge-and-corner].
    #[arg(long, value_enum)]
    boundary: Option<super::interpolate::BoundaryArg>,
    /// Start running this script (File ▸ Run script); the picture shows its progress.
    #[arg(long)]
    script: Option<PathBuf>,
    /// Multisample anti-aliasing of the 3D views: 1 (off), 2, 4 or 8, or the
    /// nearest the adapter offers [default: off on a software renderer, 4 on a
    /// GPU, as the editor].
    #[arg(long, value_parser = editor::view::antialias::parse_samples)]
    msaa: Option<u32>,
}

/// `screenshot`.
pub fn screenshot(a: ScreenshotArgs) -> Result<(), CliError> {
    let arg = a.scene_opt.clone().unwrap_or(a.scene.clone());
    let (document, path) = open_document(&arg)?;
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
    let panel = match &a.panel {
        None => None,
        Some(p) => Some(PanelName::parse(p).ok_or_else(|| {
            let names: Vec<&str> = PanelName::ALL.iter().map(|n| n.name()).collect();
            CliError::Usage(format!("--panel '{p}': choose one of {}", names.join(", ")))
        })?),
    };
    let analysis = match &a.analysis {
        None => None,
        Some(m) => Some(SurfaceMode::parse(m).ok_or_else(|| {
            CliError::Usage(format!(
                "--analysis '{m}': choose shaded, gaussian, mean, zebra, deviation or reference"
            ))
        })?),
    };
    let select_initial = match a.select.as_deref().and_then(|s| s.strip_prefix('i')) {
        None => None,
        Some(k) => Some(k.trim().parse::<usize>().map_err(|_| {
            CliError::Usage(format!(
                "--select 'i{k}': give iK for the initial curve's tangent K, e.g. i1"
            ))
        })?),
    };
    let select = match &a.select {
        None => None,
        Some(_) if select_initial.is_some() => None,
        Some(s) => Some(
            s.split_once(',')
                .and_then(|(r, c)| Some((r.trim().parse().ok()?, c.trim().parse().ok()?)))
                .ok_or_else(|| {
                    CliError::Usage(format!("--select '{s}': give ROW,COL, e.g. 3,4"))
                })?,
        ),
    };
    let _ = std::fs::remove_file(&a.out);
    let mut req = ScreenshotRequest::new(a.out.clone());
    req.panel = panel;
    req.mesh = a.mesh.clone();
    req.mesh_boundary = a.boundary.map(Into::into);
    req.script = a.script.clone();
    req.analysis = analysis;
    req.comb = a.comb;
    req.select = select;
    req.select_initial = select_initial;
    req.report = a.report.clone();
    // a screenshot never touches the user's recent files or recovery
    let dirs = EditorDirs {
        home: std::env::temp_dir().join(format!("streamline-shot-{}", std::process::id())),
    };
    let home = dirs.home.clone();
    let r = editor::run(EditorOptions {
        document,
        path,
        size,
        screenshot: Some(req),
        dirs,
        msaa: a.msaa,
    });
    let _ = std::fs::remove_dir_all(home);
    r.map_err(|e| CliError::Usage(e.to_string()))?;
    if !a.out.is_file() {
        return Err(CliError::Usage(format!(
            "no screenshot was written to {}; see the log above",
            a.out.display()
        )));
    }
    Ok(())
}
