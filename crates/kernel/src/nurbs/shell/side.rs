//! A side seam (docs/math.md §11.2, §11.5): the piece of the parent's
//! boundary curve a later face starts on, the parent's cross derivative
//! along it, and the later face's `v` spans split where the least squares
//! of Eq. 76 leaves the faces' normals apart.

use super::{SeamSpec, ShellError};
use crate::joins::{Continuity, Edge};
use crate::nurbs::curve::Curve;
use crate::nurbs::fit::FitOptions;
use crate::nurbs::knots::KnotVector;
use crate::nurbs::seam_hold::{seam_angles, side_cross};
use crate::nurbs::surface::BSplineSurface;

/// The largest angle between the faces' normals along a side G1 seam that
/// the least squares of Eq. 76 may leave before the later face's `v` spans
/// there are split (a quarter of the 0.1° asked, docs/math.md §11.5).
const SEAM_ANGLE_DEG: f64 = 0.025;

/// The most times a side G1 face's `v` knots are split for its seam's angle.
pub(super) const MAX_V_ROUNDS: usize = 6;

/// The piece of `a`'s edge that seam `k` (a side seam over `range`) is.
fn side_piece(
    a: &BSplineSurface,
    s: SeamSpec,
    (u0, u1): (f64, f64),
    opts: &FitOptions,
    k: usize,
) -> Result<Curve, ShellError> {
    let r = if s.join.edge == Edge::First {
        0
    } else {
        a.poles.rows() - 1
    };
    let edge = Curve::new(&a.knots_u, a.poles.row(r).to_vec());
    if opts.degree.0 != opts.degree.1 {
        return Err(ShellError::Seam {
            seam: k,
            problem: "a side join needs the same degree in u and v (the seam is a u curve of one face and a v curve of the other)".into(),
        });
    }
    Ok(if u0 < u1 {
        edge.piece(u0, u1)
    } else {
        edge.piece(u1, u0).reversed()
    })
}

/// Side seam `k` (`s`, over `range` of `a`'s edge): the piece of `a`'s edge
/// (`side_piece`) and, for G1, `a`'s cross derivative along it (`side_cross`).
pub(super) fn piece_and_cross(
    a: &BSplineSurface,
    s: SeamSpec,
    range: (f64, f64),
    opts: &FitOptions,
    k: usize,
) -> Result<(Option<Curve>, Option<Curve>), ShellError> {
    let piece = side_piece(a, s, range, opts, k)?;
    let cross = if s.join.continuity >= Continuity::G1 {
        Some(side_cross(a, s.join.edge, range))
    } else {
        None
    };
    Ok((Some(piece), cross))
}

/// Eq. 76 is a least squares: where the face's `v` knots `kv` are too few
/// for the turning of the earlier face's normal it leaves a residual angle;
/// the `v` spans over `SEAM_ANGLE_DEG` whose halves both hold rows `rows`
/// are halved (the seam `piece` refined onto `kv`, `cross` the earlier
/// face's cross derivative). Returns whether a knot was added; `seam` names
/// the incoming seam in the error.
pub(super) fn split_for_angle(
    surface: &BSplineSurface,
    piece: &Curve,
    cross: &Curve,
    rows: &[f64],
    kv: &mut KnotVector,
    seam: usize,
) -> Result<bool, ShellError> {
    let on_kv = piece.refined_to(kv).ok_or_else(|| ShellError::Seam {
        seam,
        problem: "the seam piece does not fit on the shared knots".into(),
    })?;
    let spans = seam_angles(surface, &on_kv, cross);
    let holds = |lo: f64, hi: f64| rows.iter().any(|x| *x > lo && *x < hi);
    let mids: Vec<f64> = (0..spans.len())
        .filter(|&j| spans[j] > SEAM_ANGLE_DEG)
        .map(|j| kv.span_range(j))
        .filter(|&(lo, hi)| holds(lo, 0.5 * (lo + hi)) && holds(0.5 * (lo + hi), hi))
        .map(|(lo, hi)| 0.5 * (lo + hi))
        .collect();
    let mut grew = false;
    for m in mids {
        grew |= kv.insert(m);
    }
    Ok(grew)
}
