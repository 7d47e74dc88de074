//! The unit tests of [`NurbsSurface`](super::NurbsSurface)
//! (`docs/math.md §12`): points and derivatives of an exact quarter cylinder
//! and of a non-uniform rational patch, areas and boxes, the exchanged,
//! scaled and §10-exported surfaces, bad input refused, and the
//! Gauss–Legendre rule.

use super::{NurbsSurface, gauss_legendre};
use crate::grid::Grid;
use crate::nurbs::knots::KnotVector;
use crate::nurbs::surface::BSplineSurface;
use glam::DVec3;

/// A quarter cylinder of radius `r` about the `z` axis, `z ∈ [0, h]`, as
/// a rational quadratic (`u`, the arc) × linear (`v`, the height).
fn quarter_cylinder(r: f64, h: f64) -> NurbsSurface {
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

#[test]
fn quarter_cylinder_points_are_on_the_circle() {
    let s = quarter_cylinder(2.5, 1.0);
    for i in 0..=50 {
        for j in 0..=5 {
            let p = s.point(i as f64 / 50.0, j as f64 / 5.0);
            let r = (p.x * p.x + p.y * p.y).sqrt();
            assert!((r - 2.5).abs() < 1e-12, "radius {r}");
        }
    }
    assert!(s.is_rational());
    assert_eq!(s.pole_counts(), (3, 2));
    assert_eq!(s.degrees(), (2, 1));
}

#[test]
fn derivatives_match_finite_differences() {
    let s = quarter_cylinder(1.3, 0.7);
    // a non-uniform cubic × quadratic too
    let kv_u = KnotVector::with_interior(3, &[0.2, 0.55]).unwrap();
    let kv_v = KnotVector::with_interior(2, &[0.4]).unwrap();
    let mut pts = Vec::new();
    let mut ws = Vec::new();
    for r in 0..kv_v.count() {
        for c in 0..kv_u.count() {
            let (x, y) = (c as f64, r as f64);
            pts.push(DVec3::new(x, y, (x * 1.7 + y * 0.3).sin()));
            ws.push(1.0 + 0.3 * ((x + 2.0 * y).cos()));
        }
    }
    let t = NurbsSurface::new(
        3,
        2,
        kv_u.knots().to_vec(),
        kv_v.knots().to_vec(),
        Grid::new(kv_v.count(), kv_u.count(), pts).unwrap(),
        Some(Grid::new(kv_v.count(), kv_u.count(), ws).unwrap()),
    )
    .unwrap();
    let h = 1e-6;
    for surf in [&s, &t] {
        for (u, v) in [(0.1, 0.3), (0.37, 0.81), (0.6, 0.5), (0.9, 0.05)] {
            let [p, du, dv] = surf.derivatives(u, v);
            assert!((p - surf.point(u, v)).length() < 1e-14);
            let fu = (surf.point(u + h, v) - surf.point(u - h, v)) / (2.0 * h);
            let fv = (surf.point(u, v + h) - surf.point(u, v - h)) / (2.0 * h);
            assert!(
                (du - fu).length() < 1e-7 * (1.0 + du.length()),
                "{du} vs {fu}"
            );
            assert!(
                (dv - fv).length() < 1e-7 * (1.0 + dv.length()),
                "{dv} vs {fv}"
            );
        }
    }
}

#[test]
fn areas_of_a_rectangle_and_a_cylinder_patch() {
    let rect = NurbsSurface::new(
        1,
        1,
        vec![0.0, 0.0, 2.0, 2.0],
        vec![-1.0, -1.0, 3.0, 3.0],
        Grid::new(
            2,
            2,
            vec![
                DVec3::ZERO,
                DVec3::new(3.0, 0.0, 0.0),
                DVec3::new(0.0, 2.0, 0.0),
                DVec3::new(3.0, 2.0, 0.0),
            ],
        )
        .unwrap(),
        None,
    )
    .unwrap();
    assert!((rect.area() - 6.0).abs() < 1e-13);
    let cyl = quarter_cylinder(2.0, 3.0);
    let want = std::f64::consts::FRAC_PI_2 * 2.0 * 3.0;
    assert!(
        (cyl.area() - want).abs() < 1e-12 * want,
        "{} vs {want}",
        cyl.area()
    );
    let b = cyl.bounds();
    assert!((b[0] - DVec3::ZERO).length() < 1e-12);
    assert!((b[1] - DVec3::new(2.0, 2.0, 3.0)).length() < 1e-12);
    assert!(!cyl.closed_u(1e-9) && !cyl.closed_v(1e-9));
}

#[test]
fn swapped_scaled_and_from_bspline() {
    let s = quarter_cylinder(1.0, 2.0);
    let w = s.swapped();
    let k = s.scaled(1e-3);
    for (u, v) in [(0.2, 0.7), (0.0, 1.0), (0.9, 0.1)] {
        assert!((w.point(v, u) - s.point(u, v)).length() < 1e-15);
        assert!((k.point(u, v) - s.point(u, v) * 1e-3).length() < 1e-15);
    }
    assert_eq!(s.scaled(f64::NAN), s);
    let b = BSplineSurface {
        knots_u: KnotVector::with_interior(3, &[0.5]).unwrap(),
        knots_v: KnotVector::bezier(2),
        poles: Grid::new(
            3,
            5,
            (0..15)
                .map(|i| DVec3::new(i as f64, (i * i) as f64, 1.0))
                .collect(),
        )
        .unwrap(),
    };
    let n = NurbsSurface::from_bspline(&b);
    assert!(!n.is_rational());
    for (u, v) in [(0.2, 0.7), (0.5, 0.5), (1.0, 1.0)] {
        assert!((n.point(u, v) - b.eval(u, v)).length() < 1e-12);
    }
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let g = Grid::filled(2, 2, DVec3::ZERO);
    let k = vec![0.0, 0.0, 1.0, 1.0];
    let cases = [
        NurbsSurface::new(0, 1, k.clone(), k.clone(), g.clone(), None),
        NurbsSurface::new(2, 1, k.clone(), k.clone(), g.clone(), None),
        NurbsSurface::new(1, 1, vec![0.0, 1.0, 0.5, 1.0], k.clone(), g.clone(), None),
        NurbsSurface::new(
            1,
            1,
            vec![0.0, 0.0, f64::NAN, 1.0],
            k.clone(),
            g.clone(),
            None,
        ),
        NurbsSurface::new(1, 1, vec![1.0; 4], k.clone(), g.clone(), None),
        NurbsSurface::new(
            1,
            1,
            k.clone(),
            k.clone(),
            g.clone(),
            Some(Grid::filled(2, 2, 0.0)),
        ),
        NurbsSurface::new(
            1,
            1,
            k.clone(),
            k.clone(),
            g.clone(),
            Some(Grid::filled(1, 2, 1.0)),
        ),
        NurbsSurface::new(
            1,
            1,
            k.clone(),
            k.clone(),
            Grid::filled(2, 2, DVec3::splat(f64::INFINITY)),
            None,
        ),
        NurbsSurface::new(
            1,
            1,
            k.clone(),
            k.clone(),
            Grid::filled(0, 0, DVec3::ZERO),
            None,
        ),
        NurbsSurface::new(1, 1, vec![], k.clone(), g.clone(), None),
    ];
    for c in cases {
        let e = c.unwrap_err();
        assert!(e.to_string().len() > 40, "{e}");
    }
    // evaluation outside the domain and at NaN clamps
    let s = quarter_cylinder(1.0, 1.0);
    assert!(s.point(f64::NAN, 5.0).is_finite());
    assert!(s.derivatives(-3.0, f64::INFINITY)[1].is_finite());
}

#[test]
fn gauss_legendre_integrates_polynomials_exactly() {
    for n in 1..12 {
        let g = gauss_legendre(n);
        for d in 0..2 * n {
            let got: f64 = g.iter().map(|(x, w)| w * x.powi(d as i32)).sum();
            let want = if d % 2 == 1 {
                0.0
            } else {
                2.0 / (d as f64 + 1.0)
            };
            assert!((got - want).abs() < 1e-13, "n{n} d{d}: {got} vs {want}");
        }
    }
}
