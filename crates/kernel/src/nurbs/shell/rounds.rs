//! A face's fitting rounds (docs/math.md §10, §11): the separable
//! least-squares fit of its points on its knots with its incoming seam
//! held, measured against its check grid, and knots added where it is over
//! the tolerance: `u` spans halved (the held boundary costs those) and `v`
//! spans the column pass' residual explains split at the rows' quantiles.
//! A side G1 face whose held slope keeps it over the tolerance is fitted
//! again with the seam curve alone held, and one whose normals stay apart
//! along the seam has its `v` spans there split (`side::split_for_angle`).

use super::hold::{Held, Incoming, hold_seam};
use super::side::{MAX_V_ROUNDS, split_for_angle};
use super::{ShellError, fit_error};
use crate::nurbs::deviation::Deviation;
use crate::nurbs::fit::{Pass, fit_pass, pieces_for, split_points};
use crate::nurbs::knots::KnotVector;
use crate::nurbs::samples::Samples;
use crate::nurbs::seam_params::{ParentMap, measure_face};
use crate::nurbs::surface::BSplineSurface;

/// The most rounds of knots added to a face whose held boundary (or shared
/// `v` knots) puts it over the tolerance.
const MAX_ROUNDS: usize = 40;

/// The share of the tolerance a direction's own pass residual must reach in
/// a span over the tolerance for a face of a shell to split that span by it
/// (as `fit` weighs its directions, docs/math.md §10).
const RESIDUAL_SHARE: f64 = 0.5;

/// A face as its rounds fit it.
pub(super) struct Face<'a> {
    /// The patch's name (for its errors).
    pub(super) name: &'a str,
    /// The points fitted, with the face's row parameters.
    pub(super) data: &'a Samples,
    /// The points measured, with the face's row parameters.
    pub(super) check: &'a Samples,
    /// The absolute tolerance.
    pub(super) tol: f64,
    /// The `u` knots every round starts from (the fit alone's).
    pub(super) ku: &'a KnotVector,
    /// The degree in `v`.
    pub(super) q: usize,
    /// The earlier face across the start edge, and where the face's points
    /// near that edge lie on it (`measure_face`).
    pub(super) parent: Option<(&'a BSplineSurface, ParentMap)>,
    /// The incoming seam.
    pub(super) seam: Option<Incoming<'a>>,
    /// Whether the face is the first of its chain group (its `v` knots its
    /// own, no earlier face sharing them).
    pub(super) is_root: bool,
}

/// The face fitted from the `v` knots `kv` (module docs). Returns the
/// surface, its deviation and whether a side G1 seam's slope is held.
pub(super) fn fit_face(
    face: &Face,
    mut kv: KnotVector,
) -> Result<(BSplineSurface, Deviation, bool), ShellError> {
    let mut v_rounds = 0;
    loop {
        let (surface, dev, side_hold) = fit_holding_slope(face, &mut kv)?;
        // Eq. 76 leaves the faces' normals apart where the v knots are too
        // few: those v spans are split and the face fitted again (a side
        // patch of its own v knots: its chain, if any, is fitted after it)
        if let Some(seam) = &face.seam
            && let (Some(c), Some(d)) = (seam.piece, seam.cross)
            && side_hold
            && face.is_root
            && v_rounds < MAX_V_ROUNDS
            && split_for_angle(&surface, c, d, &face.data.v, &mut kv, seam.k)?
        {
            v_rounds += 1;
            continue;
        }
        return Ok((surface, dev, side_hold));
    }
}

/// The face's rounds with its seam held; a side G1 seam whose held slope
/// keeps the face off its points beyond the tolerance is fitted again with
/// the seam curve alone held (the faces then meet G0 in the file, within
/// the tolerance). `kv` ends as the `v` knots of the round kept. Returns
/// the surface, its deviation and whether the slope is held.
fn fit_holding_slope(
    face: &Face,
    kv: &mut KnotVector,
) -> Result<(BSplineSurface, Deviation, bool), ShellError> {
    let is_side = face.seam.as_ref().is_some_and(|s| s.cross.is_some());
    let mut side_hold = true;
    loop {
        let (surface, dev) = rounds(face, kv, side_hold)?;
        // the knots of the round kept
        *kv = surface.knots_v.clone();
        if dev.max > face.tol && is_side && side_hold {
            side_hold = false;
            continue;
        }
        return Ok((surface, dev, side_hold));
    }
}

/// Rounds that refine where the held boundary costs the tolerance, from
/// the fit alone's `u` knots and the `v` knots `kv` (which gain the `v`
/// knots added): each fits the points, holds the seam (`hold_seam`, its
/// slope while `side_hold`), measures the face (`measure`) and adds knots
/// where it is over the tolerance (`split_spans`), until it is within the
/// tolerance, no knot is added or `MAX_ROUNDS` is reached. Returns the best
/// round's surface and deviation.
fn rounds(
    face: &Face,
    kv: &mut KnotVector,
    side_hold: bool,
) -> Result<(BSplineSurface, Deviation), ShellError> {
    let mut ku = face.ku.clone();
    let mut rounds = 0;
    let mut held: Option<(KnotVector, Option<Held>)> = None;
    let mut best: Option<(BSplineSurface, Deviation)> = None;
    loop {
        if held.as_ref().is_none_or(|(k, _)| *k != *kv) {
            let on_kv = face.seam.as_ref().map(|s| s.held_on(kv)).transpose()?;
            held = Some((kv.clone(), on_kv));
        }
        let pass = match (fit_pass(face.data, &ku, kv), best.take()) {
            (Ok(s), before) => {
                best = before;
                s
            }
            // a split left a span without data: keep the best round
            (Err(_), Some(before)) => return Ok(before),
            (Err(e), None) => return Err(fit_error(face.name, e)),
        };
        let mut surface = pass.surface.clone();
        if let Some((_, Some(seam))) = &held {
            hold_seam(&mut surface, seam, kv, side_hold);
        }
        let (dev, span_u, span_v) = measure(&surface, face);
        if best.as_ref().is_none_or(|(_, b)| dev.max < b.max) {
            best = Some((surface, dev));
        }
        if dev.max <= face.tol || rounds >= MAX_ROUNDS || ku.count() >= face.data.u.len() {
            return Ok(best.take().expect("this round's at least"));
        }
        rounds += 1;
        if !split_spans(face, &pass, &span_u, &span_v, &mut ku, kv) {
            return Ok(best.take().expect("kept above"));
        }
    }
}

/// `surface` measured as the shell measures a face: at its check grid,
/// and, where that is within the tolerance, at the fitted points too
/// (foot points one depth finer promise nothing for them). Returns the
/// deviation and the largest distance per `u` and per `v` span.
fn measure(surface: &BSplineSurface, face: &Face) -> (Deviation, Vec<f64>, Vec<f64>) {
    let (mut dev, mut span_u, mut span_v) =
        measure_face(surface, face.check, face.tol, face.parent);
    if dev.max <= face.tol {
        let at_data = measure_face(surface, face.data, face.tol, face.parent);
        if at_data.0.max > face.tol {
            (dev, span_u, span_v) = at_data;
        }
    }
    (dev, span_u, span_v)
}

/// The next round's knots where the face is over the tolerance (its
/// largest distance per span `span_u`, `span_v`), added to `ku` and `kv`;
/// whether one was added.
///
/// `v` spans over the tolerance that the column pass' own residual
/// explains are split at the rows' quantiles, as the fit alone splits them
/// (docs/math.md §10): held boundaries cost `u` spans, and splitting those
/// cannot bring a row the `v` knots miss within the tolerance. `u` spans
/// over the tolerance are halved (at most as many knots as the grid has
/// room for); while `v` spans are split, only those the row pass' residual
/// explains.
fn split_spans(
    face: &Face,
    pass: &Pass,
    span_u: &[f64],
    span_v: &[f64],
    ku: &mut KnotVector,
    kv: &mut KnotVector,
) -> bool {
    let (data, tol) = (face.data, face.tol);
    let res_v = pass.residuals_v(data);
    let mut new_v = Vec::new();
    for j in (0..span_v.len()).filter(|&j| span_v[j] > tol) {
        if res_v[j] >= RESIDUAL_SHARE * tol {
            let pieces = pieces_for(res_v[j], tol, face.q);
            split_points(kv, &data.v, j, pieces, &mut new_v);
        }
    }
    let room = data.u.len() - ku.count();
    let res_u = if new_v.is_empty() {
        Vec::new()
    } else {
        pass.residuals_u(data)
    };
    let mids: Vec<f64> = (0..span_u.len())
        .filter(|&j| span_u[j] > tol)
        .filter(|&j| new_v.is_empty() || res_u[j] >= RESIDUAL_SHARE * tol)
        .map(|j| {
            let (lo, hi) = ku.span_range(j);
            0.5 * (lo + hi)
        })
        .take(room)
        .collect();
    let mut grew = false;
    for u in mids {
        grew |= ku.insert(u);
    }
    for v in new_v {
        grew |= kv.insert(v);
    }
    grew
}
