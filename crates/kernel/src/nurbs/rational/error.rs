//! Everything that can be wrong with the data of a
//! [`NurbsSurface`](super::NurbsSurface) (`docs/math.md §12`), each error
//! with what to do about it.

use super::MAX_DEGREE;
use std::fmt;

/// Everything that can be wrong with the data of a NURBS surface, each with
/// what to do about it.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum NurbsError {
    /// No poles at all (or a knot vector too short to hold one span).
    Empty { what: &'static str },
    /// A degree of 0 or above [`MAX_DEGREE`].
    BadDegree { direction: char, degree: usize },
    /// The number of poles in a direction is not `knots − degree − 1`.
    PoleCountMismatch {
        direction: char,
        poles: usize,
        knots: usize,
        degree: usize,
    },
    /// The weight grid's shape differs from the pole grid's.
    WeightShape {
        rows: usize,
        cols: usize,
        pole_rows: usize,
        pole_cols: usize,
    },
    /// Knot `index` is smaller than the one before it.
    KnotsDecrease { direction: char, index: usize },
    /// A knot repeated more than `degree + 1` times.
    KnotMultiplicity {
        direction: char,
        index: usize,
        multiplicity: usize,
        degree: usize,
    },
    /// The parameter domain `[k_p, k_{n}]` is empty.
    EmptyDomain { direction: char },
    /// A NaN or infinite number.
    NonFinite {
        what: &'static str,
        row: usize,
        col: usize,
    },
    /// A weight that is zero or negative.
    NonPositiveWeight { row: usize, col: usize, weight: f64 },
    /// A scale factor that is not a positive finite number.
    BadScale { factor: f64 },
}

impl fmt::Display for NurbsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NurbsError::Empty { what } => write!(
                f,
                "the NURBS surface has no {what}; the face carries no surface: choose another face or re-export it from the CAD system"
            ),
            NurbsError::BadDegree { direction, degree } => write!(
                f,
                "NURBS degree {degree} in {direction} is outside 1 to {MAX_DEGREE}; re-export the face with a lower degree (rebuild it in the CAD system)"
            ),
            NurbsError::PoleCountMismatch {
                direction,
                poles,
                knots,
                degree,
            } => write!(
                f,
                "the NURBS surface has {poles} poles in {direction} but {knots} knots of degree {degree} need {} (knots − degree − 1); the file is inconsistent: check that the knot multiplicities were expanded, or re-export the face",
                knots.saturating_sub(degree + 1)
            ),
            NurbsError::WeightShape {
                rows,
                cols,
                pole_rows,
                pole_cols,
            } => write!(
                f,
                "the NURBS weights form a {rows} × {cols} grid but the poles a {pole_rows} × {pole_cols} one; give one weight per pole, or none for a non-rational surface"
            ),
            NurbsError::KnotsDecrease { direction, index } => write!(
                f,
                "the {direction} knots decrease at knot {index}; knots must be non-decreasing: the file is damaged or the knots were read in the wrong order"
            ),
            NurbsError::KnotMultiplicity {
                direction,
                index,
                multiplicity,
                degree,
            } => write!(
                f,
                "the {direction} knot at index {index} is repeated {multiplicity} times, more than degree + 1 = {}; remove the extra copies or re-export the face",
                degree + 1
            ),
            NurbsError::EmptyDomain { direction } => write!(
                f,
                "the NURBS surface's parameter range in {direction} is empty (its knots from index degree to the last pole's are all equal); the face is degenerate: choose another face"
            ),
            NurbsError::NonFinite { what, row, col } => write!(
                f,
                "the NURBS surface has a non-finite {what} at ({row}, {col}); the file is damaged: re-export the face"
            ),
            NurbsError::NonPositiveWeight { row, col, weight } => write!(
                f,
                "the NURBS weight at row {row}, column {col} is {weight}, not positive; weights must be > 0: re-export the face (or divide all weights by a negative common factor)"
            ),
            NurbsError::BadScale { factor } => write!(
                f,
                "scale factor {factor} is not a positive finite number; use the ratio of the file's length unit to metres (0.001 for millimetres)"
            ),
        }
    }
}

impl std::error::Error for NurbsError {}
