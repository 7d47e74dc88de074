//! Where a kept patch starts and what its levels and rows read there
//! (docs/math.md §11): its own initial curve, or an edge of an earlier patch
//! `A`, whose join fixes each level after its step (a chain's `t` and G1 seam
//! column, Eqs. 66–67; a side join's `σ` and G1 projection, Eq. 73) and
//! whose edge gives each row its start point (Eqs. 66, 71). What
//! [`super::patch_state::PatchState`] makes again and compares after an edit.

use crate::finetune::SurfaceTuning;
use crate::grid::Grid;
use crate::joins::chain::{chain, check_chain};
use crate::joins::edge_curve::EdgeCurve;
use crate::joins::error::JoinError;
use crate::joins::kinds::{Continuity, Edge};
use crate::joins::parts::PatchParts;
use crate::joins::side::{check_rows, project, side};
use crate::joins::stack::{Stack, place_at_starts};
use crate::levels::design::{Design, Level};
use crate::levels::dirty_window::DirtyWindow;
use crate::levels::incremental::{LevelState, tuned_points};
use crate::streamline::integrate::place_slice;
use glam::DVec3;

/// Where a patch starts (docs/math.md §11).
#[derive(Debug, Clone, Copy)]
pub enum Start<'a> {
    /// On its own initial curve (the design's).
    Curve,
    /// On edge `edge` of an earlier patch `A`: `A`'s design as it is joined
    /// and its stack as built now.
    Edge {
        /// `A`'s design.
        a_design: &'a Design,
        /// `A`'s stack.
        a: &'a Stack,
        /// The edge of `A`.
        edge: Edge,
        /// The continuity across it.
        continuity: Continuity,
    },
}

/// The kind of start, kept to know when an update must build whole.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    Curve,
    Edge(Edge, Continuity),
}

impl Start<'_> {
    pub(crate) fn kind(&self) -> Kind {
        match *self {
            Start::Curve => Kind::Curve,
            Start::Edge {
                edge, continuity, ..
            } => Kind::Edge(edge, continuity),
        }
    }
}

/// What a level's fix reads of `A` at every depth.
pub(crate) struct Parent<'a> {
    pub(crate) kind: Kind,
    a: Option<&'a Stack>,
    /// `A`'s edge curve at every depth (side joins).
    curves: Vec<EdgeCurve>,
}

impl<'a> Parent<'a> {
    /// The parent of `start` for `design`, checked as the whole build
    /// checks it.
    pub(crate) fn of(design: &Design, start: Start<'a>) -> Result<Self, JoinError> {
        let kind = start.kind();
        let Start::Edge {
            a_design,
            a,
            edge,
            continuity,
        } = start
        else {
            return Ok(Parent {
                kind,
                a: None,
                curves: Vec::new(),
            });
        };
        if continuity == Continuity::G2 {
            return Err(match edge {
                Edge::End => JoinError::G2IsOneNet,
                _ => JoinError::SideG2,
            });
        }
        let mut curves = Vec::new();
        if edge == Edge::End {
            check_chain(a_design, design, continuity)?;
        } else {
            if design.anchor() != 0 {
                return Err(JoinError::AnchorNotFirst {
                    anchor: design.anchor(),
                });
            }
            curves = (0..=a.depth())
                .map(|d| EdgeCurve::of(a, d, edge).expect("a side edge of a built depth"))
                .collect();
            check_rows(&design.params().t, curves[0].length())?;
        }
        Ok(Parent {
            kind,
            a: Some(a),
            curves,
        })
    }

    /// Level `d`'s fix (module documentation): `t` and `σ`, then column 0,
    /// from `before` (column 0 before a side G1 projection, refreshed first
    /// in the rows of `fresh`, whose column 0 the step just wrote).
    pub(crate) fn fix(
        &self,
        d: usize,
        level: &mut LevelState,
        fresh: Option<DirtyWindow>,
        before: &mut [DVec3],
    ) -> Result<(), JoinError> {
        let Kind::Edge(edge, continuity) = self.kind else {
            return Ok(());
        };
        let a = self.a.expect("a joined patch has a parent");
        let rows = level.tangents.rows();
        if edge == Edge::End {
            level.params.t.clone_from(&a.levels[d].params.t);
        }
        for r in 0..rows {
            level.params.sigma[r] = level.params.s.get(r, 0);
        }
        if continuity != Continuity::G1 {
            return Ok(());
        }
        if let Some(w) = fresh.filter(|w| w.cols.lo == 0) {
            for r in w.rows.iter() {
                before[r] = level.tangents.get(r, 0);
            }
        }
        if edge == Edge::End {
            let al = &a.levels[d];
            let last = al.tangents.cols() - 1;
            for r in 0..rows {
                level.tangents.set(r, 0, al.tangents.get(r, last));
            }
            return Ok(());
        }
        let curve = &self.curves[d];
        for (r, &b) in before.iter().enumerate().take(rows) {
            let v = project(b, curve.normal(level.params.t[r])).ok_or(
                JoinError::SideTangentAlongNormal {
                    row: r,
                    level: d as u32,
                },
            )?;
            level.tangents.set(r, 0, v);
        }
        Ok(())
    }

    /// Each row's start at depth `d` for `level` (module documentation).
    pub(crate) fn starts(&self, design: &Design, d: usize, level: &LevelState) -> Vec<DVec3> {
        match self.kind {
            Kind::Curve => (level.params.t.iter())
                .map(|&t| design.initial().point(t))
                .collect(),
            Kind::Edge(Edge::End, _) => {
                let p = &self.a.expect("a parent").points[d];
                p.column(p.cols() - 1)
            }
            Kind::Edge(..) => (level.params.t.iter())
                .map(|&t| self.curves[d].point(t))
                .collect(),
        }
    }
}

/// The whole build of `parts` on `start` (its error is the one reported).
pub(crate) fn whole(parts: PatchParts, start: Start, depth: u32) -> Result<Stack, JoinError> {
    match start {
        Start::Curve => Stack::build_parts(parts, depth).map_err(JoinError::from),
        Start::Edge {
            a_design,
            a,
            edge: Edge::End,
            continuity,
        } => chain(a_design, a, parts, continuity),
        Start::Edge {
            a,
            edge,
            continuity,
            ..
        } => side(a, parts, edge, continuity),
    }
}

/// A level's points, every row, as the whole build places them.
pub(crate) fn place_level(
    kind: Kind,
    design: &Design,
    level: &Level,
    starts: &[DVec3],
    tuning: Option<&SurfaceTuning>,
) -> Grid<DVec3> {
    match kind {
        Kind::Curve => match tuning {
            None => design.streamlines(level),
            Some(t) => tuned_points(design.initial(), &level.tangents, &level.params, Some(t)),
        },
        Kind::Edge(..) => place_at_starts(level, starts, tuning),
    }
}

/// Row `r` of an untuned level placed again in `out` (Eq. 65), as
/// [`place_level`] places it.
pub(crate) fn place_row(kind: Kind, level: &Level, start: DVec3, r: usize, out: &mut [DVec3]) {
    let s = level.params.s.row(r);
    let sigma = match kind {
        Kind::Curve => level.params.sigma[r],
        Kind::Edge(..) => s[0],
    };
    place_slice(level.tangents.row(r), s, sigma, start, out);
}
