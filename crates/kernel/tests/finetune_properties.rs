//! SPEC §6 (fine tuning) as properties over random streamlines and functions:
//! the identity changes nothing; the constraints hold; between its points the
//! fine-tuned streamline advances by `∫ α p'`, with `α` from an independent
//! Cox–de Boor recursion and Gauss–Legendre quadrature on each knot span.

mod common;

use common::*;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::finetune::bspline::BSpline;
use streamline_kernel::finetune::{Constraint, fine_tune_into};
use streamline_kernel::streamline::integrate::{place_into, point_arclength};

/// Random increasing `s` (intervals 0.05 … 2) for `n` tangents.
fn params(n: usize) -> impl Strategy<Value = Vec<f64>> {
    (-3.0f64..3.0, prop::collection::vec(0.05f64..2.0, n - 1)).prop_map(|(s0, gaps)| {
        let mut s = vec![s0];
        for g in gaps {
            s.push(s.last().unwrap() + g);
        }
        s
    })
}

fn streamline() -> impl Strategy<Value = (Vec<DVec3>, Vec<f64>)> {
    (3usize..20).prop_flat_map(|n| (walk(n..=n, 0.8), params(n)))
}

/// A streamline whose ends a constraint can actually move: every tangent
/// turns 0.15–0.8 rad from the last about a random axis and every interval is
/// 0.3–2, so the end points' dependence on the values has full rank. (A
/// straight or nearly straight run cannot move its end sideways; there the
/// least-squares change is as near as the values can get, not exact.)
fn turning_streamline() -> impl Strategy<Value = (Vec<DVec3>, Vec<f64>)> {
    (6usize..20).prop_flat_map(|n| {
        let turns = (unit(), prop::collection::vec((unit(), 0.15f64..0.8), n - 1)).prop_map(
            |(start, steps)| {
                let mut out = vec![start];
                for (axis, angle) in steps {
                    let cur = *out.last().unwrap();
                    let perp = axis
                        .reject_from(cur)
                        .try_normalize()
                        .unwrap_or_else(|| cur.any_orthonormal_vector());
                    out.push((glam::DQuat::from_axis_angle(perp, angle) * cur).normalize());
                }
                out
            },
        );
        let s = (-3.0f64..3.0, prop::collection::vec(0.3f64..2.0, n - 1)).prop_map(|(s0, gaps)| {
            let mut s = vec![s0];
            for g in gaps {
                s.push(s.last().unwrap() + g);
            }
            s
        });
        (turns, s)
    })
}

/// α(u) from the recursive definition on clamped uniform knots.
fn alpha_ref(p: usize, vals: &[f64], u: f64) -> f64 {
    let m = vals.len();
    let spans = m - p;
    let mut knots = vec![0.0; p + 1];
    knots.extend((1..spans).map(|i| i as f64 / spans as f64));
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    (0..m)
        .map(|j| vals[j] * bspline_basis(&knots, j, p + 1, u, true))
        .sum()
}

/// `∫_{x0}^{x1} α(u(s)) ds`, split at the knots, 5-point Gauss–Legendre per piece
/// (exact for degree ≤ 9).
fn integral_ref(p: usize, vals: &[f64], s0: f64, len: f64, x0: f64, x1: f64) -> f64 {
    const X: [f64; 5] = [
        0.0,
        -0.538_469_310_105_683,
        0.538_469_310_105_683,
        -0.906_179_845_938_664,
        0.906_179_845_938_664,
    ];
    const W: [f64; 5] = [
        0.568_888_888_888_889,
        0.478_628_670_499_366,
        0.478_628_670_499_366,
        0.236_926_885_056_189,
        0.236_926_885_056_189,
    ];
    let spans = vals.len() - p;
    let mut cuts = vec![x0];
    for i in 1..spans {
        let k = s0 + len * i as f64 / spans as f64;
        if k > x0 && k < x1 {
            cuts.push(k);
        }
    }
    cuts.push(x1);
    let mut total = 0.0;
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        for (x, wt) in X.iter().zip(W) {
            let s = mid + half * x;
            total += wt * half * alpha_ref(p, vals, (s - s0) / len);
        }
    }
    total
}

fn constraints() -> impl Strategy<Value = Constraint> {
    prop::sample::select(vec![
        Constraint::Free,
        Constraint::KeepEnds,
        Constraint::KeepClosed,
    ])
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn finetune_identity_changes_nothing((t, s) in streamline(), degree in 0usize..4, at in 0.0f64..1.0, c in constraints(), origin in unit()) {
        let n = s.len() - 1;
        let sigma = s[0] + at * (s[n] - s[0]);
        let f = BSpline::uniform(degree, vec![1.0; degree + 1 + (at * 4.0) as usize]).unwrap();
        let (mut a, mut b) = (Vec::new(), Vec::new());
        place_into(&t, &s, sigma, origin, &mut a);
        fine_tune_into(&t, &s, sigma, origin, &f, c, &mut b);
        let scale = 1.0 + (s[n] - s[0]);
        for (p, q) in a.iter().zip(&b) {
            prop_assert!((*p - *q).length() < 1e-12 * scale, "{p:?} vs {q:?} ({c:?})");
        }
    }

    #[test]
    fn finetune_derivative_is_alpha_times_original((t, s) in streamline(), degree in 0usize..4, raw in prop::collection::vec(0.2f64..2.5, 5..9), at in 0.0f64..1.0) {
        let n = s.len() - 1;
        let sigma = s[0] + at * (s[n] - s[0]);
        let f = BSpline::uniform(degree, raw.clone()).unwrap();
        let mut b = Vec::new();
        let used = fine_tune_into(&t, &s, sigma, DVec3::ZERO, &f, Constraint::Free, &mut b);
        prop_assert_eq!(used.alpha.values(), &raw[..]);
        let len = s[n] - s[0];
        // segment k has the original derivative t_k; the fine-tuned one advances by ∫ α t_k
        for k in 0..=n {
            let (a0, a1) = (point_arclength(&s, k), point_arclength(&s, k + 1));
            let want = t[k] * integral_ref(degree, &raw, s[0], len, a0, a1);
            let got = b[k + 1] - b[k];
            prop_assert!((got - want).length() < 1e-12 * (1.0 + len), "segment {k}: {got:?} vs {want:?}");
            // and at dense samples inside it, the rate of advance is α(s) (degree 0 jumps at knots)
            for j in (1..4).filter(|_| degree > 0) {
                let x = a0 + (a1 - a0) * j as f64 / 4.0;
                // the average of α over [x − h, x + h], integrated directly (a
                // difference of two long integrals would lose digits); a kink of
                // α (a knot) within ±h moves it by less than h·|α'| ≈ 1e-7
                let h = 1e-6 * (a1 - a0);
                let rate = integral_ref(degree, &raw, s[0], len, x - h, x + h) / (2.0 * h);
                let kernel = f.eval((x - s[0]) / len);
                prop_assert!((rate - kernel).abs() < 1e-6, "α at s={x}: {kernel} vs {rate}");
            }
        }
    }
}

proptest! {
    // A fixed seed: these streamlines are drawn at random once. Among truly
    // random ones about 1 in 16,000 is so nearly planar that its end cannot
    // move out of that plane to 1e-10 without unbounded values; there the
    // kernel keeps the least-squares change (RANK_TOLERANCE) instead.
    #![proptest_config(ProptestConfig {
        cases: 512,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20_261_122),
        ..ProptestConfig::default()
    })]

    #[test]
    fn finetune_constraints_hold((t, s) in turning_streamline(), degree in 1usize..4, raw in prop::collection::vec(0.2f64..2.5, 8..12), at in 0.0f64..1.0) {
        let n = s.len() - 1;
        let sigma = s[0] + at * (s[n] - s[0]);
        let f = BSpline::uniform(degree, raw).unwrap();
        let (mut a, mut b) = (Vec::new(), Vec::new());
        place_into(&t, &s, sigma, DVec3::ZERO, &mut a);
        let last = a.len() - 1;
        let scale = 1.0 + (s[n] - s[0]);
        fine_tune_into(&t, &s, sigma, DVec3::ZERO, &f, Constraint::KeepEnds, &mut b);
        prop_assert!((b[0] - a[0]).length() < 1e-10 * scale, "near end moved {:e}", (b[0] - a[0]).length());
        prop_assert!((b[last] - a[last]).length() < 1e-10 * scale, "far end moved {:e}", (b[last] - a[last]).length());
        fine_tune_into(&t, &s, sigma, DVec3::ZERO, &f, Constraint::KeepClosed, &mut b);
        let chord = (b[last] - b[0]) - (a[last] - a[0]);
        prop_assert!(chord.length() < 1e-10 * scale, "chord changed {:e}", chord.length());
    }
}
