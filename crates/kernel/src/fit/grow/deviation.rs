//! A net measured (`docs/math.md §12`, "Deviation, both ways"): its mesh at
//! the fit depth to the reference (eq. 12.6), at every other row and column
//! while the mesh is large and far, at every point once within the
//! tolerance; then the reference to the mesh (eq. 12.7), with the insertion
//! the mesh's chords suggest where the reference is furthest from it.

use super::insert::{Insert, chord_insert};
use super::plan::Plan;
use crate::fit::closest::Distances;
use crate::fit::construct::Nodes;
use crate::fit::error::ReferenceFitError;
use crate::fit::measure::{Measure, RowCache, from_reference};
use crate::levels::builder::Builder;

/// Meshes with more points than this are measured at every other row and
/// column while the net grows (every point once within the tolerance).
const STRIDE_FROM: usize = 40_000;

/// The measurement of one net.
pub(super) struct Measured {
    /// The mesh to the reference, with the cells' scores.
    pub(super) m: Measure,
    /// From the measured points of the mesh to the reference.
    pub(super) to: Distances,
    /// From the reference to the mesh, once `to` is within the tolerance.
    pub(super) from: Option<Distances>,
    /// With `from`: the insertion that refines the mesh's coarser direction
    /// where the reference is furthest from it.
    pub(super) chord: Option<Insert>,
    /// Whether `to` was measured at every point.
    pub(super) full: bool,
}

impl Measured {
    /// What nets are compared by: the largest distance measured, either way.
    pub(super) fn key(&self) -> f64 {
        self.from.map_or(self.to.max, |d| d.max.max(self.to.max))
    }
}

/// Measures the net of `nodes` that `builder` has just built: strided
/// while far, every point once close (the strided rows lend theirs, the
/// cells scored as they were), and both ways once within the tolerance.
pub(super) fn measure_net(
    plan: &Plan<'_, '_>,
    builder: &Builder,
    nodes: &Nodes,
    cache: &mut RowCache,
) -> Result<Measured, ReferenceFitError> {
    let Some(level) = builder.level() else {
        return Err(ReferenceFitError::NonFinite { what: "mesh" });
    };
    let points = &builder.mesh().positions;
    // strided while far, every point once close
    let (rows_d, cols_d) = (level.tangents.rows(), level.tangents.cols());
    let mut stride = if rows_d * cols_d > STRIDE_FROM { 2 } else { 1 };
    let mut m = plan.measure(nodes, level, points, (stride, stride), cache)?;
    let mut to = Distances::of(&m.dist);
    if to.max <= plan.tol && stride > 1 {
        // every point now (the strided rows lend theirs), the cells
        // scored as they were
        stride = 1;
        m = plan.measure(nodes, level, points, (1, 2), cache)?;
        to = Distances::of(&m.dist);
    }
    let mut from = None;
    let mut chord = None;
    if to.max <= plan.tol {
        let (d, at) = from_reference(plan.f, plan.anchor, level, points, &m.tables)?;
        from = Some(Distances::of(&d));
        chord = Some(chord_insert(nodes, plan.lt, level, points, at));
    }
    Ok(Measured {
        m,
        to,
        from,
        chord,
        full: stride == 1,
    })
}
