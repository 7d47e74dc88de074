//! The fit of a streamline design to a reference surface (docs/math.md §12,
//! "Refusals"): a pole, a row or an initial curve of zero length, a face
//! closed along the streamlines, non-finite points, an empty domain, bad
//! options and tolerances are each refused with the edge and the fix, with a
//! negative control (the same face fitted the way the refusal says) where
//! one applies.

mod common;

use common::reference_fit::flat;
use glam::DVec3;
use streamline_kernel::Grid;
use streamline_kernel::fit::{
    Along, AnchorAt, ClosestPoints, ReferenceFitError, ReferenceFitOptions, ReferenceSurface,
    Tolerance, fit_reference,
};
use streamline_kernel::nurbs::rational::NurbsSurface;

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
