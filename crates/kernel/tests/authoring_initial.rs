//! `docs/math.md §9`, the initial curve, the anchor and streamline lengths as handles:
//! their edits move every streamline rigidly, lengths are exact, bad values are
//! errors.

mod common;

use common::authoring::*;
use common::*;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::KernelError;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::presets;
use streamline_kernel::streamline::integrate::polyline_length;

/// Row `r` of `b` is row `r` of `a` moved by one vector.
fn rigid_rows(a: &Grid<DVec3>, b: &Grid<DVec3>, tol: f64) -> Result<(), String> {
    for r in 0..a.rows() {
        let shift = b.get(r, 0) - a.get(r, 0);
        for k in 0..a.cols() {
            let e = (b.get(r, k) - a.get(r, k) - shift).length();
            if e > tol {
                return Err(format!(
                    "row {r}, point {k}: not a rigid move (off by {e:e})"
                ));
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn initial_curve_edit_moves_every_streamline_rigidly(d in design(), which in 0usize..4, dir in unit(), k in 0usize..3, x in -2.0f64..2.0, depth in 0u32..3) {
        let e = match which {
            0 => d.with_initial_direction(k, (DVec3::Y + dir * 0.8).normalize()),
            1 => d.with_initial_length(d.initial().length() * (0.3 + x.abs())),
            2 => d.with_initial_origin(dir * x),
            _ => d.with_initial_order(2 + k % 2),
        };
        let Ok(e) = e else { return Ok(()) };
        let (la, lb) = (d.level(depth).unwrap(), e.level(depth).unwrap());
        prop_assert!(la == lb, "an initial-curve edit changes no tangent and no parameter (nothing to re-blend)");
        let (pa, pb) = (d.streamlines(&la), e.streamlines(&lb));
        rigid_rows(&pa, &pb, 1e-12).map_err(TestCaseError::fail)?;
        for r in 0..pa.rows() {
            let t = la.params.t[r];
            let want = e.initial().point(t) - d.initial().point(t);
            let got = pb.get(r, 0) - pa.get(r, 0);
            prop_assert!((want - got).length() < 1e-12, "row {r} moves by {got:?}, the curve by {want:?}");
        }
    }

    #[test]
    fn anchor_edit_moves_every_streamline_rigidly(d in design(), col in 0usize..8, depth in 0u32..3) {
        let e = d.with_anchor(col % d.net().cols()).unwrap();
        let (la, lb) = (d.level(depth).unwrap(), e.level(depth).unwrap());
        prop_assert!(la.tangents == lb.tangents && la.params.s == lb.params.s, "same tangents and s");
        rigid_rows(&d.streamlines(&la), &e.streamlines(&lb), 1e-12).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn streamline_length_is_exact(d in design(), row in 0usize..7, len in 0.01f64..30.0) {
        let row = row % d.net().rows();
        let e = match d.with_streamline_length(row, len) { Ok(e) => e, Err(KernelError::ParamsNotIncreasing { .. }) => return Ok(()), Err(x) => panic!("{x}") };
        let pts = e.streamlines(&e.base());
        let got = polyline_length(pts.row(row));
        prop_assert!((got - len).abs() < 1e-12 * len, "streamline {row} is {got} long, asked {len}");
        for r in 0..d.net().rows() {
            if r != row {
                prop_assert!(e.params().s.row(r) == d.params().s.row(r), "other rows keep their s");
            }
        }
        // same shape: the polyline is the old one scaled about its anchor point
        let old = d.streamlines(&d.base());
        let f = len / d.streamline_length(row).unwrap();
        let (a0, a1) = (old.row(row)[0], pts.row(row)[0]);
        let o = d.initial().point(d.params().t[row]);
        for k in 0..pts.cols() {
            let want = o + (old.get(row, k) - o) * f;
            prop_assert!((pts.get(row, k) - want).length() < 1e-9 * (1.0 + f), "point {k}: {:?} vs {want:?} ({a0:?} {a1:?})", pts.get(row, k));
        }
        // an interpolatory scheme keeps the control row at every depth: same length there
        if let (true, Ok(l)) = (d.scheme().is_interpolatory(), e.level(2)) {
            let fine = polyline_length(e.streamlines(&l).row(row * 4));
            prop_assert!((fine - len).abs() < 1e-12 * len, "depth 2: {fine} vs {len}");
        }
    }
}

#[test]
fn initial_and_length_bad_values_are_errors() {
    let d = presets::car1();
    assert!(matches!(
        d.with_initial_direction(4, DVec3::Y),
        Err(KernelError::IndexOutOfRange {
            index: 4,
            len: 4,
            ..
        })
    ));
    let e = d.with_initial_direction(1, DVec3::ZERO).unwrap_err();
    assert_eq!(
        e.to_string(),
        "tangent 1 is the zero vector, which has no direction; give it a non-zero direction"
    );
    assert!(matches!(
        d.with_initial_direction(1, DVec3::new(f64::NAN, 0.0, 1.0)),
        Err(KernelError::NonFiniteTangent { .. })
    ));
    for bad in [0.0, -1.0, f64::INFINITY, f64::NAN] {
        assert!(
            matches!(
                d.with_initial_length(bad),
                Err(KernelError::NotPositive { .. })
            ),
            "{bad}"
        );
        assert!(
            matches!(
                d.with_streamline_length(0, bad),
                Err(KernelError::NotPositive { .. })
            ),
            "{bad}"
        );
    }
    assert!(matches!(
        d.with_streamline_length(6, 1.0),
        Err(KernelError::IndexOutOfRange {
            index: 6,
            len: 6,
            ..
        })
    ));
    assert!(matches!(
        d.with_initial_order(5),
        Err(KernelError::OrderOutOfRange { .. })
    ));
    assert!(matches!(
        d.with_initial_origin(DVec3::new(0.0, f64::NAN, 0.0)),
        Err(KernelError::NonFiniteParameter { .. })
    ));
    assert!(matches!(
        d.with_anchor(9),
        Err(KernelError::IndexOutOfRange {
            index: 9,
            len: 9,
            ..
        })
    ));
}
