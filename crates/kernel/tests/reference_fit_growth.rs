//! The fit of a streamline design to a reference surface (docs/math.md §12,
//! "Growing the net" and "When the growth stops short"): a typical face fits
//! at the default tolerance and reports its time, a quarter torus grows rows
//! until it fits, a net at its cap (in both directions or in one) returns its
//! best and why, an approximating scheme fits or says why early, and the
//! progress hook sees the fit and can cancel it; each with a negative
//! control where one applies.

mod common;

use common::reference_fit::{outside_deviation, show, wavy};
use glam::DVec3;
use std::time::Instant;
use streamline_kernel::fit::{
    AnchorAt, ReferenceFitError, ReferenceFitOptions, fit_reference, fit_reference_with,
};
use streamline_kernel::nurbs::rational::NurbsSurface;
use streamline_kernel::{Grid, SurfaceScheme};

/// A quarter of a torus (major radius `big`, minor `small`, 90° by 90°),
/// exact as a rational biquadratic: `u` the major arc, `v` the minor one.
/// Its rows (horizontal circles) all share one tangent at each `u`, and
/// their lengths vary with `v`: the error is all across the rows.
fn torus(big: f64, small: f64) -> NurbsSurface {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let dirs = [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let minor = [(big + small, 0.0), (big + small, small), (big, small)];
    let ws = [1.0, w, 1.0];
    let mut poles = Vec::new();
    let mut weights = Vec::new();
    for (j, (rho, z)) in minor.iter().enumerate() {
        for (i, (dx, dy)) in dirs.iter().enumerate() {
            poles.push(DVec3::new(dx * rho, dy * rho, *z));
            weights.push(ws[i] * ws[j]);
        }
    }
    let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(
        2,
        2,
        k.clone(),
        k,
        Grid::new(3, 3, poles).unwrap(),
        Some(Grid::new(3, 3, weights).unwrap()),
    )
    .unwrap()
}

#[test]
fn a_typical_face_fits_within_the_default_tolerance_and_reports_its_time() {
    let reference = wavy(0.3, 0.3);
    let start = Instant::now();
    let f = fit_reference(&reference, &ReferenceFitOptions::default()).unwrap();
    let wall = start.elapsed().as_secs_f64();
    show(
        "typical face (bicubic, 4 × 2 knot spans), default options",
        &f,
    );
    assert!(f.within, "{:?}", f.why);
    assert!(f.seconds <= wall + 1e-3);
    let outside = outside_deviation(&f.design, f.depth, &reference);
    assert!(outside <= f.tolerance * (1.0 + 1e-9), "{outside}");
    let mid = fit_reference(
        &reference,
        &ReferenceFitOptions {
            anchor: AnchorAt::Middle,
            ..Default::default()
        },
    )
    .unwrap();
    show("typical face, anchored in the middle", &mid);
    assert!(mid.within, "{:?}", mid.why);
}

#[test]
fn a_net_at_its_cap_reports_the_best_and_why() {
    let f = fit_reference(
        &wavy(0.3, 0.3),
        &ReferenceFitOptions {
            max_net: (5, 5),
            ..Default::default()
        },
    )
    .unwrap();
    show("typical face capped at 5 × 5", &f);
    assert!(!f.within);
    assert!(f.net.0 <= 5 && f.net.1 <= 5);
    let why = f.why.unwrap();
    assert!(why.contains("cap") && why.contains("5 × 5"), "{why}");
}

#[test]
fn the_progress_hook_sees_the_fit_and_can_cancel_it() {
    let mut seen = Vec::new();
    let f = fit_reference_with(&wavy(0.3, 0.3), &ReferenceFitOptions::default(), &mut |p| {
        seen.push(p);
        true
    })
    .unwrap();
    assert!(f.within);
    assert!(seen.iter().all(|p| (0.0..=1.0).contains(p)));
    assert_eq!(seen.last(), Some(&1.0));
    let mut calls = 0;
    let r = fit_reference_with(
        &wavy(0.3, 0.3),
        &ReferenceFitOptions::default(),
        &mut |_| {
            calls += 1;
            false
        },
    );
    assert_eq!(r.unwrap_err(), ReferenceFitError::Cancelled);
    assert_eq!(calls, 1);
}

/// The typical face with the approximating schemes (slow: run with
/// `--ignored` to see the figures).
#[test]
#[ignore]
fn a_typical_face_with_the_approximating_schemes() {
    for scheme in [SurfaceScheme::CatmullClark, SurfaceScheme::DooSabin] {
        let f = fit_reference(
            &wavy(0.3, 0.3),
            &ReferenceFitOptions {
                scheme,
                ..Default::default()
            },
        )
        .unwrap();
        show(&format!("typical face, {}", scheme.name()), &f);
        assert!(f.within || f.why.is_some());
    }
}

#[test]
fn a_torus_whose_error_is_across_the_rows_fits_by_inserting_rows() {
    let reference = torus(0.6, 0.25);
    let point = reference.point(0.3, 0.7);
    let on = (point.x.hypot(point.y) - 0.6).hypot(point.z) - 0.25;
    assert!(on.abs() < 1e-12, "the patch is on the torus: {on}");
    let f = fit_reference(&reference, &ReferenceFitOptions::default()).unwrap();
    show("quarter torus along u", &f);
    assert!(f.within, "{:?}", f.why);
    let outside = outside_deviation(&f.design, f.depth, &reference);
    assert!(outside <= f.tolerance * (1.0 + 1e-9), "{outside}");
    // every tangent is the reference's, so only rows could bring it closer:
    // more rows than the smallest net's
    assert!(f.net.0 > 4, "{:?}", f.net);
    // negative control: the smallest net is not within the tolerance
    let small = fit_reference(
        &reference,
        &ReferenceFitOptions {
            max_net: (4, 4),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(!small.within && small.to_reference.max > f.tolerance);
}

/// With one direction at its cap, the growth stops a few nets after the
/// other stopped helping, and says which direction ran out and what to do
/// (it used to grow the other direction to its cap for nothing).
#[test]
fn a_net_full_in_one_direction_stops_early_and_says_which() {
    let reference = wavy(0.3, 0.3);
    let capped = |max_net| {
        fit_reference(
            &reference,
            &ReferenceFitOptions {
                max_net,
                ..Default::default()
            },
        )
        .unwrap()
    };
    let few_columns = capped((64, 6));
    show("typical face, columns capped at 6", &few_columns);
    assert!(!few_columns.within);
    let why = few_columns.why.clone().unwrap();
    assert!(
        why.contains("columns reached their cap of 6")
            && why.contains("run the streamlines along v"),
        "{why}"
    );
    // early: not the 60 rows the cap would allow
    assert!(few_columns.steps < 20, "{} nets", few_columns.steps);
    assert!(few_columns.net.0 < 30, "{:?}", few_columns.net);
    // negative control: the same face with room in both directions fits
    let free = capped((64, 64));
    assert!(free.within, "{:?}", free.why);
    assert!(free.net.1 > 6);
}

/// An approximating scheme on the quarter torus: Doo–Sabin fits (its limit
/// rows take the reference's lengths and rows go where the distance is not
/// the tangents' doing); Catmull–Clark, whose rows stay off though its
/// tangents are the torus's, is refused after a few nets with why and what
/// to do, not after growing to the cap.
#[test]
fn an_approximating_scheme_on_a_torus_fits_or_says_why_early() {
    let reference = torus(0.6, 0.25);
    let with = |scheme| {
        fit_reference(
            &reference,
            &ReferenceFitOptions {
                scheme,
                ..Default::default()
            },
        )
        .unwrap()
    };
    let ds = with(SurfaceScheme::DooSabin);
    show("quarter torus, doo-sabin", &ds);
    assert!(ds.within, "{:?}", ds.why);
    let outside = outside_deviation(&ds.design, ds.depth, &reference);
    assert!(outside <= ds.tolerance * (1.0 + 1e-9), "{outside}");
    let cc = with(SurfaceScheme::CatmullClark);
    show("quarter torus, catmull-clark", &cc);
    if !cc.within {
        let why = cc.why.clone().unwrap();
        assert!(
            why.contains("approximates") && why.contains("--scheme kobbelt"),
            "{why}"
        );
        assert!(cc.steps <= 40, "{} nets", cc.steps);
        // negative control: the design really is that far
        let outside = outside_deviation(&cc.design, cc.depth, &reference);
        assert!(outside > cc.tolerance, "{outside}");
    }
}
