//! Helpers shared by the ECS test files.
#![allow(dead_code)]

pub mod documents;
pub mod headless_editor;

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
