//! Exact starting designs (`docs/math.md §9`, Templates).
//!
//! * `Flat { width: W }`: every control tangent `+x`, every initial tangent
//!   `+y`, origin 0, streamline length `L`: the rectangle `[0, L] × [0, W]` in
//!   `z = 0` at every depth (all tangents equal, so every streamline is the
//!   straight segment of its length, Eq. 65).
//! * `Cylinder { radius: r, degrees: φ }`: control tangents `+x`; the initial
//!   curve is the arc of radius `r` and angle `φ` in the plane `x = 0`, from 0
//!   with tangent `+y`, bending towards `+z` (centre `(0, 0, r)`), length `rφ`.
//!   Its QI tangents lie on the great circle `x = 0` at the angles
//!   `φ·ξ_i`, `ξ_i = (u_{i+1} + … + u_{i+k−1})/(k − 1)` the Greville abscissae
//!   of the curve's clamped uniform knots. A QI curve on one great circle is
//!   the planar B-spline of its angles (docs/math.md §2), and a clamped B-spline with
//!   control values at the Greville abscissae is the linear function itself,
//!   so the tangent angle is exactly `φ·u`: the tangent of the circle. The
//!   only error left is the initial curve's quadrature (far below `1e-12 r`,
//!   tested). Every streamline is a straight segment along `x` from a point
//!   of that arc, so every point of every depth lies on `y² + (z − r)² = r²`.
//!
//! The initial curve has order 3 and enough tangents that neighbours are at
//! most 60° apart (at least 4, so the designer has handles to shape).

use super::{check_length, check_net_size};
use crate::curve::qi::QiCurve;
use crate::error::KernelError;
use crate::grid::Grid;
use crate::levels::design::Design;
use crate::levels::params::ParamGrid;
use crate::levels::surface::{BlendOrder, SurfaceScheme};
use crate::streamline::initial_curve::InitialCurve;
use glam::DVec3;

/// The order of a template's initial curve.
pub const TEMPLATE_ORDER: usize = 3;

/// The fewest initial tangents a template gets.
pub const TEMPLATE_MIN_INITIAL: usize = 4;

/// The largest angle between neighbouring initial tangents of a cylinder, degrees.
pub const TEMPLATE_MAX_STEP_DEGREES: f64 = 60.0;

/// A starting shape for a new design.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Template {
    /// The flat rectangle `[0, L] × [0, width]` in `z = 0`.
    Flat {
        /// Its extent across the streamlines (`y`).
        width: f64,
    },
    /// Part of the cylinder `y² + (z − radius)² = radius²` about the `x` axis
    /// line `(·, 0, radius)`, over an angle of `degrees` (strictly between 0 and 360).
    Cylinder {
        /// The radius.
        radius: f64,
        /// The angle of the arc, degrees.
        degrees: f64,
    },
}

impl Template {
    /// The initial curve's tangents and its length.
    fn initial(self) -> Result<(Vec<DVec3>, f64), KernelError> {
        match self {
            Template::Flat { width } => {
                let w = check_length("template width", width)?;
                Ok((vec![DVec3::Y; TEMPLATE_MIN_INITIAL], w))
            }
            Template::Cylinder { radius, degrees } => {
                let r = check_length("template radius", radius)?;
                if !(degrees.is_finite() && degrees > 0.0 && degrees < 360.0) {
                    return Err(KernelError::AngleOutOfRange {
                        what: "template angle",
                        degrees,
                        lo: 0.0,
                        hi: 360.0,
                    });
                }
                let phi = degrees.to_radians();
                let length = check_length("template arc length (radius × angle)", r * phi)?;
                let n = greville_count(degrees);
                let angles = greville_angles(n, phi)?;
                let tangents = angles
                    .iter()
                    .map(|&a| DVec3::new(0.0, a.cos(), a.sin()))
                    .collect();
                Ok((tangents, length))
            }
        }
    }
}

/// How many initial tangents an arc of `degrees` gets: order-3 clamped
/// uniform knots with `spans` spans have Greville gaps `1/spans` inside (half
/// at the ends), so `spans = ⌈φ / 60°⌉` keeps neighbours within 60°.
fn greville_count(degrees: f64) -> usize {
    let spans = (degrees / TEMPLATE_MAX_STEP_DEGREES).ceil().max(1.0) as usize;
    (spans + TEMPLATE_ORDER - 1).max(TEMPLATE_MIN_INITIAL)
}

/// `φ·ξ_i` for the `n` Greville abscissae of the QI curve's own knot vector
/// (order [`TEMPLATE_ORDER`]).
pub(crate) fn greville_angles(n: usize, phi: f64) -> Result<Vec<f64>, KernelError> {
    let k = TEMPLATE_ORDER;
    let q = QiCurve::new(&vec![DVec3::Y; n], k)?;
    let u = q.knots();
    Ok((0..n)
        .map(|i| phi * u[i + 1..i + k].iter().sum::<f64>() / (k - 1) as f64)
        .collect())
}

impl Design {
    /// A new `rows × cols` design from a template (`docs/math.md §9`):
    /// control tangents `+x`, uniform parameters (`s` from 0 to `length` along
    /// each row, `t` from 0 to the initial curve's length across), anchor 0.
    /// Refused: a side outside `2 ..= 64`, a length or width or radius that is
    /// not positive, a cylinder angle outside `(0°, 360°)`.
    pub fn from_template(
        rows: usize,
        cols: usize,
        length: f64,
        template: Template,
        scheme: SurfaceScheme,
        order: BlendOrder,
    ) -> Result<Design, KernelError> {
        check_net_size(rows, cols)?;
        let length = check_length("streamline length", length)?;
        let (tangents, width) = template.initial()?;
        let initial = InitialCurve::new(&tangents, TEMPLATE_ORDER, width, DVec3::ZERO)?;
        let params = ParamGrid::uniform(rows, cols, length, width, 0, scheme)?;
        Design::new(
            &Grid::filled(rows, cols, DVec3::X),
            params.s,
            params.t,
            0,
            scheme,
            order,
            initial,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn greville_counts_keep_steps_within_60_degrees() {
        for (deg, n) in [(1.0, 4), (90.0, 4), (120.0, 4), (121.0, 5), (359.0, 8)] {
            assert_eq!(greville_count(deg), n, "{deg}°");
            let a = greville_angles(n, f64::to_radians(deg)).unwrap();
            let step = a.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
            assert!(step.to_degrees() <= 60.0 + 1e-9, "{deg}°: step {step}");
            assert_eq!(a[0], 0.0);
            assert!((a[n - 1] - deg.to_radians()).abs() < 1e-15);
        }
    }
}
