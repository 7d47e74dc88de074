//! The initial curve of a fitted design (`docs/math.md §12`): a QI curve
//! (§2) of order 4 whose length is the anchor curve's and whose control
//! tangents are fitted so that its tangent equals the anchor curve's unit
//! tangent at the Greville abscissae `ξ_i` of its knots — progressive
//! interpolation on one curve, `t_i ← Rot(t(ξ_i) → T_C(ξ_i L)) t_i`
//! (eq. 12.4), the sphere iteration of §7. The number of control tangents
//! doubles (in spans) until the curve's points are within a quarter of the
//! tolerance of the anchor curve's at the ends of its quadrature panels,
//! then the fewest control tangents between the last count short of that
//! and the first within it that come within an eighth (bisection).

use super::error::ReferenceFitError;
use super::reference::{AnchorCurve, Frame};
use crate::curve::qi::QiCurve;
use crate::streamline::initial_curve::InitialCurve;
use glam::{DQuat, DVec3};

/// The QI order of a fitted initial curve (cubic angles, like a cubic B-spline).
pub const INITIAL_ORDER: usize = 4;

/// The most control tangents a fitted initial curve gets.
pub const MAX_INITIAL_TANGENTS: usize = 259;

/// Sphere iterations at most per fit of the QI tangents.
const MAX_ITERATIONS: usize = 200;

/// The fitted initial curve and how close it came.
#[derive(Debug, Clone)]
pub(crate) struct FittedInitial {
    pub curve: InitialCurve,
    /// Largest distance from the QI curve to the anchor curve at the check points.
    pub deviation: f64,
}

/// Greville abscissae of a QI curve's knots.
fn greville(q: &QiCurve) -> Vec<f64> {
    let (k, u) = (q.order(), q.knots());
    (0..q.tangents().len())
        .map(|i| u[i + 1..i + k].iter().sum::<f64>() / (k - 1) as f64)
        .collect()
}

fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// QI tangents whose curve's tangent at the Greville abscissae is `target`.
fn fit_tangents(
    f: &Frame<'_>,
    anchor: &AnchorCurve,
    n: usize,
) -> Result<Vec<DVec3>, ReferenceFitError> {
    let k = INITIAL_ORDER.min(n);
    let len = anchor.length();
    let xi = greville(&QiCurve::new(&vec![DVec3::X; n], k)?);
    let mut target = Vec::with_capacity(n);
    for &x in &xi {
        let v = anchor.v_exact(f, x * len)?;
        target.push(anchor.unit_tangent(f, v)?);
    }
    let mut t = target.clone();
    let mut best = (f64::INFINITY, t.clone());
    for _ in 0..MAX_ITERATIONS {
        let q = QiCurve::new(&t, k)?;
        let mut worst = 0.0f64;
        let mut next = t.clone();
        for i in 0..n {
            let cur = q.tangent(xi[i]);
            worst = worst.max(angle(cur, target[i]));
            next[i] = (DQuat::from_rotation_arc(cur, target[i]) * t[i]).normalize();
        }
        if worst < best.0 {
            best = (worst, t.clone());
        }
        if worst < 1e-13 {
            break;
        }
        t = next;
    }
    Ok(best.1)
}

/// Fits the initial curve to the anchor curve within `tolerance`, or as
/// close as [`MAX_INITIAL_TANGENTS`] tangents come.
pub(crate) fn fit_initial(
    f: &Frame<'_>,
    anchor: &AnchorCurve,
    tolerance: f64,
) -> Result<FittedInitial, ReferenceFitError> {
    let len = anchor.length();
    let origin = AnchorCurve::point(f, anchor.fraction, f.dv[0])?;
    // check points: the ends of the anchor curve's quadrature panels, whose
    // arc lengths are summed exactly
    let ts = anchor.table.s.clone();
    let mut want = Vec::with_capacity(ts.len());
    for &v in &anchor.table.x {
        want.push(AnchorCurve::point(f, anchor.fraction, v)?);
    }
    let spans = f.r.breaks_v().len() + 1;
    let fit = |n: usize| -> Result<FittedInitial, ReferenceFitError> {
        let tangents = fit_tangents(f, anchor, n)?;
        let curve = InitialCurve::new(&tangents, INITIAL_ORDER.min(n), len, origin)?;
        let deviation = ts
            .iter()
            .zip(&want)
            .map(|(&t, w)| curve.point(t).distance(*w))
            .fold(0.0, f64::max);
        Ok(FittedInitial { curve, deviation })
    };
    let mut n = (spans + INITIAL_ORDER - 1).max(INITIAL_ORDER);
    let mut best: Option<FittedInitial> = None;
    // the last count that was not within the tolerance
    let mut short = None;
    loop {
        let got = fit(n)?;
        let within = got.deviation <= tolerance;
        if best.as_ref().is_none_or(|b| got.deviation < b.deviation) {
            best = Some(got);
        }
        let next = 2 * n - INITIAL_ORDER + 1;
        if within || next > MAX_INITIAL_TANGENTS {
            break;
        }
        short = Some(n);
        n = next;
    }
    // the doubling overshoots: the fewest tangents between the last count
    // short of the tolerance and the first within it that come within half
    // of it (bisection; fewer handles for the designer to hold, and the
    // other half left to the net, which then grows no larger)
    if let (Some(mut lo), Some(b)) = (short, best.as_ref())
        && b.deviation <= 0.5 * tolerance
    {
        let mut hi = n;
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            let got = fit(mid)?;
            if got.deviation <= 0.5 * tolerance {
                hi = mid;
                best = Some(got);
            } else {
                lo = mid;
            }
        }
    }
    best.ok_or(ReferenceFitError::NonFinite {
        what: "initial curve",
    })
}
