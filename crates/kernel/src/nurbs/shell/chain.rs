//! A chain's shared `v` knots (docs/math.md §11.1): every patch of a chain
//! group is fitted on one `v` knot vector, each later face on the group's
//! knots so far and its own, and the earlier faces are then refined onto
//! the later face's knots by knot insertion (the same surfaces).

use super::{ShellError, ShellFace};
use crate::grid::Grid;
use crate::nurbs::curve::Curve;
use crate::nurbs::knots::KnotVector;
use crate::nurbs::seam_params::merge_knots;
use crate::nurbs::surface::BSplineSurface;
use glam::DVec3;

/// `s` on the `v` knots `kv` (which hold its own): every column of poles
/// refined by knot insertion (Piegl & Tiller Algorithm A5.1), the same
/// surface; `None` when `kv` lacks one of `s`'s knots.
pub(super) fn refined_v(s: &BSplineSurface, kv: &KnotVector) -> Option<BSplineSurface> {
    let cols = s.poles.cols();
    let columns: Vec<Vec<DVec3>> = (0..cols)
        .map(|c| {
            Some(
                Curve::new(&s.knots_v, s.poles.column(c))
                    .refined_to(kv)?
                    .poles,
            )
        })
        .collect::<Option<_>>()?;
    let rows = kv.count();
    let data = (0..rows * cols)
        .map(|n| columns[n % cols][n / cols])
        .collect();
    Some(BSplineSurface {
        knots_u: s.knots_u.clone(),
        knots_v: kv.clone(),
        poles: Grid::new(rows, cols, data).ok()?,
    })
}

/// The `v` knots a face must hold: a root's are the knots of the piece of
/// its parent's edge it starts on (`piece`, if any), a chain's later
/// patch's are the group's so far (`group`: they carry its seam curve).
pub(super) fn required_v_knots(
    is_root: bool,
    piece: Option<&Curve>,
    group: Option<&KnotVector>,
) -> Vec<f64> {
    if is_root {
        piece
            .map(|c| c.knots[c.degree + 1..c.knots.len() - c.degree - 1].to_vec())
            .unwrap_or_default()
    } else {
        group
            .expect("made at the group's first patch")
            .interior()
            .to_vec()
    }
}

/// The `v` knots (of degree `degree`) a face's rounds start from: the
/// `required` ones and those of its fit alone (`alone`), kept a row spacing
/// of its rows `rows` apart; `seam` names the incoming seam in the error.
pub(super) fn start_v_knots(
    rows: &[f64],
    alone: &KnotVector,
    required: &[f64],
    degree: usize,
    seam: usize,
) -> Result<KnotVector, ShellError> {
    let gap = rows.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    let knots = merge_knots(required, alone.interior(), gap);
    KnotVector::with_interior(degree, &knots).ok_or_else(|| ShellError::Seam {
        seam,
        problem: "the shared v knots are not increasing inside (0, 1)".into(),
    })
}

/// The faces before face `i` in its chain group (`root`: each patch's
/// group) refined onto its `v` knots `kv` (knots inserted, the same
/// surfaces), each seam curve by the same insertions as the later face's
/// copy of it; `seam` names face `i`'s incoming seam in the error.
pub(super) fn refine_group(
    faces: &mut [ShellFace],
    root: &[usize],
    i: usize,
    kv: &KnotVector,
    seam: usize,
) -> Result<(), ShellError> {
    for m in (0..i).filter(|&m| root[m] == root[i]) {
        if faces[m].surface.knots_v != *kv {
            faces[m].surface =
                refined_v(&faces[m].surface, kv).ok_or_else(|| ShellError::Seam {
                    seam,
                    problem: "the shared v knots do not hold an earlier face's".into(),
                })?;
        }
    }
    Ok(())
}
