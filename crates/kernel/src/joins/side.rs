//! Side joins, `edge: First | Last` (docs/math.md §11.2): the parameter
//! switch, `B`'s streamlines leave `A`'s first or last streamline across it.
//! At every depth `d`, `B`'s row `j` starts at the point of `A`'s streamline of
//! depth `d` at arc length `t_j` (Eq. 71, G0). G1 projects `B`'s first-column
//! tangents onto the great circle perpendicular to `A`'s normal there after
//! every subdivision step, before the next (Eq. 73), so the seam's normal
//! angle shrinks as the mesh is refined. G2 is refused (future work).

use crate::joins::chain::ROW_TOLERANCE;
use crate::joins::edge_curve::EdgeCurve;
use crate::joins::error::JoinError;
use crate::joins::kinds::{Continuity, Edge};
use crate::joins::parts::PatchParts;
use crate::joins::stack::{Stack, levels_with, place_at_starts};
use glam::DVec3;

/// A first-column tangent within this sine of `A`'s normal (about 1e-6 rad)
/// has no usable projection into `A`'s tangent plane: the side G1 join is
/// refused there (the projection's direction would carry the rounding of
/// `b − (b·n) n` magnified by `1/|b − (b·n) n|`).
pub const ALONG_NORMAL_SIN: f64 = 1e-6;

/// `B` started on `A`'s edge `First` or `Last` with G0 or G1, built to `A`'s
/// depth (`a` is `A`'s [`Stack`]). `B`'s `t` must increase strictly inside
/// `[0, L]`, `L` the length of `A`'s streamline at level 0, and its anchor
/// must be 0; at every depth `σ` is the first column's `s`. `B`'s details
/// apply after each step, before the G1 projection, and its fine tuning
/// places each row from its start point (docs/math.md §5, §6).
pub fn side<'b>(
    a: &Stack,
    b: impl Into<PatchParts<'b>>,
    edge: Edge,
    continuity: Continuity,
) -> Result<Stack, JoinError> {
    let parts = b.into();
    let b = parts.design;
    if edge == Edge::End {
        return Err(JoinError::NotASideEdge);
    }
    if continuity == Continuity::G2 {
        return Err(JoinError::SideG2);
    }
    if b.anchor() != 0 {
        return Err(JoinError::AnchorNotFirst { anchor: b.anchor() });
    }
    let curves: Vec<EdgeCurve> = (0..=a.depth())
        .map(|d| EdgeCurve::of(a, d, edge).expect("a side edge of a built depth"))
        .collect();
    check_rows(&b.params().t, curves[0].length())?;
    let levels = levels_with(b, parts.details, a.depth(), |d, level| {
        for r in 0..level.tangents.rows() {
            level.params.sigma[r] = level.params.s.get(r, 0);
        }
        if continuity == Continuity::G1 {
            let curve = &curves[d as usize];
            for r in 0..level.tangents.rows() {
                let t = level.params.t[r];
                let projected = project(level.tangents.get(r, 0), curve.normal(t))
                    .ok_or(JoinError::SideTangentAlongNormal { row: r, level: d })?;
                level.tangents.set(r, 0, projected);
            }
        }
        Ok::<(), JoinError>(())
    })?;
    let points = levels
        .iter()
        .zip(&curves)
        .map(|(level, curve)| {
            let starts: Vec<DVec3> = level.params.t.iter().map(|&t| curve.point(t)).collect();
            place_at_starts(level, &starts, parts.tuning)
        })
        .collect();
    Ok(Stack { levels, points })
}

/// `B`'s row parameters: strictly increasing, inside `[0, length]` (to
/// [`ROW_TOLERANCE`] times the length).
pub(crate) fn check_rows(t: &[f64], length: f64) -> Result<(), JoinError> {
    let slack = ROW_TOLERANCE * length.max(1.0);
    for (row, &v) in t.iter().enumerate() {
        if !(-slack..=length + slack).contains(&v) {
            return Err(JoinError::SideParamOutside { row, t: v, length });
        }
        if row > 0 && v <= t[row - 1] {
            return Err(JoinError::SideParamsNotIncreasing { row });
        }
    }
    Ok(())
}

/// `b` projected onto the great circle perpendicular to `n` (Eq. 73):
/// `(b − (b·n) n)/|…|`; `None` within [`ALONG_NORMAL_SIN`] of `±n`. Where `A`'s
/// normal vanishes (a collapsed edge) `b` is kept.
pub(crate) fn project(b: DVec3, n: Option<DVec3>) -> Option<DVec3> {
    let Some(n) = n else {
        return Some(b);
    };
    let p = b - n * b.dot(n);
    let len = p.length();
    (len >= ALONG_NORMAL_SIN).then(|| p / len)
}
