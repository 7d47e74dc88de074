//! A non-rational tensor-product B-spline surface
//! `F(u, v) = Σ_k Σ_l N_k(u) M_l(v) P_{l,k}` (Piegl & Tiller §3.4) and its
//! evaluation, one point at a time or on a grid of parameters (separably:
//! first the `v` sums for a row of poles, then a curve in `u`).

use super::knots::{Basis, KnotVector};
use crate::grid::Grid;
use glam::DVec3;

/// A B-spline surface on `[0, 1]²`. `poles` has one row per `v` basis
/// function and one column per `u` basis function, like the point grid it
/// approximates (rows: streamlines, parameter `t`; columns: along `s`).
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineSurface {
    /// Knots in `u` (along the streamlines).
    pub knots_u: KnotVector,
    /// Knots in `v` (across the streamlines).
    pub knots_v: KnotVector,
    /// Control points, `knots_v.count()` rows × `knots_u.count()` columns.
    pub poles: Grid<DVec3>,
}

/// The basis at each of a list of parameters, computed once.
#[derive(Debug, Clone)]
pub(crate) struct BasisTable {
    pub rows: Vec<Basis>,
}

impl BasisTable {
    pub fn new(knots: &KnotVector, params: &[f64]) -> Self {
        BasisTable {
            rows: params.iter().map(|&u| knots.basis(u)).collect(),
        }
    }
}

impl BSplineSurface {
    /// Degrees `(p, q)` in `u` and `v`.
    pub fn degree(&self) -> (usize, usize) {
        (self.knots_u.degree(), self.knots_v.degree())
    }

    /// Pole counts `(in u, in v)`.
    pub fn pole_counts(&self) -> (usize, usize) {
        (self.knots_u.count(), self.knots_v.count())
    }

    /// `F(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> DVec3 {
        let (p, q) = self.degree();
        let (fu, nu) = self.knots_u.basis(u);
        let (fv, nv) = self.knots_v.basis(v);
        let mut sum = DVec3::ZERO;
        for (l, &b) in nv[..=q].iter().enumerate() {
            let row = &self.poles.row(fv + l)[fu..=fu + p];
            let mut c = DVec3::ZERO;
            for (pt, &a) in row.iter().zip(&nu[..=p]) {
                c += *pt * a;
            }
            sum += c * b;
        }
        sum
    }

    /// The poles of the `u` curve `F(·, v)` into `out`.
    pub(crate) fn curve_at_into(&self, v: f64, out: &mut Vec<DVec3>) {
        let q = self.knots_v.degree();
        let (fv, nv) = self.knots_v.basis(v);
        out.clear();
        out.resize(self.poles.cols(), DVec3::ZERO);
        for (l, &b) in nv[..=q].iter().enumerate() {
            for (o, pt) in out.iter_mut().zip(self.poles.row(fv + l)) {
                *o += *pt * b;
            }
        }
    }
}

/// A point of the curve with poles `curve` from a precomputed basis.
#[inline]
pub(crate) fn curve_point(curve: &[DVec3], b: &Basis, p: usize) -> DVec3 {
    let (first, n) = b;
    let mut c = DVec3::ZERO;
    for (pt, &a) in curve[*first..=*first + p].iter().zip(&n[..=p]) {
        c += *pt * a;
    }
    c
}
