//! `docs/math.md §9`: a streamline's curvature profile and its logarithmic
//! curvature graph, on streamlines built from tangents whose turning is known
//! in closed form (clothoid, logarithmic spiral, circle, line), in a random
//! plane and at random, uneven arc-length spacing.

mod common;

use common::*;
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::aesthetic::{LogCurvatureGraph, curvature_profile, log_curvature_graph};

/// Unit tangents turning by `phi(s)` in the plane `rot·(x, y)`.
fn tangents(rot: DQuat, s: &[f64], phi: impl Fn(f64) -> f64) -> Vec<DVec3> {
    s.iter()
        .map(|&v| rot * DVec3::new(phi(v).cos(), phi(v).sin(), 0.0))
        .collect()
}

/// `n` increasing arc lengths from `a` to `b`, randomly uneven.
fn spacing(n: std::ops::Range<usize>) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(0.2f64..1.0, n).prop_map(|w| {
        let total: f64 = w.iter().sum();
        let mut acc = 0.0;
        std::iter::once(0.0)
            .chain(w.iter().map(|x| {
                acc += x;
                acc / total
            }))
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn clothoid_has_alpha_minus_one(u in spacing(8..200), c in 0.01f64..5.0, s0 in 0.05f64..2.0, span in 0.5f64..5.0, rot in rotation()) {
        // κ = c·s, tangent angle c s² / 2
        let s: Vec<f64> = u.iter().map(|x| s0 + span * x).collect();
        let t = tangents(rot, &s, |v| 0.5 * c * v * v);
        // the turning between neighbouring tangents stays under π (angles are atan2's)
        prop_assume!(s.windows(2).all(|w| 0.5 * c * (w[1] * w[1] - w[0] * w[0]) < 2.5));
        let p = curvature_profile(&t, &s);
        for (sk, kk) in p.s.iter().zip(&p.kappa) {
            prop_assert!((kk - c * sk).abs() <= 1e-9 * c * sk.max(1.0), "κ({sk}) = {kk} vs c·s = {}", c * sk);
        }
        match log_curvature_graph(&p) {
            LogCurvatureGraph::Graph { alpha, residual, intercept, .. } => {
                prop_assert!((alpha + 1.0).abs() < 1e-6, "clothoid α = {alpha}, want −1");
                prop_assert!(residual < 1e-6, "residual {residual}");
                prop_assert!((intercept + c.ln()).abs() < 1e-5, "intercept {intercept} vs −ln c = {}", -c.ln());
            }
            g => prop_assert!(false, "clothoid gave {g:?}"),
        }
    }

    #[test]
    fn log_spiral_has_alpha_one(u in spacing(100..300), a in 0.2f64..3.0, s0 in 0.5f64..2.0, span in 0.5f64..3.0, rot in rotation()) {
        // ρ = a·s, tangent angle ln(s) / a
        let s: Vec<f64> = u.iter().map(|x| s0 + span * x).collect();
        let t = tangents(rot, &s, |v| v.ln() / a);
        let p = curvature_profile(&t, &s);
        match log_curvature_graph(&p) {
            LogCurvatureGraph::Graph { alpha, residual, .. } => {
                prop_assert!((alpha - 1.0).abs() < 2e-3, "logarithmic spiral α = {alpha}, want 1");
                prop_assert!(residual < 1e-2, "residual {residual}");
            }
            g => prop_assert!(false, "spiral gave {g:?}"),
        }
    }

    #[test]
    fn circle_is_a_point_reported_as_such(u in spacing(2..100), r in 0.01f64..100.0, span in 0.1f64..5.0, rot in rotation()) {
        let s: Vec<f64> = u.iter().map(|x| span * x * r).collect();
        // the turning between neighbouring tangents stays under π (a turn past
        // π is the same pair of tangents as the shorter turn the other way)
        prop_assume!(u.windows(2).all(|w| span * (w[1] - w[0]) < 2.5));
        let t = tangents(rot, &s, |v| v / r);
        let p = curvature_profile(&t, &s);
        prop_assert!(p.kappa.iter().all(|k| (k * r - 1.0).abs() < 1e-9), "κ·r = {:?}", p.kappa.iter().map(|k| k * r).collect::<Vec<_>>());
        match log_curvature_graph(&p) {
            LogCurvatureGraph::Circle { kappa } => prop_assert!((kappa * r - 1.0).abs() < 1e-9),
            g => prop_assert!(false, "circle gave {g:?}"),
        }
    }
}

#[test]
fn straight_and_degenerate_profiles() {
    let s = [0.0, 1.0, 2.5, 3.0];
    let t = [DVec3::X; 4];
    assert_eq!(
        log_curvature_graph(&curvature_profile(&t, &s)),
        LogCurvatureGraph::Straight
    );
    let p = curvature_profile(&t[..1], &s[..1]);
    assert_eq!(log_curvature_graph(&p), LogCurvatureGraph::TooFew);
    // a zero-length interval gives κ = 0 there, never NaN
    let p = curvature_profile(&[DVec3::X, DVec3::Y, DVec3::X], &[0.0, 0.0, 1.0]);
    assert!(p.kappa.iter().all(|k| k.is_finite()));
}
