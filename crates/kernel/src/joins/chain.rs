//! Chains, `edge: End`, with G0 or G1 (docs/math.md §11.1): `B`'s rows are
//! `A`'s rows and, at every depth, `B`'s streamline `j` starts exactly at
//! `A`'s streamline `j`'s last point (Eq. 66). G1 also makes `B`'s first
//! column `A`'s last at every depth (Eq. 67), so the seam's two Eq. 65
//! segments of every row are parallel and its normals agree. G2 is one merged
//! net: [`crate::joins::merged`].

use crate::analysis::angle_between;
use crate::joins::error::JoinError;
use crate::joins::kinds::Continuity;
use crate::joins::parts::PatchParts;
use crate::joins::stack::{Stack, levels_with, place_at_starts};
use crate::levels::design::Design;
use crate::levels::surface::{BlendOrder, SurfaceScheme};

/// How far a chained patch's row `t` (and, for G1/G2, its seam column) may
/// be from `A`'s: the scene's files keep them to this (docs/math.md §11.1).
pub const ROW_TOLERANCE: f64 = 1e-12;

/// The scheme as a message names it (`kobbelt (omega 1)`, `catmull-clark`, …),
/// with the blend order when `order` is given.
pub(crate) fn scheme_label(scheme: SurfaceScheme, order: Option<BlendOrder>) -> String {
    let mut out = match scheme {
        SurfaceScheme::Kobbelt { omega } => format!("kobbelt (omega {omega})"),
        other => other.name().to_string(),
    };
    if let Some(o) = order {
        out.push_str(", ");
        out.push_str(o.name());
    }
    out
}

/// The checks every chain makes (docs/math.md §11.1, "Bad input"): the same
/// scheme and ω (and, for G2, blend order), the same rows, `B`'s anchor 0,
/// and for G1/G2 `B`'s first control column equal to `A`'s last.
pub(crate) fn check_chain(a: &Design, b: &Design, continuity: Continuity) -> Result<(), JoinError> {
    if continuity == Continuity::G2 && (a.scheme() != b.scheme() || a.order() != b.order()) {
        return Err(JoinError::G2SchemeDiffers {
            a: scheme_label(a.scheme(), Some(a.order())),
            b: scheme_label(b.scheme(), Some(b.order())),
        });
    }
    if a.scheme() != b.scheme() {
        return Err(JoinError::ChainSchemeDiffers {
            a: scheme_label(a.scheme(), None),
            b: scheme_label(b.scheme(), None),
        });
    }
    let (ta, tb) = (&a.params().t, &b.params().t);
    if ta.len() != tb.len() {
        return Err(JoinError::ChainRowCount {
            a: ta.len(),
            b: tb.len(),
        });
    }
    if let Some(row) = (0..ta.len()).find(|&r| (ta[r] - tb[r]).abs() > ROW_TOLERANCE) {
        return Err(JoinError::ChainRowParam {
            row,
            a: ta[row],
            b: tb[row],
        });
    }
    if b.anchor() != 0 {
        return Err(JoinError::AnchorNotFirst { anchor: b.anchor() });
    }
    if continuity >= Continuity::G1 {
        let last = a.net().cols() - 1;
        for row in 0..ta.len() {
            let (u, v) = (a.net().get(row, last), b.net().get(row, 0));
            if (u - v).abs().max_element() > ROW_TOLERANCE {
                return Err(JoinError::SeamColumnDiffers {
                    row,
                    angle_deg: angle_between(u, v).to_degrees(),
                });
            }
        }
    }
    Ok(())
}

/// `B` chained to `A` on `A`'s edge `End` with G0 or G1, built to `A`'s depth
/// (`a` is `a_design`'s [`Stack`]). At every depth `d`, `B`'s row `t` are `A`'s
/// (copied, so equal bit for bit), its `σ` is its first column's `s`, and
/// its row `j` starts at `A`'s point `(j, last)` bit for bit (Eq. 66). G1
/// puts `A`'s last column of level `d` into `B`'s first before the next step
/// (Eq. 67; a no-op for Kobbelt, whose 4-point rule refines a boundary column
/// by itself). For G2 use [`crate::joins::merged::g2_run`].
///
/// `B`'s details apply after each step, before the G1 column (a detail on
/// the seam column is `A`'s, docs/math.md §11.1), and its fine tuning
/// places each row from its start point (docs/math.md §6).
pub fn chain<'b>(
    a_design: &Design,
    a: &Stack,
    b: impl Into<PatchParts<'b>>,
    continuity: Continuity,
) -> Result<Stack, JoinError> {
    let parts = b.into();
    let b = parts.design;
    if continuity == Continuity::G2 {
        return Err(JoinError::G2IsOneNet);
    }
    check_chain(a_design, b, continuity)?;
    let levels = levels_with(b, parts.details, a.depth(), |d, level| {
        let al = &a.levels[d as usize];
        level.params.t.clone_from(&al.params.t);
        for r in 0..level.tangents.rows() {
            level.params.sigma[r] = level.params.s.get(r, 0);
        }
        if continuity == Continuity::G1 {
            let last = al.tangents.cols() - 1;
            for r in 0..level.tangents.rows() {
                level.tangents.set(r, 0, al.tangents.get(r, last));
            }
        }
        Ok::<(), JoinError>(())
    })?;
    let points = levels
        .iter()
        .zip(&a.points)
        .map(|(level, ap)| {
            let starts = ap.column(ap.cols() - 1);
            place_at_starts(level, &starts, parts.tuning)
        })
        .collect();
    Ok(Stack { levels, points })
}
