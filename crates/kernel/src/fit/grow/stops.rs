//! When the growth stops short (`docs/math.md §12`, "When the growth stops
//! short"), and why, naming what ran out and what to do: the net at its cap,
//! nets that bring the design no closer (fewer once one direction is at its
//! cap, or when an approximating scheme's rows stay off), a net past the
//! kernel's size cap, and no insertion left that keeps the parameters even.

use super::best::Best;
use super::plan::Plan;
use crate::fit::construct::Nodes;
use crate::fit::measure::Measure;

/// The fit stops when this many nets in a row come no closer (by 1 %) than
/// the best one.
const STALL_NETS: usize = 24;

/// With one direction at its cap, the fit stops when this many nets in a
/// row come no closer (by 1 %) than the best one.
const FULL_STALL_NETS: usize = 4;

/// Why the growth stops after the net measured as `m` (largest distance
/// `key`), `stalled` nets after the last that came closer, with the columns
/// and the rows at their cap or not (`full`); `None` while it goes on.
pub(super) fn stopped_short(
    plan: &Plan<'_, '_>,
    best: Option<&Best>,
    m: &Measure,
    key: f64,
    stalled: usize,
    (col_full, row_full): (bool, bool),
) -> Option<String> {
    let (opts, tol) = (plan.opts, plan.tol);
    // with one direction at its cap, only the other can grow: a few
    // nets that bring the design no closer say that it cannot
    let (psi_b, d_b, e_b, x_b) = best.map_or(m.worst, |b| b.worst);
    let b = best.map_or(key, |b| b.key);
    let other = if plan.f.along() == 'u' { 'v' } else { 'u' };
    if (col_full || row_full) && stalled >= FULL_STALL_NETS {
        return Some(if col_full {
            format!(
                "the columns reached their cap of {} control tangents and {FULL_STALL_NETS} more nets brought the design no closer than {b:.3e} (over the tolerance {tol:.3e}): the error lies along the rows (furthest at {:.0} % of their length), where the face turns faster than {} columns can follow; run the streamlines along {other}, loosen the tolerance or split the face",
                opts.max_net.1,
                100.0 * x_b,
                opts.max_net.1,
            )
        } else {
            format!(
                "the rows reached their cap of {} control tangents and {FULL_STALL_NETS} more nets brought the design no closer than {b:.3e} (over the tolerance {tol:.3e}): the error lies across the rows (furthest at {:.0} % of the initial curve), where the face changes faster than {} rows can follow; run the streamlines along {other}, loosen the tolerance or split the face",
                opts.max_net.0,
                100.0 * psi_b,
                opts.max_net.0,
            )
        });
    }
    // an approximating scheme whose tangents are the face's but whose
    // rows stay off: more nets do not help
    if plan.ph > 0 && stalled >= FULL_STALL_NETS && d_b > tol && e_b < 0.5 * d_b {
        return Some(format!(
            "{} approximates: {FULL_STALL_NETS} more nets brought the design no closer than {b:.3e} (over the tolerance {tol:.3e}); its tangents are the face's (they explain {e_b:.1e} of it) but its rows, blended from their neighbours, do not lie where the face's do (furthest at {:.0} % of the initial curve and {:.0} % of the rows' length); fit with the interpolating scheme (--scheme kobbelt), loosen the tolerance or split the face",
            opts.scheme.name(),
            100.0 * psi_b,
            100.0 * x_b,
        ));
    }
    if stalled >= STALL_NETS {
        return Some(format!(
            "the deviation stopped falling: {STALL_NETS} nets in a row came no closer than {:.3e} (over the tolerance {:.3e}); the face may have a crease or a degenerate edge: loosen the tolerance or split the face",
            best.map_or(key, |b| b.key),
            tol
        ));
    }
    None
}

/// Why the growth stops when no insertion is left: the net is at its cap
/// with the design at best `b` from the reference.
pub(super) fn at_cap(plan: &Plan<'_, '_>, b: f64) -> String {
    format!(
        "the net reached its cap of {} × {} control tangents with the design at best {:.3e} from the reference, over the tolerance {:.3e}; raise the cap, loosen the tolerance or split the face",
        plan.opts.max_net.0, plan.opts.max_net.1, b, plan.tol
    )
}

/// Why the growth stops when the net of `nodes` would pass the kernel's
/// size cap at the fit depth.
pub(super) fn past_size_cap(plan: &Plan<'_, '_>, nodes: &Nodes) -> String {
    format!(
        "a net of {} × {} control tangents would pass the kernel's size cap at depth {}; loosen the tolerance or fit at a lower depth",
        nodes.rows.len() + plan.ph,
        nodes.cols.len() + plan.ph,
        plan.opts.depth
    )
}

/// Why the growth stops when every insertion left would make the
/// parameters uneven.
pub(super) fn no_even_insertion() -> String {
    "no row or column can be inserted any more without making the parameters uneven; loosen the tolerance"
        .to_string()
}
