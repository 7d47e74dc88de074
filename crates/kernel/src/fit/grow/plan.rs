//! The plan of a fit (`docs/math.md §12`, eq. 12.3 and 12.6): what every
//! net is built and measured with, fixed when the fit starts: the frame,
//! the anchor curve, the design's setup beyond its nodes, the tolerance and
//! the net's cap less the phantoms.

use crate::fit::construct::{Nodes, Setup, phantoms};
use crate::fit::error::ReferenceFitError;
use crate::fit::measure::{Measure, RowCache, measure};
use crate::fit::options::ReferenceFitOptions;
use crate::fit::reference::{AnchorCurve, Frame};
use crate::levels::design::Level;
use crate::streamline::initial_curve::InitialCurve;
use glam::DVec3;

/// What every net of one fit is built and measured with.
pub(super) struct Plan<'f, 'a> {
    pub(super) f: &'f Frame<'a>,
    pub(super) anchor: &'f AnchorCurve,
    pub(super) opts: &'f ReferenceFitOptions,
    /// What `build_design` needs beyond the nodes (eq. 12.3).
    pub(super) setup: Setup<'f>,
    /// The absolute tolerance `ε`.
    pub(super) tol: f64,
    /// The initial curve's length `L_t`.
    pub(super) lt: f64,
    /// The anchor's fraction `φ_a` of the rows' length.
    pub(super) fraction: f64,
    /// Gauss–Newton (eq. 12.6) stops when a step moves the surface point
    /// by no more than this.
    pub(super) stop: f64,
    /// The phantom rows (or columns) of an approximating scheme, both ends
    /// together.
    pub(super) ph: usize,
    /// The node rows and columns the cap allows.
    pub(super) cap_rows: usize,
    pub(super) cap_cols: usize,
}

impl<'f, 'a> Plan<'f, 'a> {
    /// The plan of a fit within `tol` of the frame `f`, from the anchor
    /// curve at `fraction` of the rows and the initial curve fitted to it.
    pub(super) fn new(
        f: &'f Frame<'a>,
        anchor: &'f AnchorCurve,
        fraction: f64,
        initial: &'f InitialCurve,
        opts: &'f ReferenceFitOptions,
        tol: f64,
    ) -> Self {
        let lt = anchor.length();
        let setup = Setup {
            scheme: opts.scheme,
            order: opts.order,
            depth: opts.depth,
            anchor_fraction: fraction,
            initial,
            length: lt,
            angle_tolerance: 1e-3 * tol / lt.max(f.diag),
        };
        let ph = 2 * phantoms(opts.scheme);
        let (cap_rows, cap_cols) = (opts.max_net.0 - ph, opts.max_net.1 - ph);
        Plan {
            f,
            anchor,
            opts,
            setup,
            tol,
            lt,
            fraction,
            stop: 1e-3 * tol,
            ph,
            cap_rows,
            cap_cols,
        }
    }

    /// The mesh `points` of `level` (the net of `nodes`) measured to the
    /// reference (eq. 12.6) at the rows and columns `(stride, every)`.
    pub(super) fn measure(
        &self,
        nodes: &Nodes,
        level: &Level,
        points: &[DVec3],
        stride: (usize, usize),
        cache: &mut RowCache,
    ) -> Result<Measure, ReferenceFitError> {
        measure(
            self.f,
            self.anchor,
            nodes,
            self.lt,
            level,
            points,
            stride,
            self.stop,
            self.fraction,
            cache,
        )
    }
}
