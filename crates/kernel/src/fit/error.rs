//! Why a reference cannot be fitted, each with what to do (`docs/math.md §12`).

use crate::error::KernelError;
use std::fmt;

/// Everything that stops the fit of a reference. Parameters are named in
/// the reference's own `u` and `v`, whichever way the streamlines run.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ReferenceFitError {
    /// A NaN or infinite number in the input.
    NonFinite {
        /// What holds it.
        what: &'static str,
    },
    /// A parameter domain that is empty or not finite.
    EmptyDomain {
        /// `u` or `v`.
        direction: char,
    },
    /// A tolerance that is not a positive finite number.
    BadTolerance {
        /// The value given (or the absolute one it gave).
        value: f64,
    },
    /// An option outside its range.
    BadOption {
        /// Which option.
        what: &'static str,
        /// The value given.
        value: String,
        /// What is accepted.
        accepted: &'static str,
    },
    /// A point where the derivative along the streamlines vanishes, so the
    /// streamlines have no direction there.
    Pole {
        /// Where, in the reference's parameters.
        u: f64,
        /// Where, in the reference's parameters.
        v: f64,
        /// The streamlines' direction (`u` or `v`).
        along: char,
    },
    /// A row (an iso-curve along the streamlines) of zero length.
    ZeroLengthRow {
        /// The iso-curve, e.g. `v = 0`.
        edge: String,
        /// The streamlines' direction.
        along: char,
    },
    /// The initial curve (the iso-curve through the anchor) has zero length.
    ZeroLengthInitial {
        /// The iso-curve, e.g. `u = 0`.
        edge: String,
    },
    /// The surface closes on itself in the streamline direction.
    Closed {
        /// The closed direction (`u` or `v`).
        along: char,
    },
    /// The design could not be built.
    Build(KernelError),
    /// The caller's progress hook asked to stop.
    Cancelled,
}

fn other(c: char) -> char {
    if c == 'u' { 'v' } else { 'u' }
}

impl fmt::Display for ReferenceFitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReferenceFitError::NonFinite { what } => write!(
                f,
                "the reference has a non-finite {what}; the surface is damaged: re-export it or choose another face"
            ),
            ReferenceFitError::EmptyDomain { direction } => write!(
                f,
                "the reference's parameter range in {direction} is empty or not finite; the face is degenerate: choose another face"
            ),
            ReferenceFitError::BadTolerance { value } => write!(
                f,
                "fit tolerance {value} is not a positive finite number; give a relative one such as 1e-4 of the bounding box's diagonal (the default) or an absolute distance in metres"
            ),
            ReferenceFitError::BadOption {
                what,
                value,
                accepted,
            } => write!(
                f,
                "fit option {what} = {value} is not accepted; use {accepted}"
            ),
            ReferenceFitError::Pole { u, v, along } => write!(
                f,
                "the reference has a pole at u = {u}, v = {v}: its derivative along {along} vanishes there, so a streamline along {along} has no direction; run the streamlines along {}",
                other(*along)
            ),
            ReferenceFitError::ZeroLengthRow { edge, along } => write!(
                f,
                "the reference's edge {edge} has zero length, so its streamline along {along} would be a point (a degenerate, three-sided face); run the streamlines along {} or trim the face",
                other(*along)
            ),
            ReferenceFitError::ZeroLengthInitial { edge } => write!(
                f,
                "the initial curve, the reference's iso-curve {edge}, has zero length, so every streamline would start at one point; anchor the streamlines in the middle or run them the other way"
            ),
            ReferenceFitError::Closed { along } => write!(
                f,
                "the reference is closed in {along} (its edges {along} = min and {along} = max coincide), so streamlines along {along} would run round it; run the streamlines along {} or split the face in two",
                other(*along)
            ),
            ReferenceFitError::Build(e) => write!(f, "the fitted design could not be built: {e}"),
            ReferenceFitError::Cancelled => write!(f, "the fit was cancelled; nothing was changed"),
        }
    }
}

impl std::error::Error for ReferenceFitError {}

impl From<KernelError> for ReferenceFitError {
    fn from(e: KernelError) -> Self {
        ReferenceFitError::Build(e)
    }
}
