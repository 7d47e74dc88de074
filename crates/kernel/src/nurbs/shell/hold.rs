//! A face's incoming seam held (docs/math.md §11.1, §11.2, §11.5): the
//! seam's poles on the face's `v` knots, fitted once (the earlier face of a
//! chain refined onto them, or the piece of a side parent's edge), are the
//! face's first column, and for G1 and G2 its second column is held so the
//! faces' normals agree across the seam.

use super::chain::refined_v;
use super::{SeamSpec, ShellError};
use crate::joins::{Continuity, Edge};
use crate::nurbs::curve::Curve;
use crate::nurbs::knots::KnotVector;
use crate::nurbs::seam_hold::{hold, hold_side};
use crate::nurbs::surface::BSplineSurface;
use glam::DVec3;

/// How a face's poles next to its incoming seam are held for G1 and G2.
#[derive(Debug, Clone)]
pub(super) enum Smooth {
    /// G0: only the seam's poles.
    None,
    /// A chain: the earlier face on the later one's `v` knots (each row of
    /// poles made collinear across the seam with its last two columns).
    Chain(BSplineSurface),
    /// A side join: `a`'s cross derivative along the piece of its edge, a
    /// curve in `b`'s `v` (the seam's own parameter), whose normal with the
    /// seam curve is `a`'s normal there.
    Side(Curve),
}

/// A seam's poles held in a face's first column, and how its second is held.
pub(super) type Held = (Vec<DVec3>, Smooth);

/// A face's incoming seam, as its rounds hold it.
pub(super) struct Incoming<'a> {
    /// Index of the seam spec.
    pub(super) k: usize,
    /// The seam spec.
    pub(super) spec: SeamSpec,
    /// The earlier face's surface.
    pub(super) a: &'a BSplineSurface,
    /// A side seam's piece of `a`'s edge (`side::piece_and_cross`).
    pub(super) piece: Option<&'a Curve>,
    /// A side G1 seam's cross derivative of `a` along the piece.
    pub(super) cross: Option<&'a Curve>,
}

impl Incoming<'_> {
    /// The seam's poles on the knots `kv`, fitted once: a's last column
    /// (a refined onto `kv`, the same surface), or the piece of a's edge.
    pub(super) fn held_on(&self, kv: &KnotVector) -> Result<Held, ShellError> {
        let (k, s) = (self.k, self.spec);
        let unfit = |what: &str| ShellError::Seam {
            seam: k,
            problem: format!("the {what} does not fit on the shared knots"),
        };
        if s.join.edge == Edge::End {
            let a = refined_v(self.a, kv).ok_or_else(|| unfit("seam curve"))?;
            let seam = a.poles.column(a.poles.cols() - 1);
            let g1 = if s.join.continuity >= Continuity::G1 {
                Smooth::Chain(a)
            } else {
                Smooth::None
            };
            Ok((seam, g1))
        } else {
            let c = self.piece.expect("a side seam's piece");
            let refined = c.refined_to(kv).ok_or_else(|| unfit("seam piece"))?;
            let g1 = match self.cross {
                Some(d) => Smooth::Side(d.clone()),
                None => Smooth::None,
            };
            Ok((refined.poles, g1))
        }
    }
}

/// The seam held in `surface` (on the `v` knots `kv`): its poles as the
/// first column, and for G1 and G2 the second column. A chain's is
/// projected onto the lines through the earlier face's last two columns,
/// then moved along its normal as on a side seam; a side seam's is moved
/// along the earlier face's normal (`hold_side`) while `side_hold`.
pub(super) fn hold_seam(
    surface: &mut BSplineSurface,
    (poles, smooth): &Held,
    kv: &KnotVector,
    side_hold: bool,
) {
    match smooth {
        Smooth::None => hold(surface, poles, None),
        Smooth::Chain(a) => {
            let col = a.poles.cols() - 2;
            hold(surface, poles, Some((a, col)));
            // the projection leaves each row's poles collinear;
            // the cross derivatives' weights still differ row by
            // row, so the normal is then held as on a side seam
            let last = col + 1;
            let cross: Vec<DVec3> = (0..a.poles.rows())
                .map(|l| a.poles.get(l, last) - a.poles.get(l, col))
                .collect();
            let seam = Curve::new(kv, poles.clone());
            hold_side(surface, &seam, &Curve::new(kv, cross));
        }
        Smooth::Side(d) => {
            hold(surface, poles, None);
            let seam = Curve::new(kv, poles.clone());
            if side_hold {
                hold_side(surface, &seam, d);
            }
        }
    }
}
