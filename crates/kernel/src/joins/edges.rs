//! What the patches that start on a patch `A` read of it, at every depth
//! (docs/math.md §11): a chain (§11.1) reads `A`'s row parameters `t`, its
//! last column of tangents (G1, Eq. 67) and its last column of points
//! (Eq. 66); a side join (§11.2) reads `A`'s first or last streamline as an
//! [`EdgeCurve`] (Eqs. 71–72). A few hundred values per depth, against the
//! megabytes of `A`'s [`Stack`]: kept from before an edit of `A`, they are
//! all [`super::rejoin`] compares, so `A`'s stack itself can be updated in
//! place (or its old copy dropped) before its children are brought up to
//! date.

use crate::joins::edge_curve::EdgeCurve;
use crate::joins::kinds::Edge;
use crate::joins::stack::Stack;
use glam::DVec3;

/// What a joined patch reads of `A` at one depth.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeLevel {
    /// The level's row parameters `t` (a chain's, copied, Eq. 66).
    pub t: Vec<f64>,
    /// The level's last column of tangents (a G1 chain's first, Eq. 67).
    pub last_tangents: Vec<DVec3>,
    /// Each streamline's last point (a chain's start points, Eq. 66).
    pub end_points: Vec<DVec3>,
    /// `A`'s first streamline as a curve (a side join on `First`).
    pub first: Option<EdgeCurve>,
    /// `A`'s last streamline as a curve (a side join on `Last`).
    pub last: Option<EdgeCurve>,
}

impl EdgeLevel {
    /// The curve of side `edge` (`None` for `End`).
    pub fn curve(&self, edge: Edge) -> Option<&EdgeCurve> {
        match edge {
            Edge::First => self.first.as_ref(),
            Edge::Last => self.last.as_ref(),
            Edge::End => None,
        }
    }
}

/// What a joined patch reads of `A` at every depth `0 ..= d` (module
/// documentation).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Edges {
    /// Depths `0 ..= d`.
    pub levels: Vec<EdgeLevel>,
}

impl Edges {
    /// Read from `A`'s stack; its edge curves only when `sides` (a side
    /// join on `A` reads them, a chain does not).
    pub fn of(a: &Stack, sides: bool) -> Self {
        let levels = (a.levels.iter().zip(&a.points).enumerate())
            .map(|(d, (level, points))| {
                let cols = level.tangents.cols();
                let curve = |edge| {
                    sides
                        .then(|| EdgeCurve::at(&a.levels, points, d as u32, edge))
                        .flatten()
                };
                EdgeLevel {
                    t: level.params.t.clone(),
                    last_tangents: match cols {
                        0 => Vec::new(),
                        c => level.tangents.column(c - 1),
                    },
                    end_points: match points.cols() {
                        0 => Vec::new(),
                        c => points.column(c - 1),
                    },
                    first: curve(Edge::First),
                    last: curve(Edge::Last),
                }
            })
            .collect();
        Edges { levels }
    }

    /// The number of depths held (`d + 1`).
    pub fn len(&self) -> usize {
        self.levels.len()
    }

    /// No depth held.
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }
}
