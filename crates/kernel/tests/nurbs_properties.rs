//! docs/math.md §10: the B-spline fit of the streamline surface,
//! checked against closed forms (a flat template, a surface that is itself a
//! B-spline) and an independent evaluator and distance search.

mod common;

use common::*;
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::design::Design;
use streamline_kernel::levels::presets;
use streamline_kernel::levels::surface::{BlendOrder, SurfaceScheme};
use streamline_kernel::nurbs::{
    BSplineSurface, FitError, FitOptions, KnotVector, Samples, Tolerance, deviation, fit,
    fit_design, fit_knots,
};
use streamline_kernel::streamline::initial_curve::InitialCurve;

/// Cox–de Boor from the definition (half-open spans, the last closed at 1).
fn cox(k: &[f64], i: usize, p: usize, u: f64) -> f64 {
    if p == 0 {
        let last_nonempty = k[i] < k[i + 1] && k[i + 1] == 1.0;
        return f64::from(u8::from(
            (k[i] <= u && u < k[i + 1]) || (u == 1.0 && last_nonempty),
        ));
    }
    let mut v = 0.0;
    if k[i + p] > k[i] {
        v += (u - k[i]) / (k[i + p] - k[i]) * cox(k, i, p - 1, u);
    }
    if k[i + p + 1] > k[i + 1] {
        v += (k[i + p + 1] - u) / (k[i + p + 1] - k[i + 1]) * cox(k, i + 1, p - 1, u);
    }
    v
}

/// Whether each of the `n` degree-`p` basis functions of knots `k` can be
/// given a parameter of its own, in order, where it is at least `delta`
/// (Schoenberg–Whitney with a margin; `delta → 0` is the plain condition).
/// Each function's parameters at or above `delta` are a run of `params`
/// (sorted; the function rises, then falls), and the runs move right with
/// the function, so taking the first one free from the left finds such a
/// matching whenever there is one.
fn observed(k: &[f64], p: usize, n: usize, params: &[f64], delta: f64) -> bool {
    let mut next = 0;
    for i in 0..n {
        match (next..params.len()).find(|&j| cox(k, i, p, params[j]) >= delta) {
            Some(j) => next = j + 1,
            None => return false,
        }
    }
    true
}

/// The surface evaluated from the definition, over every pole.
#[allow(clippy::needless_range_loop)]
fn eval_ref(s: &BSplineSurface, u: f64, v: f64) -> DVec3 {
    let (p, q) = s.degree();
    let (nu, nv) = s.pole_counts();
    let bu: Vec<f64> = (0..nu).map(|i| cox(s.knots_u.knots(), i, p, u)).collect();
    let bv: Vec<f64> = (0..nv).map(|j| cox(s.knots_v.knots(), j, q, v)).collect();
    let mut sum = DVec3::ZERO;
    for j in 0..nv {
        for i in 0..nu {
            sum += s.poles.get(j, i) * (bu[i] * bv[j]);
        }
    }
    sum
}

/// An upper bound of the distance from `x` to the surface, from a coarse
/// search and a shrinking pattern search, both with [`eval_ref`].
fn distance_ref(s: &BSplineSurface, x: DVec3, guess: (f64, f64)) -> f64 {
    let mut best = (guess, (eval_ref(s, guess.0, guess.1) - x).length());
    let n = 12;
    for a in 0..=n {
        for b in 0..=n {
            let (u, v) = (a as f64 / n as f64, b as f64 / n as f64);
            let d = (eval_ref(s, u, v) - x).length();
            if d < best.1 {
                best = ((u, v), d);
            }
        }
    }
    let mut h = 0.05;
    while h > 1e-9 {
        let mut moved = false;
        for (du, dv) in [(h, 0.0), (-h, 0.0), (0.0, h), (0.0, -h)] {
            let (u, v) = (
                (best.0.0 + du).clamp(0.0, 1.0),
                (best.0.1 + dv).clamp(0.0, 1.0),
            );
            let d = (eval_ref(s, u, v) - x).length();
            if d < best.1 {
                best = ((u, v), d);
                moved = true;
            }
        }
        if !moved {
            h *= 0.5;
        }
    }
    best.1
}

/// Increasing parameters from 0 to 1 with random gaps.
fn params(n: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(0.2f64..3.0, n).prop_map(|gaps| {
        let total: f64 = gaps.iter().sum();
        let mut acc = 0.0;
        let mut out = vec![0.0];
        for g in &gaps {
            acc += g;
            out.push(acc / total);
        }
        *out.last_mut().unwrap() = 1.0;
        out
    })
}

/// A Flat template (docs/math.md §9): every tangent `+x`, a straight initial curve
/// along `+y`; every row shares one random `s` row, rows at random `t`.
fn flat(s_row: &[f64], t: &[f64], anchor: usize, scheme: SurfaceScheme) -> Design {
    let (rows, cols) = (t.len(), s_row.len());
    let net = Grid::filled(rows, cols, DVec3::X);
    let s = Grid::new(rows, cols, s_row.repeat(rows)).unwrap();
    let width = t[rows - 1] + 1.0;
    let initial =
        InitialCurve::new(&[DVec3::Y, DVec3::Y], 2, width, DVec3::new(0.3, -0.2, 0.7)).unwrap();
    Design::new(
        &net,
        s,
        t.to_vec(),
        anchor,
        scheme,
        BlendOrder::SFirst,
        initial,
    )
    .unwrap()
}

fn rising(n: std::ops::RangeInclusive<usize>, lo: f64) -> impl Strategy<Value = Vec<f64>> {
    (lo..lo + 2.0, prop::collection::vec(0.8f64..1.25, n)).prop_map(|(start, gaps)| {
        let mut acc = start;
        let mut out = vec![acc];
        for g in gaps {
            acc += g;
            out.push(acc);
        }
        out
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// A flat template is bilinear in its parameters: the Bézier net of
    /// `(p + 1) × (q + 1)` poles (4 × 4 bicubic) fits it exactly, corners included.
    #[test]
    fn flat_template_is_fitted_exactly_by_the_bezier_net(
        s_row in rising(2..=6, -1.0),
        t in rising(2..=5, 0.0),
        anchor_pick in 0usize..8,
        depth in 0u32..=3,
        p in 2usize..=5,
        q in 2usize..=5,
        which in 0usize..3,
    ) {
        let scheme = [SurfaceScheme::default(), SurfaceScheme::CatmullClark, SurfaceScheme::DooSabin][which];
        let anchor = anchor_pick % s_row.len();
        let d = flat(&s_row, &t, anchor, scheme);
        let opts = FitOptions { degree: (p, q), tolerance: Tolerance::Relative(1e-9) };
        let f = match fit_design(&d, depth, &opts) {
            Ok(f) => f,
            // too few points at this depth for the degree: the error says so
            Err(FitError::TooFewPoints { .. }) => return Ok(()),
            Err(e) => panic!("{e}"),
        };
        prop_assert_eq!(f.report.poles, (p + 1, q + 1), "{:?}", f.report);
        let data = Samples::build(&d, depth).unwrap();
        let diag = data.diagonal();
        prop_assert!(f.report.deviation.max <= 1e-12 * diag, "{:?} diag {}", f.report, diag);
        let (r, c) = (data.points.rows() - 1, data.points.cols() - 1);
        for (u, v, pt) in [(0.0, 0.0, data.points.get(0, 0)), (1.0, 0.0, data.points.get(0, c)),
                           (0.0, 1.0, data.points.get(r, 0)), (1.0, 1.0, data.points.get(r, c))] {
            prop_assert_eq!(f.surface.eval(u, v), pt, "corner ({}, {})", u, v);
        }
    }

    /// Samples of a B-spline surface fitted on its own knots give back its
    /// poles; a Bézier patch comes back through the adaptive fit itself.
    #[test]
    fn a_bspline_surface_comes_back(
        us in params(12..=40),
        vs in params(12..=40),
        inner_u in prop::collection::vec(0.05f64..0.95, 0..=3),
        inner_v in prop::collection::vec(0.05f64..0.95, 0..=3),
        seed in prop::collection::vec(-1.0f64..1.0, 3 * 9 * 9),
        p in 2usize..=5,
        q in 2usize..=5,
    ) {
        let sorted = |mut k: Vec<f64>| { k.sort_by(f64::total_cmp); k.dedup_by(|a, b| (*a - *b).abs() < 0.1); k };
        let ku = KnotVector::with_interior(p, &sorted(inner_u)).unwrap();
        let kv = KnotVector::with_interior(q, &sorted(inner_v)).unwrap();
        let (nu, nv) = (ku.count(), kv.count());
        let poles: Vec<DVec3> = (0..nu * nv)
            .map(|i| DVec3::new(seed[3 * i], seed[3 * i + 1], seed[3 * i + 2]) + DVec3::new((i % nu) as f64, (i / nu) as f64, 0.0))
            .collect();
        let src = BSplineSurface { knots_u: ku.clone(), knots_v: kv.clone(), poles: Grid::new(nv, nu, poles).unwrap() };
        let sample = |src: &BSplineSurface, us: &[f64], vs: &[f64]| {
            let pts: Vec<DVec3> = vs.iter().flat_map(|&v| us.iter().map(move |&u| (u, v))).map(|(u, v)| eval_ref(src, u, v)).collect();
            Samples::new(Grid::new(vs.len(), us.len(), pts).unwrap(), us.to_vec(), vs.to_vec()).unwrap()
        };
        let data = sample(&src, &us, &vs);
        // Schoenberg–Whitney can fail for random knots against random
        // parameters: then the fit must refuse, not return garbage
        // A pole is pinned down only as well as the data's own rounding
        // allows, amplified by the condition number of the collocation
        // matrix, which grows as a basis function is seen only where it is
        // small: one seen only at 2.6e-6 moves by 4e-10 from the rounding
        // of exact samples alone. The poles are compared where every function
        // has a parameter of its own at 1e-3 or more; the samples themselves
        // come back everywhere.
        let posed = observed(ku.knots(), p, nu, &us, 1e-3) && observed(kv.knots(), q, nv, &vs, 1e-3);
        match fit_knots(&data, &ku, &kv) {
            Ok(got) => {
                if posed {
                    for (a, b) in got.poles.data().iter().zip(src.poles.data()) {
                        prop_assert!((*a - *b).length() < 1e-9, "pole {} vs {}", a, b);
                    }
                }
                prop_assert!(deviation(&got, &data).max < 1e-11);
            }
            Err(FitError::TooFewPoints { .. }) => {}
            Err(e) => panic!("{e}"),
        }
        // the Bézier patch of the same poles' first (p+1)×(q+1) block
        let bz = BSplineSurface {
            knots_u: KnotVector::bezier(p),
            knots_v: KnotVector::bezier(q),
            poles: Grid::new(q + 1, p + 1, (0..=q).flat_map(|j| (0..=p).map(move |i| (i, j))).map(|(i, j)| src.poles.get(j, i)).collect()).unwrap(),
        };
        let src = bz;
        let data = sample(&src, &us, &vs);
        let fine_u: Vec<f64> = (0..=60).map(|i| i as f64 / 60.0).collect();
        let check = sample(&src, &fine_u, &fine_u);
        let f = fit(&data, &check, &FitOptions { degree: (p, q), tolerance: Tolerance::Absolute(1e-10) }).unwrap();
        prop_assert_eq!(f.report.poles, (p + 1, q + 1));
        prop_assert!(f.report.deviation.max < 1e-12, "{:?}", f.report);
        for (a, b) in f.surface.poles.data().iter().zip(src.poles.data()) {
            prop_assert!((*a - *b).length() < 1e-11, "pole {} vs {}", a, b);
        }
    }
}

/// Car-like designs with every control tangent turned a little.
fn perturbed() -> impl Strategy<Value = (Design, &'static str)> {
    (
        0usize..3,
        prop::collection::vec((unit(), 0.0f64..0.08), 6 * 9),
    )
        .prop_map(|(which, turns)| {
            let (mut d, name) = match which {
                0 => (presets::car1(), "car1"),
                1 => (presets::car2(), "car2"),
                _ => (presets::qi_demo(1), "qi-side"),
            };
            let (rows, cols) = (d.net().rows(), d.net().cols());
            for r in 0..rows {
                for c in 0..cols {
                    let (axis, angle) = turns[(r * cols + c) % turns.len()];
                    let t = DQuat::from_axis_angle(axis, angle) * d.net().get(r, c);
                    d.set_tangent(r, c, t).unwrap();
                }
            }
            (d, name)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Moving the points by a rigid motion moves the fit's poles by it (same
    /// knots, same figures): the fit has no preferred frame.
    #[test]
    fn the_fit_is_equivariant_under_rigid_motions(
        (d, name) in perturbed(),
        rot in rotation(),
        shift in (-50.0f64..50.0, -50.0f64..50.0, -50.0f64..50.0),
    ) {
        let depth = 3;
        let data = Samples::build(&d, depth).unwrap();
        let check = Samples::build(&d, depth + 1).unwrap();
        let tol = Tolerance::Absolute(2e-3 * data.diagonal());
        let opts = FitOptions { degree: (3, 3), tolerance: tol };
        let shift = DVec3::new(shift.0, shift.1, shift.2);
        let mv = |s: &Samples| Samples::new(s.points.map(|p| rot * p + shift), s.u.clone(), s.v.clone()).unwrap();
        let a = fit(&data, &check, &opts).unwrap();
        let b = fit(&mv(&data), &mv(&check), &opts).unwrap();
        prop_assert_eq!(&a.surface.knots_u, &b.surface.knots_u, "{}", name);
        prop_assert_eq!(&a.surface.knots_v, &b.surface.knots_v, "{}", name);
        for (pa, pb) in a.surface.poles.data().iter().zip(b.surface.poles.data()) {
            prop_assert!((rot * *pa + shift - *pb).length() < 1e-9, "{}: {} vs {}", name, rot * *pa + shift, pb);
        }
        prop_assert!((a.report.deviation.max - b.report.deviation.max).abs() < 1e-9);
    }

    /// The reported largest deviation, measured at the check grid (one depth
    /// finer than the export), holds two depths finer to within 5 %: the
    /// distance from the fit of points of the streamline surface there,
    /// found independently (definition-based evaluation, a distance search),
    /// is at most 1.05 times it. Between the check grid's points the
    /// distance can rise a little past the largest one sampled (car1 with
    /// turned tangents, the case kept in the regressions file: 1.0104 times).
    /// A bound of exactly 1 failed once in four clean runs.
    #[test]
    fn the_reported_deviation_holds_two_depths_finer(
        (d, name) in perturbed(),
        picks in prop::collection::vec((0.0f64..1.0, 0.0f64..1.0), 24),
    ) {
        let depth = 4;
        let f = fit_design(&d, depth, &FitOptions { degree: (3, 3), tolerance: Tolerance::Relative(3e-4) });
        // a design whose depth-4 grid cannot reach the tolerance is refused
        // (TooFewPoints, tested in `bad_options_are_refused_with_what_to_do`):
        // nothing to check then, so the case is skipped, not passed
        prop_assume!(f.is_ok());
        let f = f.unwrap();
        let fine = Samples::build(&d, depth + 2).unwrap();
        let (rows, cols) = (fine.points.rows(), fine.points.cols());
        for (a, b) in picks {
            let (r, c) = (((rows - 1) as f64 * a).round() as usize, ((cols - 1) as f64 * b).round() as usize);
            let dist = distance_ref(&f.surface, fine.points.get(r, c), (fine.u[c], fine.v[r]));
            prop_assert!(dist <= 1.05 * f.report.deviation.max, "{}: point ({}, {}) is {:e} from the fit, reported {:?}", name, r, c, dist, f.report);
        }
    }
}

#[test]
fn bad_options_are_refused_with_what_to_do() {
    let car = presets::car1();
    for (opts, want) in [
        (
            FitOptions {
                degree: (3, 3),
                tolerance: Tolerance::Relative(0.0),
            },
            "positive finite",
        ),
        (
            FitOptions {
                degree: (3, 3),
                tolerance: Tolerance::Absolute(-1.0),
            },
            "positive finite",
        ),
        (
            FitOptions {
                degree: (3, 3),
                tolerance: Tolerance::Absolute(f64::NAN),
            },
            "positive finite",
        ),
        (
            FitOptions {
                degree: (3, 3),
                tolerance: Tolerance::Relative(f64::INFINITY),
            },
            "positive finite",
        ),
        (
            FitOptions {
                degree: (1, 3),
                tolerance: Tolerance::Relative(1e-4),
            },
            "outside 2 to 5",
        ),
        (
            FitOptions {
                degree: (3, 6),
                tolerance: Tolerance::Relative(1e-4),
            },
            "outside 2 to 5",
        ),
        (
            FitOptions {
                degree: (3, 3),
                tolerance: Tolerance::Relative(1e-12),
            },
            "loosen the tolerance or export deeper",
        ),
    ] {
        let e = fit_design(&car, 2, &opts).unwrap_err();
        assert!(e.to_string().contains(want), "{opts:?}: {e}");
    }
}

#[test]
fn shipped_designs_fit_within_the_default_tolerance_at_depth_5() {
    for (name, d, depth) in [
        ("car1", presets::car1(), 5),
        ("car2", presets::car2(), 5),
        ("car1", presets::car1(), 4),
        ("car2", presets::car2(), 4),
        ("qi-side", presets::qi_demo(1), 5),
    ] {
        let f = fit_design(&d, depth, &FitOptions::DEFAULT).unwrap();
        let r = f.report;
        // the report is the deviation at the grid one depth finer, measured again here
        let check = Samples::build(&d, depth + 1).unwrap();
        assert_eq!(
            deviation(&f.surface, &check),
            r.deviation,
            "{name} d{depth}"
        );
        assert!(r.deviation.max <= r.tolerance, "{name}: {r:?}");
        assert!(r.deviation.mean <= r.deviation.max, "{name}: {r:?}");
        assert_eq!(
            r.checked,
            (check.v.len(), check.u.len()),
            "{name}: checked one depth finer"
        );
    }
}
