//! Fine tuning (paper 003; docs/math.md §6): reshape a curve or a surface without
//! touching its tangents, by scaling its derivative with a smooth B-spline
//! scalar function `α`:
//!
//! `p(s) = p(s_a) + ∫_{s_a}^{s} α(s) t(s) ds`.
//!
//! - [`streamline`]: one streamline of Eq. 65 (whose derivative is the
//!   piecewise-constant tangent), with `α(u)`, `u = (s − s₀)/(s_n − s₀)`;
//!   a surface uses the tensor function `α(u, v)` of [`crate::finetune::bspline::TensorBSpline`],
//!   each streamline the restriction to its `v`.
//! - [`chaikin`]: a closed Chaikin (uniform quadratic B-spline) curve times a
//!   linear periodic function: a cubic B-spline with double knots (003 Eqs. 9–12).
//! - [`constraint`]: the end points and closedness are linear in the control
//!   values, so a [`Constraint`] is met exactly by the least-squares change
//!   to the designer's values.

pub mod bspline;
pub mod chaikin;
pub mod constraint;
pub mod streamline;
pub mod surface;

pub use constraint::{Constraint, nearest_meeting};
pub use streamline::{FineTuned, fine_tune_into};
pub use surface::{SurfaceRows, SurfaceTuning, fine_tune_rows_into};
