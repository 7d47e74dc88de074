//! The growth of the net (`docs/math.md §12`, "Growing the net"), one
//! round at a time: the current nodes built and measured, the design kept
//! if the best, the progress reported, and then either the end of the
//! growth (within the tolerance, or stopped short) or the next insertion.

use super::best::keep;
use super::build::build_net;
use super::deviation::measure_net;
use super::next::grow_next;
use super::plan::Plan;
use super::state::{Growth, Round};
use super::stops::stopped_short;
use crate::fit::error::ReferenceFitError;

/// Grows the net round by round until it ends: within the tolerance
/// (`None`) or short of it, and why. `progress` as for
/// `fit_reference_with`.
pub(super) fn grow(
    plan: &Plan<'_, '_>,
    g: &mut Growth<'_, '_>,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Option<String>, ReferenceFitError> {
    loop {
        if let Round::Stop(why) = round(plan, g, progress)? {
            return Ok(why);
        }
    }
}

/// One growth round: builds and measures the current nodes (on a net that
/// cannot be built, goes back to the last one and blocks that insertion),
/// keeps the design if the best, and ends the growth or makes the next
/// insertion.
fn round(
    plan: &Plan<'_, '_>,
    g: &mut Growth<'_, '_>,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Round, ReferenceFitError> {
    let design = match build_net(plan, g)? {
        Ok(d) => d,
        Err(round) => return Ok(round),
    };
    g.steps += 1;
    let net = measure_net(plan, &g.builder, &g.nodes, &mut g.cache)?;
    let key = net.key();
    // with an approximating scheme (whose node rows are not mesh rows,
    // so that the scores tell the directions apart less well), an
    // insertion that brought the design no closer sends the next one
    // the other way in the worst cell
    let no_gain = g.prev_key.is_some_and(|p| key > 0.99 * p);
    let flip = plan.ph > 0 && no_gain && !g.flip_used;
    g.flip_used = flip;
    g.prev_key = Some(key);
    if keep(&mut g.best, design, &g.nodes, &net, key) {
        g.best_step = g.steps;
    }
    if net.from.is_some_and(|d| d.max <= plan.tol) {
        return Ok(Round::Stop(None));
    }
    report_progress(plan.tol, g, key, progress)?;
    let full = (
        g.nodes.cols.len() >= plan.cap_cols,
        g.nodes.rows.len() >= plan.cap_rows,
    );
    let stalled = g.steps - g.best_step;
    if let Some(why) = stopped_short(plan, g.best.as_ref(), &net.m, key, stalled, full) {
        return Ok(Round::Stop(Some(why)));
    }
    Ok(grow_next(plan, g, net, no_gain, flip, full))
}

/// Reports the fraction done after a net whose largest distance is `key`:
/// how far `key` has come down from the first net's towards `tol`, on a
/// log scale (never back, at most 95 % while growing); `false` from
/// `progress` cancels the fit.
fn report_progress(
    tol: f64,
    g: &mut Growth<'_, '_>,
    key: f64,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(), ReferenceFitError> {
    let fm = *g.first_max.get_or_insert(key);
    if fm > tol && key > 0.0 {
        let p = 1.0 - ((key / tol).ln() / (fm / tol).ln()).clamp(0.0, 1.0);
        g.done = g.done.max(0.95 * p);
    }
    if !progress(g.done) {
        return Err(ReferenceFitError::Cancelled);
    }
    Ok(())
}
