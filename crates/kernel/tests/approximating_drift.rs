//! docs/math.md §11.5, "Where it does not reach": why a Catmull–Clark or
//! Doo–Sabin streamline moves between depths by a length that halves per
//! depth, and what would make it converge.
//!
//! An approximating scheme shortens the row: its first parameter `s₀` of
//! depth `d` climbs towards the limit start `a` (the cubic B-spline's
//! `(s₀ + 4s₁ + s₂)/6`, Chaikin's `(s₀ + s₁)/2` of level 0), while the anchor
//! `σ` stays at level 0's `s₀`. The placement (Eqs. 1–2,
//! `streamline::integrate::place_slice`) reaches `σ` by extending the
//! polyline back along the level's first tangent `t₀` over `s₀ − σ`, a
//! length that tends to `a − σ`, not to 0; `t₀` turns by a sample spacing's
//! worth each depth, so the whole row moves by `O(h)`: halving per depth.
//! Anchored instead at the limit start, the polyline's own point at `a`
//! placed at `σ`'s point plus the limit tangent `t_a` times `a − σ` (both
//! the same at every depth), the row moves only by the integration's
//! `O(h²)`: quartering per depth. The figures are measured here on a
//! streamline that bends unevenly in a plane, where the planar limit masks
//! are exact (docs/math.md §2: the great-circle reduction).

use streamline_kernel::DVec3;
use streamline_kernel::curve::scheme::{CurveScheme, subdivide};
use streamline_kernel::streamline::integrate::place_into;

/// The largest distance from a point of `fine` to the polyline `coarse`.
fn drift(fine: &[DVec3], coarse: &[DVec3]) -> f64 {
    fine.iter()
        .map(|&p| {
            coarse
                .windows(2)
                .map(|w| {
                    let ab = w[1] - w[0];
                    let u = ((p - w[0]).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
                    (w[0] + ab * u - p).length()
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

fn at(phi: f64) -> DVec3 {
    DVec3::new(phi.cos(), phi.sin(), 0.0)
}

/// The row's drift from depth `d − 1` to `d`, for `d` in `1 ..= 9`, as placed
/// today and anchored at the limit start.
fn drifts(scheme: CurveScheme) -> (Vec<f64>, Vec<f64>) {
    let phis = [0.0f64, 0.3, 0.9, 1.1, 1.8, 2.0];
    let s0 = [0.0f64, 0.4, 0.9, 1.2, 1.9, 2.3];
    let tangents: Vec<DVec3> = phis.iter().map(|&p| at(p)).collect();
    let sigma = s0[0];
    // the limit start and its tangent (the planar masks, exact on a plane)
    let (a, ta) = match scheme {
        CurveScheme::CubicBSpline => (
            (s0[0] + 4.0 * s0[1] + s0[2]) / 6.0,
            at((phis[0] + 4.0 * phis[1] + phis[2]) / 6.0),
        ),
        _ => (0.5 * (s0[0] + s0[1]), at(0.5 * (phis[0] + phis[1]))),
    };
    let (mut today, mut limit) = (Vec::new(), Vec::new());
    let mut prev: Option<(Vec<DVec3>, Vec<DVec3>)> = None;
    for d in 0..10u32 {
        let t = subdivide(scheme, &tangents, d).unwrap();
        let mut s = s0.to_vec();
        for _ in 0..d {
            let mut next = Vec::new();
            scheme.refine_scalars(&s, &mut next);
            s = next;
        }
        assert!(s[0] < a, "depth {d}: the row starts before its limit start");
        let mut placed = Vec::new();
        place_into(&t, &s, sigma, DVec3::ZERO, &mut placed);
        let mut anchored = Vec::new();
        place_into(&t, &s, a, ta * (a - sigma), &mut anchored);
        if let Some((p, q)) = &prev {
            today.push(drift(&placed, p));
            limit.push(drift(&anchored, q));
        }
        prev = Some((placed, anchored));
    }
    (today, limit)
}

#[test]
fn an_approximating_row_drifts_by_its_start_s_extension_and_would_converge_anchored_at_its_limit() {
    for (scheme, name) in [
        (CurveScheme::CubicBSpline, "Catmull–Clark's cubic B-spline"),
        (CurveScheme::Chaikin, "Doo–Sabin's Chaikin"),
    ] {
        let (today, limit) = drifts(scheme);
        let e = |v: &[f64]| {
            v.iter()
                .map(|x| format!("{x:.2e}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        eprintln!(
            "{name}: drift per depth today {}; anchored at the limit {}",
            e(&today),
            e(&limit)
        );
        // depths 5-9: the ratios have settled
        for d in 4..today.len() {
            let r = today[d] / today[d - 1];
            assert!(
                (0.45..0.55).contains(&r),
                "{name}, depth {}: today's ratio {r}",
                d + 1
            );
            let q = limit[d] / limit[d - 1];
            assert!(
                (0.2..0.3).contains(&q),
                "{name}, depth {}: anchored ratio {q}",
                d + 1
            );
        }
        // at depth 7 the limit anchor is at least 20 times closer
        assert!(
            today[6] > 20.0 * limit[6],
            "{name}: {} against {}",
            today[6],
            limit[6]
        );
    }
}
