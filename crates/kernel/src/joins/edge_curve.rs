//! A side edge of patch `A` at one depth (docs/math.md §11.2, Eqs. 71–72):
//! its first or last streamline as a polyline parametrised by arc length,
//! with `A`'s unit normal along it — the streamline's tangent crossed with
//! `A`'s cross derivative `∂S/∂t`, by the differences `A`'s mesh normals use,
//! linear along a segment.
//!
//! The arc length is `A`'s own `s` less the row's first `s` **at level 0**,
//! so at level 0 it is the arc length from `A`'s first point, and at every
//! depth a value names the same place of `A`'s surface (the streamline's
//! point at that `s`, Eq. 65). An approximating scheme's boundary streamline
//! starts and ends inside `A`'s level-0 range at depth `d > 0`; outside its
//! points the curve continues along its end segments.

use crate::grid::Grid;
use crate::joins::kinds::Edge;
use crate::joins::stack::Stack;
use crate::levels::design::Level;
use crate::streamline::integrate::point_arclength;
use glam::DVec3;

/// One of `A`'s boundary streamlines, as a curve `B` starts on.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeCurve {
    /// The streamline's `n + 2` points.
    points: Vec<DVec3>,
    /// The direction of each of its `n + 1` segments (the level's tangents).
    tangents: Vec<DVec3>,
    /// The arc length of each point from the first.
    arc: Vec<f64>,
    /// `∂S/∂t` at each point: the one-sided difference of the mesh normals
    /// (row 1 − row 0 on `First`, row `R−1` − row `R−2` on `Last`).
    cross: Vec<DVec3>,
}

impl EdgeCurve {
    /// `A`'s edge `First` or `Last` at depth `d` of `a`; `None` for `End` (a
    /// chain's edge is a column of points, not a curve) or a depth past `a`'s.
    pub fn of(a: &Stack, d: u32, edge: Edge) -> Option<Self> {
        Self::at(&a.levels, a.points.get(d as usize)?, d, edge)
    }

    /// [`Self::of`] from a stack's `levels` and the streamline `points` of
    /// depth `d` (a stack whose parts are held apart).
    pub fn at(levels: &[Level], points: &Grid<DVec3>, d: u32, edge: Edge) -> Option<Self> {
        let row = match edge {
            Edge::Last => levels.first()?.params.s.rows() - 1,
            _ => 0,
        };
        let s0 = levels[0].params.s.get(row, 0);
        Self::new(levels.get(d as usize)?, points, edge, s0)
    }

    /// `A`'s edge `First` or `Last` of `level` and its streamlines `points`,
    /// its arc length measured from `A`'s arc-length parameter `s0` (the
    /// row's first `s` at level 0); `None` for `End`.
    pub fn new(level: &Level, points: &Grid<DVec3>, edge: Edge, s0: f64) -> Option<Self> {
        let rows = points.rows();
        let (r, inner) = match edge {
            Edge::End => return None,
            Edge::First => (0, 1.min(rows - 1)),
            Edge::Last => (rows - 1, rows.saturating_sub(2)),
        };
        let s = level.params.s.row(r);
        let row = points.row(r).to_vec();
        let arc = (0..row.len()).map(|k| point_arclength(s, k) - s0).collect();
        let cross = match edge {
            Edge::First => (0..row.len())
                .map(|k| points.get(inner, k) - row[k])
                .collect(),
            _ => (0..row.len())
                .map(|k| row[k] - points.get(inner, k))
                .collect(),
        };
        Some(EdgeCurve {
            points: row,
            tangents: level.tangents.row(r).to_vec(),
            arc,
            cross,
        })
    }

    /// The arc length of the streamline's last point: at level 0 its length
    /// `L` (exactly `s_n − s_0`, Eq. 65).
    pub fn length(&self) -> f64 {
        *self.arc.last().expect("a streamline has points")
    }

    /// The arc length of the streamline's first point (0 at level 0).
    pub fn start(&self) -> f64 {
        self.arc[0]
    }

    /// The streamline's points.
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The segment `k` that holds arc length `t` and the fraction `λ ∈ [0, 1]`
    /// of it (segment 0 before the start, the last one past the end).
    pub fn locate(&self, t: f64) -> (usize, f64) {
        let n = self.tangents.len() - 1;
        let k = self
            .arc
            .partition_point(|&x| x <= t)
            .saturating_sub(1)
            .min(n);
        let (a, b) = (self.arc[k], self.arc[k + 1]);
        let lambda = if b > a {
            ((t - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (k, lambda)
    }

    /// The point at arc length `t` (Eq. 71): on segment `k`, `P_k + t_k (t − a_k)`;
    /// before the start and past the end along the end segments.
    pub fn point(&self, t: f64) -> DVec3 {
        let (k, _) = self.locate(t);
        self.points[k] + self.tangents[k] * (t - self.arc[k])
    }

    /// `A`'s unit normal at arc length `t` (Eq. 72): `t_k × ((1 − λ) D_k + λ D_{k+1})`,
    /// normalised; `None` where it vanishes (a collapsed edge).
    pub fn normal(&self, t: f64) -> Option<DVec3> {
        let (k, lambda) = self.locate(t);
        let d = self.cross[k] * (1.0 - lambda) + self.cross[k + 1] * lambda;
        self.tangents[k].cross(d).try_normalize()
    }
}
