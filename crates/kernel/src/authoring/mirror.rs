//! Mirror symmetry (`docs/math.md §9`, Mirror symmetry).
//!
//! The plane `P` passes through the initial curve's point at `t₀` (row 0's
//! `t`) and is perpendicular to its tangent there; with `t₀ = 0`, the usual
//! case, that is the curve's start point and its first control tangent `c₀`
//! (the QI curve starts on `c₀`). `R` is the reflection in `P`. The design is
//! the half `t ≥ t₀` of a symmetric surface whose tangent field is the one
//! of the doubled net `R(row_{m−1}), …, R(row_1), row_0, row_1, …, row_{m−1}`
//! (`s` and `σ` copied, `t` reflected about `t₀` as `2t₀ − t_j`), so the
//! field is as smooth across the seam as the scheme makes it anywhere. Row 0
//! is the seam: its tangents are projected into `P`; the initial curve is the
//! design's own for `t ≥ t₀` and its reflection `R(C(2t₀ − t))` below. Blends
//! on the sphere commute with every isometry, reflections included, so the
//! doubled surface equals its reflection, and meets `P` at right angles
//! (`∂S/∂t ∥ c₀` on the seam): G2 across it, since a curve that crosses its
//! mirror plane at right angles continues into its reflection with equal curvature.
//!
//! Only the half is stored and edited; [`Design::mirrored`] is a pure
//! function of it, so turning the mirror off and on again gives back the same
//! surface bit for bit. [`Design::with_seam_in_plane`] writes the projection
//! into the half (what turning the mirror on does, one undo step); projecting
//! a tangent already in `P` (within [`SEAM_IN_PLANE`]) leaves it as it is,
//! so doing it twice changes nothing.

use crate::error::KernelError;
use crate::grid::Grid;
use crate::levels::design::Design;
use glam::DVec3;

pub use crate::plane::{MirrorPlane, SEAM_IN_PLANE, SEAM_MIN_SIN};

impl Design {
    /// The mirror plane `P` (module doc).
    pub fn mirror_plane(&self) -> MirrorPlane {
        let t0 = self.params.t[0];
        MirrorPlane {
            point: self.initial.point(t0),
            normal: self.initial.tangent(t0),
        }
    }

    /// Row 0 (the seam) projected into `P`; tangents already in it keep their bits.
    fn seam_row(&self, plane: &MirrorPlane) -> Result<Vec<DVec3>, KernelError> {
        self.net
            .row(0)
            .iter()
            .enumerate()
            .map(|(c, &v)| plane.project_dir(v, c))
            .collect()
    }

    /// A copy whose row 0 lies in the mirror plane (what turning the mirror on
    /// does to the half). Refused when a row-0 tangent is along the plane's normal.
    pub fn with_seam_in_plane(&self) -> Result<Design, KernelError> {
        let seam = self.seam_row(&self.mirror_plane())?;
        let mut net = self.net.clone();
        net.row_mut(0).copy_from_slice(&seam);
        Ok(Design {
            net,
            ..self.clone()
        })
    }

    /// The doubled design: `2m − 1` rows (module doc); row `m − 1 + r` is the
    /// half's row `r`, row `m − 1 − r` its reflection.
    pub fn mirrored(&self) -> Result<Design, KernelError> {
        let plane = self.mirror_plane();
        let seam = self.seam_row(&plane)?;
        let (m, cols) = (self.net.rows(), self.net.cols());
        let t0 = self.params.t[0];
        let order: Vec<usize> = (1..m).rev().chain(0..m).collect();
        let mut net = Vec::with_capacity((2 * m - 1) * cols);
        let mut s = Vec::with_capacity((2 * m - 1) * cols);
        let mut t = Vec::with_capacity(2 * m - 1);
        for (i, &r) in order.iter().enumerate() {
            let mirrored = i < m - 1;
            match (r, mirrored) {
                (0, _) => net.extend_from_slice(&seam),
                (_, true) => net.extend(self.net.row(r).iter().map(|&v| plane.reflect_dir(v))),
                (_, false) => net.extend_from_slice(self.net.row(r)),
            }
            s.extend_from_slice(self.params.s.row(r));
            t.push(if mirrored {
                2.0 * t0 - self.params.t[r]
            } else {
                self.params.t[r]
            });
        }
        let net = Grid::new(2 * m - 1, cols, net).expect("2m − 1 rows");
        let s = Grid::new(2 * m - 1, cols, s).expect("2m − 1 rows");
        let params = crate::levels::params::ParamGrid::new(s, t, self.anchor, self.scheme)?;
        Ok(Design {
            net,
            params,
            initial: self.initial.mirrored_about(t0, plane),
            ..self.clone()
        })
    }
}
