//! Whether a seam's measured figures meet its continuity (docs/math.md
//! §11.3), as Alias's continuity check shows pass or fail: each figure the
//! continuity promises is held to a threshold (docs/editor.md, "Several
//! patches"):
//!
//! * position (G0 and up): the largest gap at most [`GAP_MEETS`] of the
//!   scene's size (a chain's gap is 0 by construction, a side start lies on
//!   `A`'s polyline within rounding);
//! * tangency (G1 and up): the largest normal angle at most
//!   [`ANGLE_MEETS_DEG`], the angle the export keeps across a G1 or G2 seam
//!   (docs/cad.md);
//! * curvature (G2): the curvature deviation `|(κ_A − κ_B)/(|κ_A| + |κ_B|)|`
//!   (Eq. 75) at most [`CURVATURE_MEETS`].
//!
//! Ten times the gap's threshold, five times the angle's (0.5°, CATIA's
//! default) and five times the curvature deviation's (0.5) is
//! "near": amber, a seam that holds its continuity only loosely at this
//! depth (a side G1 seam's angle halves per level, §11.2); beyond is a
//! failure: red.

use bevy::prelude::*;
use streamline_kernel::joins::{Continuity, SeamReport};

/// Largest gap that meets position continuity, as a share of the scene's size.
pub const GAP_MEETS: f64 = 1e-6;
/// Largest normal angle (degrees) that meets tangency.
pub const ANGLE_MEETS_DEG: f64 = 0.1;
/// Largest curvature deviation (in size) that meets curvature continuity.
pub const CURVATURE_MEETS: f64 = 0.1;
/// A gap up to this many times its threshold is "near".
pub const NEAR: f64 = 10.0;
/// The angle's "near" factor: 0.5°, CATIA's default tangency tolerance.
pub const ANGLE_NEAR: f64 = 5.0;
/// The curvature deviation's "near" factor: up to 0.5 (a deviation lies in
/// `[−1, 1]`; a G1 chain's stays about 0.45 at every depth, §11.3's table).
pub const CURVATURE_NEAR: f64 = 5.0;

/// What a seam's figures say of its continuity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Verdict {
    /// Every promised figure within its threshold.
    Meets,
    /// Some figure within its "near" band, none beyond.
    Near,
    /// Some figure beyond its "near" band.
    Fails,
    /// Not measured (a side not built).
    Unmeasured,
}

impl Verdict {
    /// The seam's colour in the view and the table.
    pub fn color(self) -> [u8; 3] {
        match self {
            Verdict::Meets => [60, 210, 90],
            Verdict::Near => [250, 190, 30],
            Verdict::Fails => [240, 60, 50],
            Verdict::Unmeasured => [150, 150, 155],
        }
    }

    /// As a Bevy colour.
    pub fn bevy(self) -> Color {
        let [r, g, b] = self.color();
        Color::srgb_u8(r, g, b)
    }

    /// A word for tooltips and the screenshot report.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Meets => "meets",
            Verdict::Near => "near",
            Verdict::Fails => "fails",
            Verdict::Unmeasured => "unmeasured",
        }
    }
}

/// One figure against its threshold and "near" factor.
fn grade(value: f64, meets: f64, near: f64) -> Verdict {
    if !value.is_finite() {
        Verdict::Fails
    } else if value <= meets {
        Verdict::Meets
    } else if value <= meets * near {
        Verdict::Near
    } else {
        Verdict::Fails
    }
}

/// The verdict of a seam of `continuity` whose report is `report`, in a
/// scene of size `size` (the bounding box's diagonal).
pub fn judge(report: Option<&SeamReport>, continuity: Continuity, size: f64) -> Verdict {
    let Some(r) = report else {
        return Verdict::Unmeasured;
    };
    let size = if size.is_finite() && size > 0.0 {
        size
    } else {
        1.0
    };
    let mut v = grade(r.gap, GAP_MEETS * size, NEAR);
    if continuity >= Continuity::G1 {
        v = v.max(grade(r.angle_deg, ANGLE_MEETS_DEG, ANGLE_NEAR));
    }
    if continuity >= Continuity::G2 {
        v = v.max(grade(
            r.curvature_dev.abs(),
            CURVATURE_MEETS,
            CURVATURE_NEAR,
        ));
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(gap: f64, angle_deg: f64, curvature_dev: f64) -> SeamReport {
        SeamReport {
            gap,
            angle_deg,
            curvature_dev,
            samples: Vec::new(),
        }
    }

    /// Each continuity is judged on exactly the figures it promises: a G0
    /// seam with a crease meets G0 and fails G1; a G1 seam with a curvature
    /// jump meets G1 and fails G2 (the negative controls of the label).
    #[test]
    fn a_seam_is_judged_on_what_its_continuity_promises() {
        let crease = report(0.0, 12.0, 0.9);
        assert_eq!(judge(Some(&crease), Continuity::G0, 2.0), Verdict::Meets);
        assert_eq!(judge(Some(&crease), Continuity::G1, 2.0), Verdict::Fails);
        let jump = report(0.0, 1e-9, 0.45);
        assert_eq!(judge(Some(&jump), Continuity::G1, 2.0), Verdict::Meets);
        assert_eq!(judge(Some(&jump), Continuity::G2, 2.0), Verdict::Near);
        let smooth = report(0.0, 1e-9, 0.05);
        assert_eq!(judge(Some(&smooth), Continuity::G2, 2.0), Verdict::Meets);
        assert_eq!(judge(None, Continuity::G2, 2.0), Verdict::Unmeasured);
    }

    /// The bands' edges: the gap scales with the scene, the angle does not.
    #[test]
    fn the_bands_edges() {
        let g = |gap| judge(Some(&report(gap, 0.0, 0.0)), Continuity::G0, 10.0);
        assert_eq!(g(0.99e-5), Verdict::Meets);
        assert_eq!(g(1.01e-5), Verdict::Near);
        assert_eq!(g(0.99e-4), Verdict::Near);
        assert_eq!(g(1.01e-4), Verdict::Fails);
        let a = |deg| judge(Some(&report(0.0, deg, 0.0)), Continuity::G1, 1e6);
        assert_eq!(a(0.1), Verdict::Meets);
        assert_eq!(a(0.3), Verdict::Near);
        assert_eq!(a(0.51), Verdict::Fails);
        let c = |dev| judge(Some(&report(0.0, 0.0, dev)), Continuity::G2, 1.0);
        assert_eq!(c(-0.1), Verdict::Meets);
        assert_eq!(c(-0.2), Verdict::Near);
        assert_eq!(c(0.5), Verdict::Near);
        assert_eq!(c(-0.9), Verdict::Fails);
    }

    /// No panic and no pass on figures that are not numbers.
    #[test]
    fn not_a_number_fails() {
        let r = report(f64::NAN, 0.0, 0.0);
        assert_eq!(judge(Some(&r), Continuity::G0, 1.0), Verdict::Fails);
        let r = report(0.0, f64::INFINITY, 0.0);
        assert_eq!(judge(Some(&r), Continuity::G1, f64::NAN), Verdict::Fails);
    }
}
