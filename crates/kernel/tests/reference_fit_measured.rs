//! The fit of a streamline design to a reference surface (docs/math.md §12):
//! the deviation a fit reports is what a measurement from outside the fit
//! finds (designs exported by §10 and fitted back, random faces), each with
//! a negative control, and the closest points it is measured by are exact
//! and fast.

mod common;

use common::reference_fit::{cylinder, outside_deviation, show};
use glam::DVec3;
use proptest::prelude::*;
use std::time::Instant;
use streamline_kernel::Grid;
use streamline_kernel::fit::{ClosestPoints, ReferenceFitOptions, fit_reference};
use streamline_kernel::levels::presets;
use streamline_kernel::nurbs::rational::NurbsSurface;
use streamline_kernel::nurbs::{FitOptions, fit_design};

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
