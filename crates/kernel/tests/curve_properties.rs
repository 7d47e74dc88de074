//! SPEC §1–2 invariants of blending and curve subdivision, as properties over random input.

mod common;

use common::*;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::curve::scheme::{CurveScheme, subdivide};
use streamline_kernel::sphere::blend::{blend, combine, mid};
use streamline_kernel::sphere::tangent::normalize_all;

fn schemes(omega: f64) -> [(CurveScheme, &'static str); 3] {
    [
        (CurveScheme::Chaikin, "chaikin"),
        (CurveScheme::CubicBSpline, "cubic"),
        (CurveScheme::FourPoint { omega }, "four"),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn blend_stays_on_great_circle(a0 in -3.0f64..0.0, d in 0.0f64..3.1, u in -2.0f64..3.0, r in rotation()) {
        let (a, b) = (on_circle(r, a0), on_circle(r, a0 + d));
        let got = blend(a, b, u);
        let (ang, off) = circle_angle(r, got, a0 + u * d);
        prop_assert!(off < 1e-13, "off circle by {off:e}");
        prop_assert!((ang - (a0 + u * d)).abs() < 1e-12, "blend angle {ang} vs planar {}", a0 + u * d);
        prop_assert!((blend(b, a, 1.0 - u) - got).length() < 1e-12, "blend(a,b,u) = blend(b,a,1-u)");
    }

    #[test]
    fn mid_is_blend_half(a in unit(), b in unit()) {
        prop_assume!(a.dot(b) > -0.999);
        prop_assert!((mid(a, b) - blend(a, b, 0.5)).length() < 1e-12);
    }

    #[test]
    fn combine_on_great_circle_is_weighted_angle(angles in circle_angles(1..=7), raw in prop::collection::vec(0.01f64..1.0, 7), r in rotation()) {
        let n = angles.len();
        let total: f64 = raw[..n].iter().sum();
        let c: Vec<f64> = raw[..n].iter().map(|x| x / total).collect();
        let ts: Vec<DVec3> = angles.iter().map(|&a| on_circle(r, a)).collect();
        let got = combine(&ts, &c).unwrap();
        let want: f64 = angles.iter().zip(&c).map(|(a, w)| a * w).sum();
        let (ang, off) = circle_angle(r, got, want);
        prop_assert!(off < 1e-12 && (ang - want).abs() < 1e-11, "combine {ang} vs Σcφ {want}");
        // reversal symmetry (Eqs. 38–48)
        let rt: Vec<DVec3> = ts.iter().rev().copied().collect();
        let rc: Vec<f64> = c.iter().rev().copied().collect();
        prop_assert!((combine(&rt, &rc).unwrap() - got).length() < 1e-12);
    }

    #[test]
    fn curve_outputs_are_unit(t in walk(2..=9, 3.0), depth in 0u32..5, omega in 0.0f64..2.4) {
        for (s, _) in schemes(omega) {
            if t.len() < s.min_len() { continue; }
            for v in subdivide(s, &t, depth).unwrap() {
                prop_assert!((v.length() - 1.0).abs() < 1e-12, "{}: |t| = {}", s.name(), v.length());
            }
        }
    }

    #[test]
    fn curve_nasty_inputs_never_nan(t in nasty(3..=8), depth in 0u32..4, omega in 0.0f64..2.4) {
        for (s, _) in schemes(omega) {
            for v in subdivide(s, &t, depth).unwrap() {
                prop_assert!(v.is_finite() && (v.length() - 1.0).abs() < 1e-12, "{}: {v:?}", s.name());
            }
        }
    }

    #[test]
    fn curve_rotation_equivariant(t in walk(3..=8, 2.6), depth in 1u32..4, r in rotation(), omega in 0.0f64..2.4) {
        let rt: Vec<DVec3> = t.iter().map(|&v| r * v).collect();
        for (s, _) in schemes(omega) {
            let a = subdivide(s, &t, depth).unwrap();
            let b = subdivide(s, &rt, depth).unwrap();
            for (x, y) in a.iter().zip(&b) {
                prop_assert!((r * *x - *y).length() < 1e-11, "{}: R f(t) ≠ f(R t): {:e}", s.name(), (r * *x - *y).length());
            }
        }
    }

    #[test]
    fn curve_reversal_symmetric(t in walk(3..=8, 2.6), depth in 1u32..4, omega in 0.0f64..2.4) {
        let rev: Vec<DVec3> = t.iter().rev().copied().collect();
        for (s, _) in schemes(omega) {
            let a = subdivide(s, &t, depth).unwrap();
            let mut b = subdivide(s, &rev, depth).unwrap();
            b.reverse();
            for (x, y) in a.iter().zip(&b) {
                prop_assert!((*x - *y).length() < 1e-11, "{}: reversal broken by {:e}", s.name(), (*x - *y).length());
            }
        }
    }

    #[test]
    fn four_point_keeps_inputs_exactly(t in walk(2..=8, 3.0), depth in 1u32..5, omega in 0.0f64..2.4) {
        let unit_t = normalize_all(&t).unwrap();
        let out = subdivide(CurveScheme::FourPoint { omega }, &t, depth).unwrap();
        let step = 1usize << depth;
        for (i, v) in unit_t.iter().enumerate() {
            prop_assert_eq!(out[i * step], *v, "input {} at output {}", i, i * step);
        }
    }

    #[test]
    fn curve_great_circle_reduces_to_planar(raw in circle_angles(3..=8), depth in 1u32..5, r in rotation(), omega in 0.0f64..2.4) {
        // Spread under π / (1 + ω/4) so the 4-point rule's extrapolated pairs stay under π apart.
        let k = 0.95 * std::f64::consts::PI / (1.0 + omega / 4.0) / 3.0;
        let angles: Vec<f64> = raw.iter().map(|a| a * k).collect();
        let t: Vec<DVec3> = angles.iter().map(|&a| on_circle(r, a)).collect();
        for (s, name) in schemes(omega) {
            let got = subdivide(s, &t, depth).unwrap();
            let want = planar(name, &angles, depth, omega);
            prop_assert_eq!(got.len(), want.len());
            for (v, &w) in got.iter().zip(&want) {
                let (a, off) = circle_angle(r, *v, w);
                prop_assert!(off < 1e-12, "{name}: off the great circle by {off:e}");
                prop_assert!((a - w).abs() < 1e-11, "{name}: angle {a} vs planar {w}");
            }
        }
    }
}

#[test]
fn curve_counts_table1_every_depth() {
    let t: Vec<DVec3> = (0..5)
        .map(|i| DVec3::new(1.0, i as f64 * 0.3, 0.1 * i as f64))
        .collect();
    let want = [
        (CurveScheme::Chaikin, 7, 386),
        (CurveScheme::CubicBSpline, 7, 259),
        (CurveScheme::FourPoint { omega: 1.0 }, 6, 257),
    ];
    for (s, d, n) in want {
        assert_eq!(
            subdivide(s, &t, d).unwrap().len(),
            n,
            "{} depth {d}: Table 1 says {n}",
            s.name()
        );
    }
}
