//! `docs/math.md §9`, templates: Flat is the rectangle, Cylinder lies on the cylinder
//! (closed forms), bad values are errors that say the fix.

mod common;

use common::authoring::*;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::authoring::{MAX_NET_SIDE, Template};
use streamline_kernel::streamline::surface_mesh::bounds;
use streamline_kernel::{BlendOrder, Design, KernelError, SurfaceScheme};

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn template_flat_is_the_rectangle(rows in 2usize..12, cols in 2usize..12, len in 0.01f64..50.0, width in 0.01f64..50.0, which in 0usize..3, depth in 0u32..4) {
        let scheme = SCHEMES[which];
        prop_assume!(rows.min(cols) >= scheme.curve().min_len() || depth == 0);
        let d = Design::from_template(rows, cols, len, Template::Flat { width }, scheme, BlendOrder::SFirst).unwrap();
        let p = points(&d, depth);
        let tol = 1e-12 * len.max(width);
        // the rows are anchored at their limit start (docs/math.md §4, "The
        // anchor"), one spacing in for the cubic B-spline, half of one for
        // Chaikin: the rectangle is moved back by that much
        let h = len / (cols - 1) as f64;
        let a = match scheme {
            SurfaceScheme::CatmullClark if cols >= 3 => h,
            SurfaceScheme::DooSabin => 0.5 * h,
            _ => 0.0,
        };
        for v in p.data() {
            prop_assert!(v.z == 0.0, "z = {} at {v:?}", v.z);
            prop_assert!(v.x >= -a - tol && v.x <= len - a + tol && v.y >= -tol && v.y <= width + tol, "{v:?} outside [{},{}]x[0,{width}]", -a, len - a);
        }
        if scheme.is_interpolatory() {
            let [lo, hi] = bounds(p.data().iter().copied());
            prop_assert!(lo.length() < tol && (hi - DVec3::new(len, width, 0.0)).length() < tol, "bounds {lo:?} {hi:?} vs the rectangle {len} x {width}");
        }
    }

    #[test]
    fn template_cylinder_lies_on_the_cylinder(rows in 2usize..10, cols in 2usize..8, len in 0.1f64..10.0, r in 0.01f64..100.0, degrees in 0.5f64..359.5, which in 0usize..3, depth in 0u32..5) {
        let scheme = SCHEMES[which];
        prop_assume!(rows.min(cols) >= scheme.curve().min_len() || depth == 0);
        let d = Design::from_template(rows, cols, len, Template::Cylinder { radius: r, degrees }, scheme, BlendOrder::SFirst).unwrap();
        let phi = degrees.to_radians();
        prop_assert!((d.initial().length() - r * phi).abs() < 1e-14 * r * phi, "length r·φ");
        // the initial curve is the closed-form arc, to the quadrature's error
        for j in 0..=20 {
            let t = r * phi * j as f64 / 20.0;
            let exact = DVec3::new(0.0, r * (t / r).sin(), r * (1.0 - (t / r).cos()));
            let e = (d.initial().point(t) - exact).length();
            prop_assert!(e < 1e-12 * r, "arc point at t={t}: error {e:e} (r={r}, φ={degrees}°)");
        }
        prop_assert!(d.initial().quadrature_error_estimate() < 1e-13 * r, "quadrature {:e}", d.initial().quadrature_error_estimate());
        let p = points(&d, depth);
        let worst = p.data().iter().map(|v| ((v.y * v.y + (v.z - r) * (v.z - r)).sqrt() - r).abs()).fold(0.0, f64::max);
        prop_assert!(worst < 1e-6 * r, "off the cylinder by {worst:e} (r={r})");
        prop_assert!(worst < 1e-12 * r, "off the cylinder by {worst:e}: more than the quadrature explains");
    }
}

#[test]
fn template_bad_values_are_errors_with_the_fix() {
    let k = SurfaceScheme::default();
    let o = BlendOrder::SFirst;
    let flat = Template::Flat { width: 1.0 };
    let e = Design::from_template(65, 4, 1.0, flat, k, o).unwrap_err();
    assert_eq!(
        e,
        KernelError::NetTooLarge {
            rows: 65,
            cols: 4,
            max: MAX_NET_SIDE
        }
    );
    assert!(
        e.to_string().contains("use at most 64 rows and 64 columns"),
        "{e}"
    );
    assert!(matches!(
        Design::from_template(1, 4, 1.0, flat, k, o),
        Err(KernelError::NetTooSmall { .. })
    ));
    assert!(matches!(
        Design::from_template(3, 4, 0.0, flat, k, o),
        Err(KernelError::NotPositive { .. })
    ));
    assert!(matches!(
        Design::from_template(3, 4, 1.0, Template::Flat { width: f64::NAN }, k, o),
        Err(KernelError::NotPositive { .. })
    ));
    for deg in [0.0, 360.0, -10.0, 400.0, f64::NAN] {
        let e = Design::from_template(
            3,
            4,
            1.0,
            Template::Cylinder {
                radius: 1.0,
                degrees: deg,
            },
            k,
            o,
        )
        .unwrap_err();
        assert!(
            matches!(e, KernelError::AngleOutOfRange { .. }),
            "{deg}: {e:?}"
        );
        assert!(
            e.to_string().contains("strictly between 0 and 360 degrees"),
            "{e}"
        );
    }
    assert!(matches!(
        Design::from_template(
            3,
            4,
            1.0,
            Template::Cylinder {
                radius: -1.0,
                degrees: 90.0
            },
            k,
            o
        ),
        Err(KernelError::NotPositive { .. })
    ));
    assert!(Design::from_template(64, 64, 1.0, flat, k, o).is_ok());
}
