//! SPEC §2: the QI curve (Eqs. 22–26) — unit, end points, rotation equivariance,
//! the great-circle reduction against an independent Cox–de Boor basis, and the
//! (non-)symmetry the paper notes in Eq. 27.

mod common;

use common::*;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::curve::qi::QiCurve;

proptest! {
    #![proptest_config(ProptestConfig { cases: 150, ..ProptestConfig::default() })]

    #[test]
    fn qi_unit_endpoints_equivariant(t in walk(5..=9, 2.8), k in 2usize..6, r in rotation(), u in 0.0f64..1.0) {
        let k = k.min(t.len());
        let q = QiCurve::new(&t, k).unwrap();
        prop_assert!((q.tangent(0.0) - t[0]).length() < 1e-12);
        prop_assert!((q.tangent(1.0) - *t.last().unwrap()).length() < 1e-12);
        let v = q.tangent(u);
        prop_assert!((v.length() - 1.0).abs() < 1e-12);
        let rt: Vec<DVec3> = t.iter().map(|&x| r * x).collect();
        let rq = QiCurve::new(&rt, k).unwrap();
        prop_assert!((rq.tangent(u) - r * v).length() < 1e-11, "rotation equivariance");
    }

    #[test]
    fn qi_great_circle_is_planar_bspline_of_angles(angles in circle_angles(4..=8), k in 2usize..6, r in rotation(), u in 0.0f64..=1.0) {
        let k = k.min(angles.len());
        let t: Vec<DVec3> = angles.iter().map(|&a| on_circle(r, a)).collect();
        let q = QiCurve::new(&t, k).unwrap();
        // φ(u) = φ₀ + Σ_i (φ_i − φ_{i−1}) B̃_i(u),  B̃_i = Σ_{j≥i} B_j (Eq. 24)
        let knots = q.knots().to_vec();
        let n = angles.len() - 1;
        let b: Vec<f64> = (0..=n).map(|j| bspline_basis(&knots, j, k, u, true)).collect();
        let mut want = angles[0];
        for i in 1..=n {
            let cum: f64 = b[i..].iter().sum();
            want += (angles[i] - angles[i - 1]) * cum;
        }
        let (a, off) = circle_angle(r, q.tangent(u), want);
        prop_assert!(off < 1e-12 && (a - want).abs() < 1e-11, "k={k} u={u}: {a} vs {want}");
        // On a great circle the curve is reversal symmetric (Eq. 27's asymmetry needs 3D).
        let rev: Vec<DVec3> = t.iter().rev().copied().collect();
        let rq = QiCurve::new(&rev, k).unwrap();
        prop_assert!((rq.tangent(1.0 - u) - q.tangent(u)).length() < 1e-11);
    }

    #[test]
    fn qi_nasty_inputs_never_nan(t in nasty(3..=7), k in 2usize..5, u in 0.0f64..=1.0) {
        let k = k.min(t.len());
        let q = QiCurve::new(&t, k).unwrap();
        let v = q.tangent(u);
        prop_assert!(v.is_finite() && (v.length() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn qi_is_not_reversal_symmetric_in_3d() {
    // Eq. 27: r_r(u) ≠ q(1 − u) in general.
    let t = [
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        DVec3::new(1.0, 1.0, 0.0).normalize(),
        DVec3::new(0.0, 1.0, 1.0).normalize(),
    ];
    let q = QiCurve::new(&t, 4).unwrap();
    let rev: Vec<DVec3> = t.iter().rev().copied().collect();
    let r = QiCurve::new(&rev, 4).unwrap();
    let d = (r.tangent(0.7) - q.tangent(0.3)).length();
    assert!(
        d > 1e-6,
        "QI curves differ from their reversal (Eq. 27): {d:e}"
    );
}
