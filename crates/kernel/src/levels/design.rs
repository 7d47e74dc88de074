//! A whole streamline surface: control net, parameters, scheme, blend order,
//! anchor column and initial curve. Its full build (blend → integrate → mesh),
//! [`Design::build`], is defined in `builder.rs`, next to the [`Builder`] it
//! uses once, so that `builder.rs` imports this file and not the other way round.
//!
//! [`Builder`]: crate::levels::builder::Builder

use crate::error::{KernelError, Place};
use crate::grid::Grid;
use crate::levels::params::ParamGrid;
use crate::levels::surface::{BlendOrder, SurfaceScheme, normalize_grid, refine_grid};
use crate::streamline::initial_curve::InitialCurve;
use crate::streamline::integrate::place_slice;
use crate::streamline::surface_mesh::SurfaceMesh;
use glam::DVec3;

/// Everything that defines a streamline surface at level 0.
///
/// Its invariants hold from [`Design::new`] on: every tangent is unit, the
/// parameter grid has the net's shape and increases along each row, the
/// scheme is valid and the net within the size cap. The fields are read
/// through getters and changed only through the setters here (and the
/// authoring operations of [`crate::authoring`]), which check them again.
#[derive(Debug, Clone)]
pub struct Design {
    /// Unit control tangents, one row per streamline.
    pub(crate) net: Grid<DVec3>,
    /// Level-0 parameters.
    pub(crate) params: ParamGrid,
    /// The tensor-product scheme.
    pub(crate) scheme: SurfaceScheme,
    /// Which direction is blended first.
    pub(crate) order: BlendOrder,
    /// The anchor column at level 0.
    pub(crate) anchor: usize,
    /// The initial curve the streamlines start on.
    pub(crate) initial: InitialCurve,
}

/// One subdivision level: tangents and their parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    /// Unit tangents.
    pub tangents: Grid<DVec3>,
    /// Their parameters.
    pub params: ParamGrid,
}

impl Design {
    /// Validates and normalises a design.
    pub fn new(
        net: &Grid<DVec3>,
        s: Grid<f64>,
        t: Vec<f64>,
        anchor: usize,
        scheme: SurfaceScheme,
        order: BlendOrder,
        initial: InitialCurve,
    ) -> Result<Self, KernelError> {
        let scheme = scheme.validate()?;
        let net = normalize_grid(net)?;
        if (s.rows(), s.cols()) != (net.rows(), net.cols()) {
            return Err(KernelError::LengthMismatch {
                what: "s parameter grid",
                got: s.rows() * s.cols(),
                expected: net.rows() * net.cols(),
            });
        }
        scheme.check_depth(net.rows(), net.cols(), 0)?;
        let params = ParamGrid::new(s, t, anchor, scheme)?;
        Ok(Design {
            net,
            params,
            scheme,
            order,
            anchor,
            initial,
        })
    }

    /// The unit control tangents, one row per streamline.
    #[inline]
    pub fn net(&self) -> &Grid<DVec3> {
        &self.net
    }

    /// The level-0 parameters (`s` per tangent, `t` and `σ` per row).
    #[inline]
    pub fn params(&self) -> &ParamGrid {
        &self.params
    }

    /// The tensor-product scheme.
    #[inline]
    pub fn scheme(&self) -> SurfaceScheme {
        self.scheme
    }

    /// Which direction is blended first.
    #[inline]
    pub fn order(&self) -> BlendOrder {
        self.order
    }

    /// The anchor column at level 0 (where `σ` is measured, Eqs. 1–2).
    #[inline]
    pub fn anchor(&self) -> usize {
        self.anchor
    }

    /// The initial curve the streamlines start on.
    #[inline]
    pub fn initial(&self) -> &InitialCurve {
        &self.initial
    }

    /// Replaces the scheme, validated, and checked against the net's size;
    /// `σ` follows the scheme's limit ends ([`crate::levels::params::anchor_sigma`]).
    pub fn set_scheme(&mut self, scheme: SurfaceScheme) -> Result<(), KernelError> {
        let scheme = scheme.validate()?;
        scheme.check_depth(self.net.rows(), self.net.cols(), 0)?;
        let s = self.params.s.clone();
        self.params = ParamGrid::new(s, self.params.t.clone(), self.anchor, scheme)?;
        self.scheme = scheme;
        Ok(())
    }

    /// Replaces the blend order.
    pub fn set_order(&mut self, order: BlendOrder) {
        self.order = order;
    }

    /// Replaces the initial curve (an [`InitialCurve`] is checked when it is made).
    pub fn set_initial(&mut self, initial: InitialCurve) {
        self.initial = initial;
    }

    /// Replaces every control tangent (normalised) with a net of the same
    /// shape; the parameters stay. On an error the design is unchanged.
    pub fn set_net(&mut self, net: &Grid<DVec3>) -> Result<(), KernelError> {
        if (net.rows(), net.cols()) != (self.net.rows(), self.net.cols()) {
            return Err(KernelError::LengthMismatch {
                what: "control net",
                got: net.rows() * net.cols(),
                expected: self.net.rows() * self.net.cols(),
            });
        }
        self.net = normalize_grid(net)?;
        Ok(())
    }

    /// Replaces the level-0 parameters `s` of row `row` (one per tangent),
    /// checked as [`Design::new`] checks them (finite, within range, strictly
    /// increasing); the row's `σ` follows its anchor column (Eqs. 1–2). On an
    /// error the design is unchanged.
    pub fn set_s_row(&mut self, row: usize, s: &[f64]) -> Result<(), KernelError> {
        let (rows, cols) = (self.net.rows(), self.net.cols());
        if row >= rows {
            return Err(KernelError::IndexOutOfRange {
                what: "row",
                index: row,
                len: rows,
            });
        }
        if s.len() != cols {
            return Err(KernelError::LengthMismatch {
                what: "arc-length parameters s of a row",
                got: s.len(),
                expected: cols,
            });
        }
        let mut grid = self.params.s.clone();
        grid.row_mut(row).copy_from_slice(s);
        self.params = ParamGrid::new(grid, self.params.t.clone(), self.anchor, self.scheme)?;
        Ok(())
    }

    /// Level 0.
    pub fn base(&self) -> Level {
        Level {
            tangents: self.net.clone(),
            params: self.params.clone(),
        }
    }

    /// Levels `0 ..= depth`.
    pub fn levels(&self, depth: u32) -> Result<Vec<Level>, KernelError> {
        self.scheme
            .check_depth(self.net.rows(), self.net.cols(), depth)?;
        let mut out = vec![self.base()];
        for d in 1..=depth {
            let prev = out.last().expect("level 0 exists");
            out.push(self.refine(prev, d)?);
        }
        Ok(out)
    }

    /// The level `depth` alone.
    pub fn level(&self, depth: u32) -> Result<Level, KernelError> {
        self.scheme
            .check_depth(self.net.rows(), self.net.cols(), depth)?;
        let mut cur = self.base();
        for d in 1..=depth {
            cur = self.refine(&cur, d)?;
        }
        Ok(cur)
    }

    /// One step from `prev` to level `level`.
    pub fn refine(&self, prev: &Level, level: u32) -> Result<Level, KernelError> {
        let params = prev.params.refine(self.scheme, self.order, level)?;
        let tangents = refine_grid(self.scheme, self.order, &prev.tangents);
        Ok(Level { tangents, params })
    }

    /// The streamlines of a level: `rows × (cols + 1)` points.
    pub fn streamlines(&self, level: &Level) -> Grid<DVec3> {
        let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
        let mut data = Vec::with_capacity(rows * (cols + 1));
        let mut buf = Vec::with_capacity(cols + 1);
        for r in 0..rows {
            self.streamline_into(level, r, &mut buf);
            data.extend_from_slice(&buf);
        }
        Grid::new(rows, cols + 1, data).expect("sizes agree")
    }

    /// Row `r`'s streamline into `out`.
    pub(crate) fn streamline_into(&self, level: &Level, r: usize, out: &mut Vec<DVec3>) {
        out.clear();
        out.resize(level.tangents.cols() + 1, DVec3::ZERO);
        self.place_row(level, r, out);
    }

    /// Row `r`'s streamline into `out`, which holds exactly `cols + 1` points.
    pub fn place_row(&self, level: &Level, r: usize, out: &mut [DVec3]) {
        let origin = self.initial.point(level.params.t[r]);
        place_slice(
            level.tangents.row(r),
            level.params.s.row(r),
            level.params.sigma[r],
            origin,
            out,
        );
    }

    /// Replaces one control tangent (normalised), for editing.
    pub fn set_tangent(&mut self, row: usize, col: usize, v: DVec3) -> Result<(), KernelError> {
        if row >= self.net.rows() || col >= self.net.cols() {
            return Err(KernelError::IndexOutOfRange {
                what: "tangent",
                index: row * self.net.cols() + col,
                len: self.net.data().len(),
            });
        }
        let t = crate::sphere::tangent::normalize_at(v, Place::Grid { row, col })?;
        self.net.set(row, col, t);
        Ok(())
    }
}

/// The result of a full build.
#[derive(Debug, Clone)]
pub struct Built {
    /// The finest level.
    pub level: Level,
    /// Its streamlines.
    pub points: Grid<DVec3>,
    /// The triangle mesh.
    pub mesh: SurfaceMesh,
}
