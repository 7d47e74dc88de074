//! The fit of a reference (`docs/math.md §12`, "Growing the net"): from the
//! smallest net, one column or one row at a time where the design is
//! furthest from the reference, until the design's mesh at the fit depth is
//! within the tolerance both ways, or the net reaches its cap.
//!
//! **Measuring** (eq. 12.6): every point of the mesh at the fit depth is
//! expected where its row's `t` and its arc length say (the fraction of the
//! row's length); Gauss–Newton from there finds the closest point of the
//! reference. Both ways (eq. 12.7): the reference sampled at the same places
//! and at the cells' centres (twice the mesh's points), each to the mesh's
//! triangles around where it is expected.
//!
//! **Where to grow**: the position error a row gathers is the integral of
//! its tangent error, so the fit localises by the tangent error instead:
//! each level tangent's angle to the reference's tangent at its arc length,
//! times its interval `ds`, summed over a cell of the node grid (one
//! interval between node rows × one between node columns). In the worst
//! cell, if the error on the node rows bounding it is at least half of the
//! error between them, the rows are already as good as the columns let them
//! be: a column is inserted at the middle of the cell's column interval;
//! otherwise a row in the middle of its row interval. After an insertion a
//! neighbouring interval more than twice as long is halved too, so that the
//! positions stay graded (the 4-point rule keeps them increasing).
//!
//! * `checks`: the options, the tolerance and the reference checked before
//!   the fit starts;
//! * `plan`: what every net is built and measured with, fixed at the start;
//! * `state`: what the growth carries from one net to the next;
//! * `round`: one growth round, from building a net to the next insertion;
//! * `build`: a net built, and the way back from one that cannot be;
//! * `deviation`: a net measured, strided while far and both ways once close;
//! * `best`: the best design met, measured in full before it is returned;
//! * `stops`: when and why the growth stops short;
//! * `next`: where the net grows next;
//! * `insert`: which column or row the scores or the chords suggest, and the
//!   graded insertion.

mod best;
mod build;
mod checks;
mod deviation;
mod insert;
mod next;
mod plan;
mod round;
mod state;
mod stops;

use self::best::measure_in_full;
use self::checks::{absolute_tolerance, check_options, check_reference};
use self::plan::Plan;
use self::round::grow;
use self::state::Growth;
use super::closest::Distances;
use super::construct::anchor_fraction;
use super::error::ReferenceFitError;
use super::initial::fit_initial;
use super::options::{Along, ReferenceFitOptions};
use super::reference::{AnchorCurve, Frame, ReferenceSurface, Swapped};
use crate::levels::design::Design;
use std::time::Instant;

/// A design fitted to a reference, and how well it fits.
#[derive(Debug, Clone)]
pub struct ReferenceFit {
    /// The design (the best reached when not within the tolerance).
    pub design: Design,
    /// Its control net, `(rows, columns)`.
    pub net: (usize, usize),
    /// The fit depth it was measured at.
    pub depth: u32,
    /// The absolute tolerance used.
    pub tolerance: f64,
    /// From every point of the design's mesh at the fit depth to the reference.
    pub to_reference: Distances,
    /// From the reference (twice as densely sampled as the mesh) to the mesh.
    pub from_reference: Distances,
    /// Whether both are within the tolerance.
    pub within: bool,
    /// Why not, when not.
    pub why: Option<String>,
    /// The initial curve's largest distance to the reference's anchor curve.
    pub initial_deviation: f64,
    /// Its control tangents.
    pub initial_tangents: usize,
    /// Nets built and measured.
    pub steps: usize,
    /// Wall-clock seconds the fit took.
    pub seconds: f64,
}

/// [`fit_reference_with`] without a progress hook.
pub fn fit_reference(
    reference: &dyn ReferenceSurface,
    opts: &ReferenceFitOptions,
) -> Result<ReferenceFit, ReferenceFitError> {
    fit_reference_with(reference, opts, &mut |_| true)
}

/// Fits a streamline design to `reference` (`docs/math.md §12`).
/// `progress` is called after every net measured with a rough fraction done
/// in `[0, 1]`; returning `false` cancels the fit
/// ([`ReferenceFitError::Cancelled`]). Ends after at most one net per
/// column and row the cap allows.
pub fn fit_reference_with(
    reference: &dyn ReferenceSurface,
    opts: &ReferenceFitOptions,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<ReferenceFit, ReferenceFitError> {
    let start = Instant::now();
    check_options(opts)?;
    let swapped = Swapped(reference);
    let r: &dyn ReferenceSurface = match opts.along {
        Along::U => reference,
        Along::V => &swapped,
    };
    let f = Frame::new(r, opts.along == Along::V)?;
    let tol = absolute_tolerance(opts.tolerance, f.diag)?;
    check_reference(&f)?;
    let fraction = anchor_fraction(opts.scheme, opts.anchor);
    let anchor = AnchorCurve::new(&f, fraction)?;
    let initial = fit_initial(&f, &anchor, 0.25 * tol)?;
    let plan = Plan::new(&f, &anchor, fraction, &initial.curve, opts, tol);
    let mut g = Growth::new(&plan);
    let why = grow(&plan, &mut g, progress)?;
    let Some(mut b) = g.best.take() else {
        return Err(ReferenceFitError::NonFinite { what: "design" });
    };
    measure_in_full(&plan, &mut g.builder, &mut g.cache, &mut b)?;
    let from = b.from.unwrap_or_default();
    let within = b.to.max <= tol && from.max <= tol;
    let why = if within {
        None
    } else {
        why.or_else(|| {
            Some(format!(
                "the design came within {:.3e} of the reference, over the tolerance {:.3e}",
                b.to.max.max(from.max),
                tol
            ))
        })
    };
    let _ = progress(1.0);
    Ok(ReferenceFit {
        net: (b.design.net().rows(), b.design.net().cols()),
        design: b.design,
        depth: opts.depth,
        tolerance: tol,
        to_reference: b.to,
        from_reference: from,
        within,
        why,
        initial_deviation: initial.deviation,
        initial_tangents: initial.curve.qi().tangents().len(),
        steps: g.steps,
        seconds: start.elapsed().as_secs_f64(),
    })
}
