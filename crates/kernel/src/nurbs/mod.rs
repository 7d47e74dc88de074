//! The streamline surface as a B-spline surface, for CAD exchange (docs/math.md §10,
//! `docs/math.md §10`): clamped knot vectors and their basis ([`knots`]), a
//! non-rational tensor-product surface ([`surface`]), the separable
//! least-squares fit with adaptive knots (`fit`) and the deviation between
//! the streamline surface and its fit (`deviation`).

mod banded;
pub mod curve;
pub mod deviation;
pub mod error;
pub mod fit;
pub mod knots;
mod lsq;
pub mod rational;
pub mod samples;
mod seam_hold;
mod seam_params;
pub mod shell;
pub mod surface;

pub use deviation::{Deviation, deviation, deviation_field, deviation_within};
pub use error::{Direction, FitError};
pub use fit::{Fit, FitOptions, FitReport, Tolerance, fit, fit_design, fit_knots};
pub use knots::KnotVector;
pub use samples::Samples;
pub use shell::{
    PatchGrid, SeamSpec, ShellError, ShellFace, ShellFit, ShellSeam, face_deviation, face_rows,
    fit_alone, fit_shell,
};
pub use surface::BSplineSurface;
