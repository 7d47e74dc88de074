//! The scene's surface as a B-spline surface (docs/math.md §10):
//! the points of the scene at a depth, as the editor shows them (details,
//! fine tuning, interpolated tangents included, both halves of a mirrored
//! design as one surface, docs/math.md §9), with the parameters the kernel's
//! fit gives them, and the fit checked one depth finer.

use std::time::Instant;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::incremental::{reference_levels, tuned_points};
use streamline_kernel::nurbs::{Fit, FitError, FitOptions, Samples, deviation_field, fit};

use super::model::Scene;

/// The scene's streamline points at `depth` with their fit parameters; a
/// mirrored scene's are the doubled design's (one surface over both halves).
pub fn samples(scene: &Scene, depth: u32) -> Result<Samples, FitError> {
    let design = scene.shown_design()?;
    let levels = reference_levels(&design, &scene.details, depth)?;
    let level = levels.last().expect("level 0 at least");
    let points = tuned_points(
        design.initial(),
        &level.tangents,
        &level.params,
        scene.tuning.as_ref(),
    );
    Samples::from_level(level, points)
}

/// The most points the check grid of an export may have: the fit at depth
/// `d` is checked at every point of depth `d + 1` (docs/math.md §10), and
/// the deepest export depth is the last whose check grid stays within this
/// (a 2049 × 1025 grid; the car's depth 6, whose check grid of 1025 × 641
/// points builds and measures in about a second on one core).
pub const MAX_CHECK_POINTS: usize = 1 << 21;

/// The deepest depth `fit_scene` samples `scene` at: the last whose check
/// grid (one depth finer) has at most [`MAX_CHECK_POINTS`] points and passes
/// the kernel's size limits.
pub fn max_fit_depth(scene: &Scene) -> u32 {
    let Ok(design) = scene.shown_design() else {
        return scene.display_depth;
    };
    let (rows, cols) = (design.net().rows(), design.net().cols());
    let mut depth = 0;
    while let Ok((r, c)) = design.scheme().check_depth(rows, cols, depth + 2) {
        if r.saturating_mul(c + 1) > MAX_CHECK_POINTS {
            break;
        }
        depth += 1;
    }
    depth
}

/// A fit of a scene with its time.
#[derive(Debug, Clone)]
pub struct SceneFit {
    /// The surface and its figures.
    pub fit: Fit,
    /// Seconds the fit took (the builds at `depth` and `depth + 1` not counted).
    pub seconds: f64,
    /// The depth it was fitted at: the first from the requested one whose
    /// points were enough for the tolerance.
    pub depth: u32,
}

/// Fits the scene's surface within the options' tolerance, sampled at
/// `depth` (checked at `depth + 1`) or, when the tolerance needs more
/// control points than that grid has points, as much deeper as it needs, up
/// to [`max_fit_depth`]: which sampling reaches the tolerance is the
/// exporter's business, not the designer's (the depth used is in
/// [`SceneFit::depth`]). Only when even the deepest grid is not enough is the
/// fit refused ([`FitError::TooFewPoints`] at that depth, whose message says
/// to loosen the tolerance).
pub fn fit_scene(scene: &Scene, depth: u32, opts: &FitOptions) -> Result<SceneFit, FitError> {
    let deepest = max_fit_depth(scene).max(depth);
    let mut depth = depth;
    let mut data = samples(scene, depth)?;
    let mut seconds = 0.0;
    loop {
        let check = samples(scene, depth + 1)?;
        let start = Instant::now();
        let result = fit(&data, &check, opts);
        seconds += start.elapsed().as_secs_f64();
        match result {
            Ok(fit) => {
                return Ok(SceneFit {
                    fit,
                    seconds,
                    depth,
                });
            }
            Err(FitError::TooFewPoints { .. }) if depth < deepest => {
                depth += 1;
                data = check;
            }
            Err(FitError::TooFewPoints {
                direction,
                points,
                tolerance,
                reached,
            }) => {
                return Err(FitError::TooFewPointsAtDeepest {
                    direction,
                    points,
                    tolerance,
                    reached,
                    depth,
                });
            }
            Err(e) => return Err(e),
        }
    }
}

/// The scene's fit at its display depth ([`fit_scene`], the face a
/// one-patch export writes) and the distance of each shown point to it
/// (the one-patch deviation map, docs/cad.md).
pub fn fit_shown(scene: &Scene, opts: &FitOptions) -> Result<(SceneFit, Grid<f64>), FitError> {
    let depth = scene.display_depth;
    let f = fit_scene(scene, depth, opts)?;
    let shown = samples(scene, depth)?;
    let field = deviation_field(&f.fit.surface, &shown);
    Ok((f, field))
}
