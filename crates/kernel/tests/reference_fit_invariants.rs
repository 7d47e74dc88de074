//! The fit of a streamline design to a reference surface (docs/math.md §12):
//! the invariants of "Starting from what exists" on faces whose design is
//! known, each with a negative control: a flat rectangle gets equal
//! tangents, a cylinder's rulings keep one tangent (with every scheme and
//! anchor), and exchanging `u` and `v` and running along `v` gives the same
//! design.

mod common;

use common::reference_fit::{cylinder, flat, outside_deviation, show, wavy};
use glam::DVec3;
use streamline_kernel::fit::{Along, AnchorAt, ReferenceFitOptions, Tolerance, fit_reference};
use streamline_kernel::nurbs::rational::NurbsSurface;
use streamline_kernel::{Grid, SurfaceScheme};

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
