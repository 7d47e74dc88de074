//! A (possibly rational) tensor-product B-spline surface as CAD files carry it
//! (STEP `B_SPLINE_SURFACE_WITH_KNOTS` with or without
//! `RATIONAL_B_SPLINE_SURFACE`, IGES entity 128): any degree from 1 to
//! [`MAX_DEGREE`], any non-decreasing knots (clamped or not, multiplicities
//! expanded), weights optional. It is the reference a streamline design is
//! fitted to (`docs/math.md §12`), evaluated by the rational quotient rule
//! `S = A/W`, `S_u = (A_u − W_u S)/W` (Piegl & Tiller, *The NURBS Book*,
//! Eq. 4.8), with the homogeneous sums `A = Σ N_k M_l w_{lk} P_{lk}`,
//! `W = Σ N_k M_l w_{lk}`.
//!
//! * `error`: every inconsistency of the data ([`NurbsError`]);
//! * `construct`: a surface from CAD data or from the §10 export, and the
//!   same surface exchanged or scaled;
//! * `eval`: the basis functions, points, first derivatives and closedness;
//! * `area_bounds`: the area and the boxes, and the Gauss–Legendre rule.

mod area_bounds;
mod construct;
mod error;
mod eval;
#[cfg(test)]
mod tests;

pub use area_bounds::{WORK_BUDGET, gauss_legendre};
pub use error::NurbsError;

use crate::grid::Grid;
use glam::DVec3;

/// The largest degree accepted in either direction (STEP and IGES allow
/// more in principle; CAD systems write at most 25, and a file with more is
/// refused with [`NurbsError::BadDegree`]).
pub const MAX_DEGREE: usize = 25;

/// A (possibly rational) B-spline surface as CAD files carry it.
///
/// `poles` has one row per `v` basis function and one column per `u` basis
/// function (rows index `v`, columns index `u`), like
/// [`BSplineSurface::poles`](crate::nurbs::surface::BSplineSurface::poles).
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface {
    degree_u: usize,
    degree_v: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    poles: Grid<DVec3>,
    weights: Option<Grid<f64>>,
    /// Homogeneous poles `(w P, w)`, row-major like `poles`.
    hom: Vec<[f64; 4]>,
}

impl NurbsSurface {
    /// Degrees `(in u, in v)`.
    pub fn degrees(&self) -> (usize, usize) {
        (self.degree_u, self.degree_v)
    }

    /// Pole counts `(in u, in v)` = (columns, rows) of [`Self::poles`].
    pub fn pole_counts(&self) -> (usize, usize) {
        (self.poles.cols(), self.poles.rows())
    }

    /// Whether the surface carries weights.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// The full `u` knot vector.
    pub fn knots_u(&self) -> &[f64] {
        &self.knots_u
    }

    /// The full `v` knot vector.
    pub fn knots_v(&self) -> &[f64] {
        &self.knots_v
    }

    /// The poles, rows index `v`, columns index `u`.
    pub fn poles(&self) -> &Grid<DVec3> {
        &self.poles
    }

    /// The weights, when rational.
    pub fn weights(&self) -> Option<&Grid<f64>> {
        self.weights.as_ref()
    }

    /// The parameter domain `([u0, u1], [v0, v1])`: `[k_p, k_n]` in each
    /// direction, `n` the pole count.
    pub fn domain(&self) -> ([f64; 2], [f64; 2]) {
        let (nu, nv) = self.pole_counts();
        (
            [self.knots_u[self.degree_u], self.knots_u[nu]],
            [self.knots_v[self.degree_v], self.knots_v[nv]],
        )
    }

    /// The non-empty knot spans in `u` and in `v`, each as `[a, b]`.
    pub fn spans(&self) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
        let (nu, nv) = self.pole_counts();
        let f = |k: &[f64], p: usize, n: usize| -> Vec<[f64; 2]> {
            (p..n)
                .filter(|&i| k[i + 1] > k[i])
                .map(|i| [k[i], k[i + 1]])
                .collect()
        };
        (
            f(&self.knots_u, self.degree_u, nu),
            f(&self.knots_v, self.degree_v, nv),
        )
    }
}
