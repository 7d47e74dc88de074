//! Fine tuning a streamline surface (SPEC §6): one tensor function `α(u, v)`
//! over the surface (`u` along each streamline, `v` across the rows), applied
//! to each streamline as its restriction `α(·, v_row)`, with the constraint
//! met streamline by streamline ([`super::fine_tune_into`]). A constraint on
//! every streamline (3 or 6 equations each) cannot in general be met by the
//! few tensor values (the paper's 3×3 or 3×4), so each streamline's own
//! values `dᵢ = Σ_j c_{j,i} M_j(v)` take the least-squares change instead.

use super::constraint::Constraint;
use crate::finetune::bspline::{BSpline, TensorBSpline};
use crate::grid::Grid;

/// The fine-tuning of a surface: the function and the constraint.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceTuning {
    /// `α(u, v)`: rows across the streamlines, columns along them.
    pub function: TensorBSpline,
    /// What every streamline keeps.
    pub constraint: Constraint,
}

impl SurfaceTuning {
    /// The paper's usual start: quadratic × quadratic, 3×3 values of 1 (changes nothing).
    pub fn identity() -> Self {
        SurfaceTuning {
            function: TensorBSpline::new(2, 2, Grid::filled(3, 3, 1.0)).expect("3×3 quadratic"),
            constraint: Constraint::Free,
        }
    }

    /// `v ∈ [0, 1]` of a row with parameter `t`, on rows spanning `[t_min, t_max]`.
    pub fn row_v(t: f64, t_min: f64, t_max: f64) -> f64 {
        if t_max > t_min {
            ((t - t_min) / (t_max - t_min)).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The function along the streamline at `v`.
    pub fn row_function(&self, v: f64) -> BSpline {
        self.function.along_at(v)
    }
}
