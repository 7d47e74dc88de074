//! The scene's surface as a B-spline surface (docs/math.md §10):
//! the points of the scene at a depth, as the editor shows them (details,
//! fine tuning, interpolated tangents included, both halves of a mirrored
//! design as one surface, docs/math.md §9), with the parameters the kernel's
//! fit gives them, and the fit checked one depth finer.

use std::time::Instant;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::incremental::{place_rows_tuned, reference_levels};
use streamline_kernel::nurbs::{Fit, FitError, FitOptions, Samples, fit};

use super::model::Scene;

/// The scene's streamline points at `depth` with their fit parameters; a
/// mirrored scene's are the doubled design's (one surface over both halves).
pub fn samples(scene: &Scene, depth: u32) -> Result<Samples, FitError> {
    let design = scene.shown_design()?;
    let levels = reference_levels(&design, &scene.details, depth)?;
    let level = levels.last().expect("level 0 at least");
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols() + 1);
    let mut data = Vec::with_capacity(rows * cols);
    place_rows_tuned(
        design.initial(),
        &level.tangents,
        &level.params,
        scene.tuning.as_ref(),
        &mut data,
    );
    Samples::from_level(level, Grid::new(rows, cols, data)?)
}

/// A fit of a scene with its time.
#[derive(Debug, Clone)]
pub struct SceneFit {
    /// The surface and its figures.
    pub fit: Fit,
    /// Seconds the fit took (the builds at `depth` and `depth + 1` not counted).
    pub seconds: f64,
    /// The depth it was fitted at.
    pub depth: u32,
}

/// Fits the scene's surface at `depth` (checked at `depth + 1`).
pub fn fit_scene(scene: &Scene, depth: u32, opts: &FitOptions) -> Result<SceneFit, FitError> {
    let data = samples(scene, depth)?;
    let check = samples(scene, depth + 1)?;
    let start = Instant::now();
    let fit = fit(&data, &check, opts)?;
    Ok(SceneFit {
        fit,
        seconds: start.elapsed().as_secs_f64(),
        depth,
    })
}
