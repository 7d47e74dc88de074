//! docs/math.md §11.5, "A start that moves": why a Catmull–Clark or
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

use proptest::prelude::*;
use streamline_kernel::curve::scheme::{CurveScheme, subdivide};
use streamline_kernel::grid::Grid;
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::streamline::integrate::place_into;
use streamline_kernel::{BlendOrder, DQuat, DVec3, Design, SurfaceScheme};

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

/// A design of three equal rows on a straight initial curve, so every level's
/// rows are one row translated: `tangents` and `s` of that row.
fn equal_rows(tangents: &[DVec3], s: &[f64], scheme: SurfaceScheme, anchor: usize) -> Design {
    let n = tangents.len();
    let net = Grid::new(3, n, [tangents, tangents, tangents].concat()).unwrap();
    let s = Grid::new(3, n, [s, s, s].concat()).unwrap();
    let initial = InitialCurve::new(&[DVec3::Y; 3], 3, 2.0, DVec3::ZERO).unwrap();
    Design::new(
        &net,
        s,
        vec![0.0, 1.0, 2.0],
        anchor,
        scheme,
        BlendOrder::SFirst,
        initial,
    )
    .unwrap()
}

/// Row 0 of each level up to `depth`, relative to its point on the initial
/// curve, placed by the design and as placed with `σ` at level 0's `s₀`
/// (the anchor before the limit start).
fn rows_by_level(design: &Design, depth: u32) -> Vec<(Vec<DVec3>, Vec<DVec3>)> {
    let sigma0 = design.params().s.get(0, 0);
    design
        .levels(depth)
        .unwrap()
        .iter()
        .map(|level| {
            let origin = design.initial().point(level.params.t[0]);
            let mut row = vec![DVec3::ZERO; level.tangents.cols() + 1];
            design.place_row(level, 0, &mut row);
            let row = row.iter().map(|p| *p - origin).collect();
            let mut before = Vec::new();
            place_into(
                level.tangents.row(0),
                level.params.s.row(0),
                sigma0,
                DVec3::ZERO,
                &mut before,
            );
            (row, before)
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// docs/math.md §4, "The anchor": a Catmull–Clark or Doo–Sabin design
    /// anchored at its first column converges at the integration's order,
    /// its drift quartering per depth, where `σ` at level 0's `s₀` only halves
    /// it (the negative control); a Kobbelt design's `σ` is its anchor
    /// column's `s`, bit for bit.
    #[test]
    fn a_design_anchored_at_its_first_column_converges_at_second_order(
        turns in prop::collection::vec((0.15f64..0.5, -0.4f64..0.4), 5..8),
        gaps in prop::collection::vec(0.2f64..1.0, 8),
        approximating in any::<bool>(),
        anchor in 0usize..8,
    ) {
        let mut t = DVec3::X;
        let mut tangents = Vec::new();
        for &(bend, twist) in &turns {
            tangents.push(t);
            t = DQuat::from_axis_angle(DVec3::new(0.0, twist.sin(), twist.cos()), bend) * t;
        }
        let n = tangents.len();
        let s: Vec<f64> = (0..n).map(|i| gaps[..i].iter().sum()).collect();
        let kobbelt = equal_rows(&tangents, &s, SurfaceScheme::Kobbelt { omega: 1.0 }, anchor % n);
        for r in 0..3 {
            prop_assert_eq!(kobbelt.params().sigma[r].to_bits(), s[anchor % n].to_bits());
        }
        let scheme = if approximating { SurfaceScheme::CatmullClark } else { SurfaceScheme::DooSabin };
        let design = equal_rows(&tangents, &s, scheme, 0);
        let rows = rows_by_level(&design, 8);
        let step = |d: usize| {
            (
                drift(&rows[d].0, &rows[d - 1].0),
                drift(&rows[d].1, &rows[d - 1].1),
            )
        };
        let ((now7, before7), (now8, before8)) = (step(7), step(8));
        eprintln!(
            "{}: the row moves {now7:.2e} from depth 6 to 7, {now8:.2e} from 7 to 8; with σ = s₀ {before7:.2e}, {before8:.2e}",
            scheme.name()
        );
        prop_assert!(now8 <= 0.35 * now7 + 1e-13, "{}: {now7:.3e} then {now8:.3e}", scheme.name());
        prop_assert!(
            (0.4..0.6).contains(&(before8 / before7)),
            "{}: anchored before the row, {before7:.3e} then {before8:.3e}",
            scheme.name()
        );
        prop_assert!(now8 < 0.1 * before8, "{}: {now8:.3e} against {before8:.3e}", scheme.name());
    }
}

/// docs/math.md §10: the car on Catmull–Clark or Doo–Sabin is fitted
/// within the default tolerance at depth 4 (Catmull–Clark) or 5, its check
/// grid one depth finer measured in its data's frame (`Samples::pair`).
/// Negative control: each grid normalised by its own ends, the check grid's
/// parameters slide a sample spacing against the data's and the fit is
/// refused even at depth 7, by a distance that halves per depth.
#[test]
fn the_car_on_an_approximating_scheme_fits_once_its_check_grid_shares_the_data_s_frame() {
    use streamline_kernel::levels::presets;
    use streamline_kernel::nurbs::{FitError, FitOptions, Samples, fit, fit_design};
    for (scheme, depth) in [
        (SurfaceScheme::CatmullClark, 4),
        (SurfaceScheme::DooSabin, 5),
    ] {
        let mut car = presets::car1();
        car.set_scheme(scheme).unwrap();
        let f = fit_design(&car, depth, &FitOptions::DEFAULT)
            .unwrap_or_else(|e| panic!("{}: {e}", scheme.name()));
        eprintln!(
            "{} at depth {depth}: {:.3e} within {:.3e}, {:?} poles",
            scheme.name(),
            f.report.deviation.max,
            f.report.tolerance,
            f.report.poles
        );
        let own = |d: u32| Samples::build(&car, d).unwrap();
        let mut reached = Vec::new();
        for d in 6..=7 {
            match fit(&own(d), &own(d + 1), &FitOptions::DEFAULT) {
                Err(FitError::TooFewPoints { reached: r, .. }) => reached.push(r),
                other => panic!("{} at depth {d}, own frames: {other:?}", scheme.name()),
            }
        }
        eprintln!(
            "{}: own frames refused, {:.3e} then {:.3e}",
            scheme.name(),
            reached[0],
            reached[1]
        );
        let r = reached[1] / reached[0];
        assert!((0.4..0.6).contains(&r), "{}: ratio {r}", scheme.name());
    }
}
