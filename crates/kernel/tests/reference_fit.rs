//! The fit of a streamline design to a reference surface (docs/math.md §12):
//! the invariants of "Starting from what exists", each with a negative
//! control, the refusals, and the figures (deviations, net sizes, seconds).

use glam::DVec3;
use proptest::prelude::*;
use std::time::Instant;
use streamline_kernel::fit::{
    Along, AnchorAt, ClosestPoints, ReferenceFit, ReferenceFitError, ReferenceFitOptions,
    ReferenceSurface, Tolerance, distances_to_reference, fit_reference, fit_reference_with,
};
use streamline_kernel::levels::presets;
use streamline_kernel::nurbs::rational::NurbsSurface;
use streamline_kernel::nurbs::{FitOptions, fit_design};
use streamline_kernel::{Design, Grid, SurfaceScheme};

/// The flat rectangle `[0, w] × [0, h]` in `z = 0`, bilinear.
fn flat(w: f64, h: f64) -> NurbsSurface {
    NurbsSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        Grid::new(
            2,
            2,
            vec![
                DVec3::ZERO,
                DVec3::new(w, 0.0, 0.0),
                DVec3::new(0.0, h, 0.0),
                DVec3::new(w, h, 0.0),
            ],
        )
        .unwrap(),
        None,
    )
    .unwrap()
}

/// A quarter cylinder of radius `r` about the `z` axis: `u` the arc (rational
/// quadratic, exact), `v` the height `0..h` (linear).
fn cylinder(r: f64, h: f64) -> NurbsSurface {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [
        DVec3::new(r, 0.0, 0.0),
        DVec3::new(r, r, 0.0),
        DVec3::new(0.0, r, 0.0),
    ];
    let mut poles = Vec::new();
    let mut weights = Vec::new();
    for z in [0.0, h] {
        for p in arc {
            poles.push(p + DVec3::new(0.0, 0.0, z));
        }
        weights.extend([1.0, w, 1.0]);
    }
    NurbsSurface::new(
        2,
        1,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        Grid::new(2, 3, poles).unwrap(),
        Some(Grid::new(2, 3, weights).unwrap()),
    )
    .unwrap()
}

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

/// A full cylinder (closed in `u`): four rational quarter arcs.
fn full_cylinder(r: f64, h: f64) -> NurbsSurface {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let ring = [
        (r, 0.0, 1.0),
        (r, r, w),
        (0.0, r, 1.0),
        (-r, r, w),
        (-r, 0.0, 1.0),
        (-r, -r, w),
        (0.0, -r, 1.0),
        (r, -r, w),
        (r, 0.0, 1.0),
    ];
    let mut poles = Vec::new();
    let mut weights = Vec::new();
    for z in [0.0, h] {
        for (x, y, wt) in ring {
            poles.push(DVec3::new(x, y, z));
            weights.push(wt);
        }
    }
    NurbsSurface::new(
        2,
        1,
        vec![
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
        ],
        vec![0.0, 0.0, 1.0, 1.0],
        Grid::new(2, 9, poles).unwrap(),
        Some(Grid::new(2, 9, weights).unwrap()),
    )
    .unwrap()
}

/// A wavy bicubic face with interior knots (a typical freeform face).
fn wavy(seed: f64, amp: f64) -> NurbsSurface {
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let (nu, nv) = (ku.len() - 4, kv.len() - 4);
    let mut poles = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (x, y) = (i as f64 / (nu - 1) as f64, j as f64 / (nv - 1) as f64);
            let z = amp * ((3.0 * x + seed).sin() * (2.0 * y - seed).cos());
            poles.push(DVec3::new(2.0 * x + 0.1 * y * y, 1.5 * y, z));
        }
    }
    NurbsSurface::new(3, 3, ku, kv, Grid::new(nv, nu, poles).unwrap(), None).unwrap()
}

/// A bicubic Bézier patch `x = (2u − 1)³`, `y = v`: `∂R/∂u = 0` along `u = ½`.
fn cusp() -> NurbsSurface {
    let xs = [-1.0, 1.0, -1.0, 1.0];
    let mut poles = Vec::new();
    for j in 0..4 {
        for x in xs {
            poles.push(DVec3::new(x, j as f64 / 3.0, 0.1 * x * x));
        }
    }
    let k = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(3, 3, k.clone(), k, Grid::new(4, 4, poles).unwrap(), None).unwrap()
}

/// A triangle-like patch: its edge `v = 0` is one point.
fn collapsed_row() -> NurbsSurface {
    let poles = vec![
        DVec3::ZERO,
        DVec3::ZERO,
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
    ];
    let k = vec![0.0, 0.0, 1.0, 1.0];
    NurbsSurface::new(1, 1, k.clone(), k, Grid::new(2, 2, poles).unwrap(), None).unwrap()
}

fn show(name: &str, f: &ReferenceFit) {
    eprintln!(
        "{name}: net {:?}, to reference max {:.3e} mean {:.3e}, from reference max {:.3e} mean {:.3e}, tolerance {:.3e}, within {}, {} nets, initial curve {:.1e} ({} tangents), {:.3} s",
        f.net,
        f.to_reference.max,
        f.to_reference.mean,
        f.from_reference.max,
        f.from_reference.mean,
        f.tolerance,
        f.within,
        f.steps,
        f.initial_deviation,
        f.initial_tangents,
        f.seconds
    );
}

/// The largest distance from the design's mesh at `depth` to `reference`,
/// measured from outside the fit (nearest sample, then Newton).
fn outside_deviation(design: &Design, depth: u32, reference: &dyn ReferenceSurface) -> f64 {
    let b = design.build(depth).unwrap();
    distances_to_reference(reference, b.points.data())
        .unwrap()
        .into_iter()
        .fold(0.0, f64::max)
}

fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

#[test]
fn a_flat_rectangle_needs_four_by_four_and_equal_tangents() {
    let f = fit_reference(&flat(2.0, 1.0), &ReferenceFitOptions::default()).unwrap();
    show("flat rectangle", &f);
    assert!(f.within && f.why.is_none());
    assert!(f.net.0 <= 4 && f.net.1 <= 4, "{:?}", f.net);
    let t0 = f.design.net().get(0, 0);
    for t in f.design.net().data() {
        assert!(angle(*t, t0) < 1e-12, "{t} vs {t0}");
    }
    assert!(f.to_reference.max < 1e-12 && f.from_reference.max < 1e-12);
    // negative control: a gently bent face does not get equal tangents
    let g = fit_reference(&wavy(0.0, 0.05), &ReferenceFitOptions::default()).unwrap();
    let spread = g
        .design
        .net()
        .data()
        .iter()
        .map(|t| angle(*t, g.design.net().get(0, 0)))
        .fold(0.0, f64::max);
    assert!(spread > 1e-3, "{spread}");
}

#[test]
fn a_cylinder_patch_fits_and_its_rulings_keep_one_tangent() {
    let r = 1.0;
    let reference = cylinder(r, 2.0);
    for along in [Along::U, Along::V] {
        let f = fit_reference(
            &reference,
            &ReferenceFitOptions {
                along,
                ..Default::default()
            },
        )
        .unwrap();
        show(&format!("quarter cylinder along {along:?}"), &f);
        assert!(f.within, "{:?}", f.why);
        assert!(f.to_reference.max <= f.tolerance && f.from_reference.max <= f.tolerance);
        let net = f.design.net();
        match along {
            // rows are arcs: a ruling is a column
            Along::U => {
                for c in 0..net.cols() {
                    for r in 1..net.rows() {
                        assert!(angle(net.get(r, c), net.get(0, c)) < 1e-12);
                    }
                }
            }
            // rows are rulings: every tangent of a row is the same
            Along::V => {
                for r in 0..net.rows() {
                    for c in 1..net.cols() {
                        assert!(angle(net.get(r, c), net.get(r, 0)) < 1e-12);
                    }
                }
            }
        }
        // every mesh point on the cylinder, within the tolerance
        let b = f.design.build(f.depth).unwrap();
        for p in b.points.data() {
            let rad = (p.x * p.x + p.y * p.y).sqrt();
            assert!((rad - r).abs() <= f.tolerance, "radius {rad}");
        }
    }
    // negative control: a twisted face (a hyperbolic paraboloid) does not
    // keep one tangent down a column
    let twisted = NurbsSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        Grid::new(
            2,
            2,
            vec![
                DVec3::ZERO,
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
                DVec3::new(1.0, 1.0, 0.6),
            ],
        )
        .unwrap(),
        None,
    )
    .unwrap();
    let f = fit_reference(&twisted, &ReferenceFitOptions::default()).unwrap();
    let net = f.design.net();
    let d = angle(net.get(0, 0), net.get(net.rows() - 1, 0));
    assert!(d > 0.1, "{d}");
}

#[test]
fn swapping_u_and_v_and_running_along_v_gives_the_same_design() {
    let reference = wavy(0.7, 0.25);
    let o = ReferenceFitOptions {
        tolerance: Tolerance::Relative(1e-3),
        ..Default::default()
    };
    let a = fit_reference(&reference, &o).unwrap();
    let b = fit_reference(
        &reference.swapped(),
        &ReferenceFitOptions {
            along: Along::V,
            ..o
        },
    )
    .unwrap();
    show("wavy along u", &a);
    show("wavy swapped, along v", &b);
    assert_eq!(a.net, b.net);
    let (na, nb) = (a.design.net(), b.design.net());
    for (x, y) in na.data().iter().zip(nb.data()) {
        assert!(angle(*x, *y) < 1e-9, "{x} vs {y}");
    }
    for (x, y) in a
        .design
        .params()
        .s
        .data()
        .iter()
        .zip(b.design.params().s.data())
    {
        assert!((x - y).abs() < 1e-9, "{x} vs {y}");
    }
    assert!((a.to_reference.max - b.to_reference.max).abs() < 1e-9);
    // negative control: the swapped reference along u is another design
    let c = fit_reference(&reference.swapped(), &o).unwrap();
    let differs = c.net != a.net
        || c.design
            .net()
            .data()
            .iter()
            .zip(na.data())
            .any(|(x, y)| angle(*x, *y) > 1e-3);
    assert!(differs);
}

#[test]
fn a_design_exported_as_a_b_spline_and_fitted_back_is_within_the_tolerance() {
    // (the presets whose streamlines do not cross: `wavy(5, 6)` folds over
    // at its far end, where a closest point is no longer one point)
    for (name, design) in [("car 1", presets::car1()), ("car 2", presets::car2())] {
        let exported = fit_design(&design, 4, &FitOptions::default()).unwrap();
        let reference = NurbsSurface::from_bspline(&exported.surface);
        let f = fit_reference(&reference, &ReferenceFitOptions::default()).unwrap();
        show(&format!("{name} exported and fitted back"), &f);
        assert!(f.within, "{name}: {:?}", f.why);
        let outside = outside_deviation(&f.design, f.depth, &reference);
        eprintln!(
            "  {name}: outside measurement {outside:.6e}, reported {:.6e}",
            f.to_reference.max
        );
        assert!(outside <= f.tolerance * (1.0 + 1e-9));
        assert!(
            (outside - f.to_reference.max).abs() <= 1e-6 * f.to_reference.max.max(1e-12),
            "{outside} vs {}",
            f.to_reference.max
        );
        // negative control: the same design against the surface scaled by 1 %
        let moved = reference.scaled(1.01);
        assert!(outside_deviation(&f.design, f.depth, &moved) > f.tolerance);
    }
}

#[test]
fn the_schemes_and_the_middle_anchor_fit_a_cylinder() {
    let reference = cylinder(1.5, 2.0);
    for (scheme, anchor) in [
        (SurfaceScheme::CatmullClark, AnchorAt::First),
        (SurfaceScheme::DooSabin, AnchorAt::First),
        (SurfaceScheme::default(), AnchorAt::Middle),
        (SurfaceScheme::CatmullClark, AnchorAt::Middle),
    ] {
        let f = fit_reference(
            &reference,
            &ReferenceFitOptions {
                scheme,
                anchor,
                ..Default::default()
            },
        )
        .unwrap();
        show(
            &format!("cylinder, {} anchored {anchor:?}", scheme.name()),
            &f,
        );
        assert!(f.within, "{}: {:?}", scheme.name(), f.why);
        let outside = outside_deviation(&f.design, f.depth, &reference);
        assert!(outside <= f.tolerance * (1.0 + 1e-9), "{outside}");
    }
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

/// A closed-form reference whose points turn NaN.
struct Broken;

impl ReferenceSurface for Broken {
    fn domain(&self) -> ([f64; 2], [f64; 2]) {
        ([0.0, 1.0], [0.0, 1.0])
    }
    fn point(&self, u: f64, v: f64) -> DVec3 {
        if u > 0.5 {
            DVec3::NAN
        } else {
            DVec3::new(u, v, 0.0)
        }
    }
    fn derivatives(&self, u: f64, v: f64) -> [DVec3; 3] {
        [self.point(u, v), DVec3::X, DVec3::Y]
    }
}

/// A closed-form reference with an empty domain.
struct Empty;

impl ReferenceSurface for Empty {
    fn domain(&self) -> ([f64; 2], [f64; 2]) {
        ([0.0, 1.0], [1.0, 1.0])
    }
    fn point(&self, u: f64, v: f64) -> DVec3 {
        DVec3::new(u, v, 0.0)
    }
    fn derivatives(&self, u: f64, v: f64) -> [DVec3; 3] {
        [self.point(u, v), DVec3::X, DVec3::Y]
    }
}

#[test]
fn every_refusal_names_the_edge_and_the_fix() {
    let o = ReferenceFitOptions::default();
    let along_v = ReferenceFitOptions {
        along: Along::V,
        ..o
    };
    // a pole: ∂R/∂u = 0 along u = 1/2
    match fit_reference(&cusp(), &o) {
        Err(e @ ReferenceFitError::Pole { u, .. }) => {
            assert!((u - 0.5).abs() < 1e-12, "{u}");
            assert!(e.to_string().contains("run the streamlines along v"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    // negative control: along v the same face fits
    assert!(fit_reference(&cusp(), &along_v).unwrap().within);
    // a row of zero length
    match fit_reference(&collapsed_row(), &o) {
        Err(e @ ReferenceFitError::ZeroLengthRow { .. }) => {
            assert!(e.to_string().contains("v = 0"), "{e}");
            assert!(e.to_string().contains("along v"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    // an initial curve of zero length: along v, the collapsed edge is it
    match fit_reference(&collapsed_row(), &along_v) {
        Err(e @ ReferenceFitError::ZeroLengthInitial { .. }) => {
            assert!(e.to_string().contains("v = 0"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    // negative control: anchored in the middle, the initial curve has a length
    let mid = fit_reference(
        &collapsed_row(),
        &ReferenceFitOptions {
            anchor: AnchorAt::Middle,
            ..along_v
        },
    );
    assert!(
        !matches!(mid, Err(ReferenceFitError::ZeroLengthInitial { .. })),
        "{mid:?}"
    );
    // closed in the streamline direction
    match fit_reference(&full_cylinder(1.0, 1.0), &o) {
        Err(e @ ReferenceFitError::Closed { .. }) => {
            assert!(e.to_string().contains("run the streamlines along v"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    // negative control: along the rulings it fits
    let f = fit_reference(&full_cylinder(1.0, 1.0), &along_v).unwrap();
    assert!(f.within, "{:?}", f.why);
    // non-finite input, an empty domain, bad options
    assert!(matches!(
        fit_reference(&Broken, &o),
        Err(ReferenceFitError::NonFinite { .. })
    ));
    assert!(matches!(
        fit_reference(&Empty, &o),
        Err(ReferenceFitError::EmptyDomain { direction: 'v' })
    ));
    for bad in [
        ReferenceFitOptions { depth: 0, ..o },
        ReferenceFitOptions { depth: 9, ..o },
        ReferenceFitOptions {
            max_net: (3, 64),
            ..o
        },
        ReferenceFitOptions {
            max_net: (64, 65),
            ..o
        },
    ] {
        let e = fit_reference(&flat(1.0, 1.0), &bad).unwrap_err();
        assert!(matches!(e, ReferenceFitError::BadOption { .. }), "{e:?}");
    }
    for t in [
        Tolerance::Relative(0.0),
        Tolerance::Absolute(-1.0),
        Tolerance::Absolute(f64::NAN),
    ] {
        let e =
            fit_reference(&flat(1.0, 1.0), &ReferenceFitOptions { tolerance: t, ..o }).unwrap_err();
        assert!(matches!(e, ReferenceFitError::BadTolerance { .. }), "{e:?}");
    }
    assert!(ClosestPoints::new(&Empty).is_err());
}

#[test]
fn closest_points_are_exact_on_a_cylinder_and_fast() {
    let r = 2.0;
    let reference = cylinder(r, 3.0);
    let index = ClosestPoints::new(&reference).unwrap();
    // points off the cylinder by known distances, inside its angle and height
    let n = 50_000;
    let mut pts = Vec::with_capacity(n);
    let mut want = Vec::with_capacity(n);
    for i in 0..n {
        let a = std::f64::consts::FRAC_PI_2 * (0.05 + 0.9 * ((i * 7919) % n) as f64 / n as f64);
        let z = 0.1 + 2.8 * ((i * 104_729) % n) as f64 / n as f64;
        let off = 0.2 * (((i * 31) % 101) as f64 / 100.0 - 0.5);
        pts.push(DVec3::new((r + off) * a.cos(), (r + off) * a.sin(), z));
        want.push(off.abs());
    }
    let start = Instant::now();
    let got = index.distances(&pts);
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "closest points: {n} points in {:.1} ms ({} samples)",
        secs * 1e3,
        index.samples()
    );
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-10, "{g} vs {w}");
    }
    // negative control: a point past the patch's edge is further than its
    // distance to the full cylinder
    let outside = DVec3::new(-r, 0.1, 1.0);
    assert!(index.closest(outside).0 > 1.0);
    assert_eq!(index.closest(DVec3::NAN).0, f64::INFINITY);
}

/// A random bicubic face: a plane bent by random heights at its poles.
fn random_face(heights: &[f64], knot: f64, w: f64, h: f64) -> NurbsSurface {
    let ku = vec![0.0, 0.0, 0.0, 0.0, knot, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let mut poles = Vec::new();
    for j in 0..4 {
        for i in 0..5 {
            let (x, y) = (i as f64 / 4.0, j as f64 / 3.0);
            poles.push(DVec3::new(w * x, h * y, heights[j * 5 + i]));
        }
    }
    NurbsSurface::new(3, 3, ku, kv, Grid::new(4, 5, poles).unwrap(), None).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]

    /// Random faces fit within the tolerance (or say why), and the reported
    /// deviation is what an outside measurement finds.
    #[test]
    fn random_faces_fit_and_report_what_is_measured(
        heights in prop::collection::vec(-0.15f64..0.15, 20),
        knot in 0.3f64..0.7,
        w in 1.0f64..3.0,
        h in 0.8f64..2.0,
    ) {
        let reference = random_face(&heights, knot, w, h);
        let f = fit_reference(&reference, &ReferenceFitOptions::default()).unwrap();
        prop_assert!(f.within || f.why.is_some());
        prop_assert!(f.within, "{:?}", f.why);
        let outside = outside_deviation(&f.design, f.depth, &reference);
        prop_assert!(outside <= f.tolerance * (1.0 + 1e-9));
        prop_assert!((outside - f.to_reference.max).abs() <= 1e-6 * f.to_reference.max);
        // negative control: the design is not within the tolerance of the
        // flat face it was bent from
        let plane = random_face(&[0.0; 20], knot, w, h);
        let bent = heights.iter().any(|x| x.abs() > 0.05);
        if bent {
            prop_assert!(outside_deviation(&f.design, f.depth, &plane) > f.tolerance);
        }
    }
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
