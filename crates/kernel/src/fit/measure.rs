//! Measuring a fit (`docs/math.md §12`, "Deviation, both ways"): a built
//! mesh against the reference, every point from where its row's `t` and its
//! arc length expect it (eq. 12.6), with the cells' tangent-error scores
//! that say where to grow; and the reference, sampled at the same places
//! and the cells' centres, to the mesh (eq. 12.7).
//!
//! * `mesh_to_reference`: the mesh's points to the reference (eq. 12.6) and
//!   the cells' scores;
//! * `reference_to_mesh`: the reference's samples to the mesh (eq. 12.7);
//! * `row_cache`: the rows of the last net, not measured again when
//!   unchanged.

mod mesh_to_reference;
mod reference_to_mesh;
mod row_cache;

pub(super) use self::mesh_to_reference::measure;
pub(super) use self::reference_to_mesh::from_reference;
pub(super) use self::row_cache::RowCache;

use super::error::ReferenceFitError;
use super::reference::RowTable;
use glam::DVec3;

/// The measurements of one mesh row.
#[derive(Clone)]
pub(super) struct RowResult {
    pub(super) dist: Vec<f64>,
    /// Of each measured point, the position error its row's tangent error
    /// explains: the angle × interval summed from the anchor to the point
    /// (a bound on the gap that the tangents alone open).
    pub(super) explained: Vec<f64>,
    /// Of each measured point, its fraction of the row's length.
    pub(super) at: Vec<f64>,
    /// Of each measured point, where Newton starts (`u`), and whether its
    /// distance is the converged one or the first step's (never less).
    start: Vec<f64>,
    exact: Vec<bool>,
    /// Angle × interval of each level tangent.
    pub(super) contrib: Vec<f64>,
    /// Fraction of the row's length at each level tangent.
    pub(super) frac: Vec<f64>,
    pub(super) table: RowTable,
}

/// The measurement of a whole mesh.
pub(super) struct Measure {
    pub(super) dist: Vec<f64>,
    /// The furthest measured point: its row's `t / L_t`, its distance,
    /// the part of it that its row's tangent error explains, and its
    /// fraction of the row's length.
    pub(super) worst: (f64, f64, f64, f64),
    /// Cell scores on node rows and between them, `rows − 1` × `cols − 1`.
    pub(super) on_nodes: Vec<Vec<f64>>,
    pub(super) between: Vec<Vec<f64>>,
    pub(super) tables: Vec<RowTable>,
}

pub(super) fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The interval of increasing `xs` holding `x` (clamped to the first and last).
pub(super) fn interval(xs: &[f64], x: f64) -> usize {
    xs.partition_point(|&v| v <= x)
        .saturating_sub(1)
        .min(xs.len().saturating_sub(2))
}

/// Runs `work` on every row index, on two threads, one taking the even
/// indices and the other the odd ones (so that rows that cost more, such
/// as those a row insertion changed, which lie together, are shared).
pub(super) fn rows_parallel<T: Send>(
    rows: usize,
    work: &(dyn Fn(usize) -> Result<T, ReferenceFitError> + Sync),
) -> Result<Vec<T>, ReferenceFitError> {
    let mut even: Vec<Result<T, ReferenceFitError>> = Vec::new();
    let mut odd: Vec<Result<T, ReferenceFitError>> = Vec::new();
    crate::parallel::join(
        || even = (0..rows).step_by(2).map(work).collect(),
        || odd = (1..rows).step_by(2).map(work).collect(),
    );
    let mut out = Vec::with_capacity(rows);
    let mut odd = odd.into_iter();
    for e in even {
        out.push(e?);
        if let Some(o) = odd.next() {
            out.push(o?);
        }
    }
    Ok(out)
}

/// The cells' bounds in one direction: the nodes, and 0 and 1 where the
/// nodes stop short of them (Doo–Sabin's), so that the border can grow too.
pub(super) fn breaks(xs: &[f64]) -> Vec<f64> {
    let mut b = Vec::with_capacity(xs.len() + 2);
    if xs.first().is_some_and(|&x| x > 0.0) {
        b.push(0.0);
    }
    b.extend_from_slice(xs);
    if xs.last().is_some_and(|&x| x < 1.0) {
        b.push(1.0);
    }
    b
}
