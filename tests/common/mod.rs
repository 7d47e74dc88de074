//! Helpers shared by the ECS test files.
#![allow(dead_code)]

pub mod built;
pub mod documents;
pub mod headless_editor;
pub mod shell_read;

use bevy::prelude::*;
use streamline_kernel::{DVec3, Grid};
use streamline_studio::ecs::{self, SurfaceData};
use streamline_studio::scene::Scene;

/// The surface's streamline points.
pub fn points(app: &App) -> Grid<DVec3> {
    app.world().resource::<SurfaceData>().points.clone()
}

/// The model's scene.
pub fn scene(app: &App) -> Scene {
    ecs::patch::scene(app.world())
}

/// The largest distance between two grids of the same shape.
pub fn max_diff(a: &Grid<DVec3>, b: &Grid<DVec3>) -> f64 {
    assert_eq!(
        (a.rows(), a.cols()),
        (b.rows(), b.cols()),
        "grid shapes differ"
    );
    a.data()
        .iter()
        .zip(b.data())
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max)
}

/// The test virtual environment's python (`scripts/venv.sh`:
/// `$STREAMLINE_VENV`, default `~/.cache/streamline-venv`), or a failure
/// that says how to make it; `holds` names the reader the test needs.
pub fn venv_python(holds: &str) -> std::path::PathBuf {
    use std::path::PathBuf;
    let venv = std::env::var_os("STREAMLINE_VENV")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(std::env::var_os("HOME").expect("HOME is set"))
                .join(".cache/streamline-venv")
        });
    let py = venv.join("bin/python");
    assert!(
        py.exists(),
        "the test virtual environment with {holds} is missing ({}); run `bash scripts/setup.sh --tests` (it makes it)",
        py.display()
    );
    py
}

/// Runs `tests/python/<script>` with OpenCascade in the test virtual
/// environment on `args`, and returns the JSON lines it printed, in order
/// (OpenCascade's own messages also go to stdout: the results are the lines
/// that start with `{`). Fails with OpenCascade's reason when the script
/// exits non-zero (it refused a file).
pub fn opencascade_lines(script: &str, args: &[&std::path::Path]) -> Vec<serde_json::Value> {
    let py = venv_python("OpenCascade (cadquery-ocp-novtk)");
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/python")
        .join(script);
    let out = std::process::Command::new(&py)
        .arg(&script)
        .args(args)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let head: String = stdout.chars().take(4000).collect();
    assert!(
        out.status.success(),
        "OpenCascade refused a file:\n{head}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
        .lines()
        .filter(|l| l.starts_with('{'))
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

/// [`opencascade_lines`] with a manifest of files to check (written as
/// `manifest.json` into `dir`): one result per entry, in its order.
pub fn opencascade_manifest(
    script: &str,
    dir: &std::path::Path,
    manifest: &[serde_json::Value],
) -> Vec<serde_json::Value> {
    let m = dir.join("manifest.json");
    std::fs::write(&m, serde_json::to_string(manifest).unwrap()).unwrap();
    let results = opencascade_lines(script, &[&m]);
    assert_eq!(
        results.len(),
        manifest.len(),
        "one result per file: {results:?}"
    );
    results
}
