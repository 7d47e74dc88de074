//! The best design met while the net grows (`docs/math.md §12`, "Growing
//! the net"): the one whose largest distance, either way, is the least; the
//! design the fit returns, measured at every point and both ways
//! (eq. 12.6, 12.7) when it was not yet.

use super::deviation::Measured;
use super::plan::Plan;
use crate::fit::closest::Distances;
use crate::fit::construct::Nodes;
use crate::fit::error::ReferenceFitError;
use crate::fit::measure::{RowCache, from_reference};
use crate::levels::builder::Builder;
use crate::levels::design::Design;

/// The best design met so far.
pub(super) struct Best {
    pub(super) design: Design,
    pub(super) nodes: Nodes,
    pub(super) key: f64,
    pub(super) to: Distances,
    pub(super) from: Option<Distances>,
    /// Whether `to` was measured at every point.
    pub(super) full: bool,
    /// Its furthest measured point (`Measure::worst`).
    pub(super) worst: (f64, f64, f64, f64),
}

/// Keeps `design` (of `nodes`, measured as `net`, compared by `key`) when
/// it is closer than `best`; says whether it is closer by 1 % (which
/// restarts the count of nets that bring the design no closer).
pub(super) fn keep(
    best: &mut Option<Best>,
    design: Design,
    nodes: &Nodes,
    net: &Measured,
    key: f64,
) -> bool {
    let closer = best.as_ref().is_none_or(|b| key < 0.99 * b.key);
    if best.as_ref().is_none_or(|b| key < b.key) {
        *best = Some(Best {
            design,
            nodes: nodes.clone(),
            key,
            to: net.to,
            from: net.from,
            full: net.full,
            worst: net.m.worst,
        });
    }
    closer
}

/// Measures `b` at every point and both ways, unless it was.
pub(super) fn measure_in_full(
    plan: &Plan<'_, '_>,
    builder: &mut Builder,
    cache: &mut RowCache,
    b: &mut Best,
) -> Result<(), ReferenceFitError> {
    if b.from.is_some() && b.full {
        return Ok(());
    }
    builder.build(&b.design, plan.opts.depth)?;
    if let Some(level) = builder.level() {
        let points = &builder.mesh().positions;
        let m = plan.measure(&b.nodes, level, points, (1, 2), cache)?;
        b.to = Distances::of(&m.dist);
        b.from = Some(Distances::of(
            &from_reference(plan.f, plan.anchor, level, points, &m.tables)?.0,
        ));
    }
    Ok(())
}
