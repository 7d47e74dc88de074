//! What can be wrong with a fit, each with what to do.

use crate::error::KernelError;
use crate::levels::surface::SurfaceScheme;
use std::fmt;

/// A parameter direction of the surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Along the streamlines (`s`, the grid's columns).
    U,
    /// Across the streamlines (`t`, the grid's rows).
    V,
}

impl fmt::Display for Direction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Direction::U => "u (along the streamlines)",
            Direction::V => "v (across the streamlines)",
        })
    }
}

/// Everything that can stop a fit.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum FitError {
    /// A tolerance that is not a positive finite number.
    BadTolerance { value: f64 },
    /// A degree outside `2 ..= 5`.
    BadDegree { direction: Direction, degree: usize },
    /// The tolerance would need more poles than the grid has points (or a
    /// span with too few points to split).
    TooFewPoints {
        direction: Direction,
        points: usize,
        tolerance: f64,
        reached: f64,
    },
    /// [`FitError::TooFewPoints`] at the deepest depth an exporter samples
    /// (it tries deeper grids first).
    TooFewPointsAtDeepest {
        direction: Direction,
        points: usize,
        tolerance: f64,
        reached: f64,
        /// The depth of that grid.
        depth: u32,
        /// For a patch on an earlier patch's edge, the approximating scheme
        /// (Catmull–Clark or Doo–Sabin) down its chain of starts: where the
        /// patch starts moves between depths, and its check grid is measured
        /// from there, but a turn of the direction it leaves in is not
        /// (docs/math.md §11.5, "A start that moves"); it halves per depth,
        /// so no pole is missing and the message says which tolerance does
        /// export.
        moving: Option<SurfaceScheme>,
    },
    /// Parameters that do not rise strictly from 0 to 1 (or sizes that do not match).
    BadSamples { problem: String },
    /// Building the design at the export depth (or one finer) failed.
    Build(KernelError),
}

impl fmt::Display for FitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FitError::BadTolerance { value } => write!(
                f,
                "fit tolerance {value} is not a positive finite number; give one such as 1e-4 of the bounding box's diagonal (the default) or an absolute distance in scene units"
            ),
            FitError::BadDegree { direction, degree } => write!(
                f,
                "B-spline degree {degree} in {direction} is outside 2 to 5; use 3 (the default, C2 like the streamlines)"
            ),
            FitError::TooFewPoints {
                direction,
                points,
                tolerance,
                reached,
            } => write!(
                f,
                "fitting within {tolerance:e} needs more control points in {direction} than the grid's {points} points (the closest it came was {reached:e}); loosen the tolerance or export deeper"
            ),
            FitError::TooFewPointsAtDeepest {
                tolerance,
                reached,
                depth,
                moving: Some(scheme),
                ..
            } => write!(
                f,
                "this patch starts on the edge of an earlier patch, and on the {} scheme the way it leaves that edge turns between depths by an angle that only halves per depth, as the rows shorten when sampled deeper (docs/math.md §11.5, \"A start that moves\"): at depth {depth}, the deepest an export samples, its points one depth finer, measured from where it starts, are still {reached:.3e} from the closest fit, over the tolerance {tolerance:.3e}; export with a tolerance of at least {:.1e}, or choose the Kobbelt scheme for both patches, whose edges stay put",
                scheme.title(),
                round_up(*reached)
            ),
            FitError::TooFewPointsAtDeepest {
                direction,
                points,
                tolerance,
                reached,
                depth,
                moving: None,
            } => write!(
                f,
                "fitting within {tolerance:e} needs more control points in {direction} than even depth {depth}'s {points} points, the deepest an export samples (the closest it came was {reached:e}); loosen the tolerance"
            ),
            FitError::BadSamples { problem } => write!(f, "fit input: {problem}"),
            FitError::Build(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for FitError {}

/// `x` rounded up to two significant digits (a tolerance to suggest that is
/// not below what was reached).
fn round_up(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    let unit = 10f64.powf(x.log10().floor() - 1.0);
    let up = (x / unit).ceil() * unit;
    // the printed two digits (`{:.1e}`) are never below `x`
    match format!("{up:.1e}").parse::<f64>() {
        Ok(v) if v >= x => v,
        _ => up + unit,
    }
}

impl From<KernelError> for FitError {
    fn from(e: KernelError) -> Self {
        FitError::Build(e)
    }
}
