//! What a fit checks before it starts (`docs/math.md §12`, "Refusals"):
//! options within their ranges, a tolerance that is a positive number, and
//! a reference not closed along the streamlines, without zero-length rows,
//! poles or non-finite derivatives.

use crate::fit::construct::{initial_nodes, phantoms};
use crate::fit::error::ReferenceFitError;
use crate::fit::options::{MAX_FIT_DEPTH, MAX_NET_SIDE, ReferenceFitOptions, Tolerance};
use crate::fit::reference::Frame;

pub(super) fn check_options(opts: &ReferenceFitOptions) -> Result<(), ReferenceFitError> {
    if !(1..=MAX_FIT_DEPTH).contains(&opts.depth) {
        return Err(ReferenceFitError::BadOption {
            what: "depth",
            value: opts.depth.to_string(),
            accepted: "a fit depth from 1 to 7 (5 by default)",
        });
    }
    opts.scheme.validate()?;
    let nodes = initial_nodes(opts.scheme, opts.anchor);
    let ph = 2 * phantoms(opts.scheme);
    let (rows, cols) = opts.max_net;
    let (min_r, min_c) = (nodes.rows.len() + ph, nodes.cols.len() + ph);
    if !(min_r..=MAX_NET_SIDE).contains(&rows) || !(min_c..=MAX_NET_SIDE).contains(&cols) {
        return Err(ReferenceFitError::BadOption {
            what: "largest net",
            value: format!("{rows} × {cols}"),
            accepted: "at least the smallest net of the scheme (4 × 4, 4 × 5 anchored in the middle) and at most 64 × 64",
        });
    }
    Ok(())
}

/// The absolute tolerance `ε`: a relative one times the reference's
/// bounding-box diagonal `diag`; refused unless a positive number.
pub(super) fn absolute_tolerance(
    tolerance: Tolerance,
    diag: f64,
) -> Result<f64, ReferenceFitError> {
    let tol = match tolerance {
        Tolerance::Relative(x) => {
            if !(x.is_finite() && x > 0.0) {
                return Err(ReferenceFitError::BadTolerance { value: x });
            }
            x * diag
        }
        Tolerance::Absolute(a) => a,
    };
    if !(tol.is_finite() && tol > 0.0) {
        return Err(ReferenceFitError::BadTolerance { value: tol });
    }
    Ok(tol)
}

/// Checks that the reference is not closed along the streamlines, then its
/// edges and a grid of points for zero-length rows and poles.
pub(super) fn check_reference(f: &Frame<'_>) -> Result<(), ReferenceFitError> {
    if f.closed_along() {
        return Err(ReferenceFitError::Closed { along: f.along() });
    }
    for &v in [f.dv[0], f.dv[1]].iter() {
        let fastest = f
            .panels_u
            .iter()
            .map(|&u| f.r.derivatives(u, v)[1].length())
            .fold(0.0, f64::max);
        if fastest.is_nan() || fastest < f.min_speed {
            return Err(ReferenceFitError::ZeroLengthRow {
                edge: f.row_name(v),
                along: f.along(),
            });
        }
    }
    for &v in &f.panels_v {
        for &u in &f.panels_u {
            let [p, du, dv] = f.r.derivatives(u, v);
            if !(p.is_finite() && du.is_finite() && dv.is_finite()) {
                return Err(ReferenceFitError::NonFinite { what: "derivative" });
            }
            if du.length().is_nan() || du.length() < f.min_speed {
                return Err(f.pole(u, v));
            }
        }
    }
    Ok(())
}
