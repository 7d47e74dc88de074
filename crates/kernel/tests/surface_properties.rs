//! docs/math.md §3 invariants of the tensor-product surface schemes on the sphere.

mod common;

use common::*;
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::surface::{
    BlendOrder, SurfaceScheme, refine_cols, refine_rows, subdivide,
};

fn schemes(omega: f64) -> [(SurfaceScheme, &'static str); 3] {
    [
        (SurfaceScheme::Kobbelt { omega }, "four"),
        (SurfaceScheme::CatmullClark, "cubic"),
        (SurfaceScheme::DooSabin, "chaikin"),
    ]
}

const ORDERS: [BlendOrder; 2] = [BlendOrder::SFirst, BlendOrder::TFirst];

/// A random net: rows are random walks, each row a small rotation of the previous.
fn net(
    rows: std::ops::RangeInclusive<usize>,
    cols: std::ops::RangeInclusive<usize>,
    max_angle: f64,
) -> impl Strategy<Value = Grid<DVec3>> {
    (
        walk(cols, max_angle),
        prop::collection::vec((unit(), 0.0..max_angle), rows),
    )
        .prop_map(|(first, steps)| {
            let mut data = Vec::new();
            let mut cur = first.clone();
            for (axis, angle) in steps {
                let q = DQuat::from_axis_angle(axis, angle);
                cur = cur.iter().map(|&v| (q * v).normalize()).collect();
                data.extend_from_slice(&cur);
            }
            let rows = data.len() / first.len();
            Grid::new(rows, first.len(), data).unwrap()
        })
}

fn close(a: &Grid<DVec3>, b: &Grid<DVec3>, tol: f64) -> Result<(), String> {
    if (a.rows(), a.cols()) != (b.rows(), b.cols()) {
        return Err(format!(
            "sizes {}x{} vs {}x{}",
            a.rows(),
            a.cols(),
            b.rows(),
            b.cols()
        ));
    }
    let worst = a
        .data()
        .iter()
        .zip(b.data())
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max);
    if worst < tol {
        Ok(())
    } else {
        Err(format!("differ by {worst:e}"))
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn surface_outputs_unit_and_nasty_safe(g in net(3..=5, 3..=6, 3.0), depth in 0u32..3, omega in 0.0f64..2.4) {
        for (s, _) in schemes(omega) {
            for o in ORDERS {
                let out = subdivide(s, o, &g, depth).unwrap();
                prop_assert!(out.data().iter().all(|v| v.is_finite() && (v.length() - 1.0).abs() < 1e-12), "{} {}", s.name(), o.name());
            }
        }
    }

    #[test]
    fn surface_nasty_rows_never_nan(rows in prop::collection::vec(nasty(4..=4), 3..=4), depth in 0u32..3) {
        let g = Grid::from_rows(&rows).unwrap();
        for (s, _) in schemes(1.0) {
            for o in ORDERS {
                let out = subdivide(s, o, &g, depth).unwrap();
                prop_assert!(out.data().iter().all(|v| v.is_finite() && (v.length() - 1.0).abs() < 1e-12), "{} {}", s.name(), o.name());
            }
        }
    }

    #[test]
    fn surface_rotation_equivariant(g in net(3..=5, 3..=5, 2.0), depth in 1u32..3, r in rotation(), omega in 0.0f64..2.4) {
        let rg = g.map(|v| r * v);
        for (s, _) in schemes(omega) {
            for o in ORDERS {
                let a = subdivide(s, o, &g, depth).unwrap().map(|v| r * v);
                let b = subdivide(s, o, &rg, depth).unwrap();
                close(&a, &b, 1e-11).map_err(|e| TestCaseError::fail(format!("{} {}: {e}", s.name(), o.name())))?;
            }
        }
    }

    #[test]
    fn surface_reversal_of_rows_and_cols(g in net(3..=5, 3..=5, 2.0), depth in 1u32..3, omega in 0.0f64..2.4) {
        for (s, _) in schemes(omega) {
            for o in ORDERS {
                let base = subdivide(s, o, &g, depth).unwrap();
                let rr = subdivide(s, o, &g.reverse_rows(), depth).unwrap().reverse_rows();
                close(&base, &rr, 1e-11).map_err(|e| TestCaseError::fail(format!("{} {} rows: {e}", s.name(), o.name())))?;
                let rc = subdivide(s, o, &g.reverse_cols(), depth).unwrap().reverse_cols();
                close(&base, &rc, 1e-11).map_err(|e| TestCaseError::fail(format!("{} {} cols: {e}", s.name(), o.name())))?;
            }
        }
    }

    #[test]
    fn surface_transpose_swaps_blend_order(g in net(3..=5, 3..=5, 2.5), depth in 1u32..3, omega in 0.0f64..2.4) {
        for (s, _) in schemes(omega) {
            let a = subdivide(s, BlendOrder::SFirst, &g, depth).unwrap();
            let b = subdivide(s, BlendOrder::TFirst, &g.transpose(), depth).unwrap().transpose();
            prop_assert_eq!(a, b, "{}: s-first(N) = t-first(Nᵀ)ᵀ", s.name());
        }
    }

    #[test]
    fn kobbelt_interpolates_net(g in net(2..=5, 2..=5, 3.0), depth in 1u32..4, omega in 0.0f64..2.4) {
        for o in ORDERS {
            let out = subdivide(SurfaceScheme::Kobbelt { omega }, o, &g, depth).unwrap();
            let step = 1usize << depth;
            for r in 0..g.rows() {
                for c in 0..g.cols() {
                    let v = g.get(r, c);
                    let unit = streamline_kernel::Tangent::new(v).unwrap().get();
                    prop_assert_eq!(out.get(r * step, c * step), unit, "({}, {})", r, c);
                }
            }
        }
    }

    #[test]
    fn surface_great_circle_reduces_to_planar(rows in prop::collection::vec(circle_angles(3..=3), 3..=4), r in rotation(), depth in 1u32..3, omega in 0.0f64..2.4) {
        // Squash the angle grid so every blend stays along the circle: the 4-point
        // rule extrapolates by ω/8 of a leg on each side, so pairs stay under π
        // apart when the spread is under π / (1 + ω/4).
        let flat: Vec<f64> = rows.iter().flatten().copied().collect();
        let lo = flat.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = flat.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let max_spread = 0.95 * std::f64::consts::PI / (1.0 + omega / 4.0);
        let scale = if hi - lo > max_spread { max_spread / (hi - lo) } else { 1.0 };
        let ang: Vec<Vec<f64>> = rows.iter().map(|row| row.iter().map(|a| lo + (a - lo) * scale).collect()).collect();
        let g = Grid::from_rows(&ang.iter().map(|row| row.iter().map(|&a| on_circle(r, a)).collect()).collect::<Vec<_>>()).unwrap();
        for (s, name) in schemes(omega) {
            // planar tensor product: rows, then columns
            let by_rows: Vec<Vec<f64>> = ang.iter().map(|row| planar(name, row, depth, omega)).collect();
            let cols = by_rows[0].len();
            let mut want = vec![Vec::new(); cols];
            for (c, w) in want.iter_mut().enumerate() {
                let col: Vec<f64> = by_rows.iter().map(|row| row[c]).collect();
                *w = planar(name, &col, depth, omega);
            }
            for o in ORDERS {
                let out = subdivide(s, o, &g, depth).unwrap();
                prop_assert_eq!((out.rows(), out.cols()), (want[0].len(), want.len()));
                for (c, col) in want.iter().enumerate() {
                    for (rr, &w) in col.iter().enumerate() {
                        let (a, off) = circle_angle(r, out.get(rr, c), w);
                        prop_assert!(off < 1e-12 && (a - w).abs() < 1e-11, "{} {}: ({rr},{c}) {a} vs planar {w}", s.name(), o.name());
                    }
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// The vector path (AVX2 where the CPU has it) gives the scalar rules'
    /// bits: a step of the windowed path against the curve-by-curve step
    /// (`FourPointRule::refine`, scalar), on nets from nearly equal to
    /// antipodal neighbours, including nasty rows spliced in.
    #[test]
    fn vector_step_is_bitwise_the_scalar_step(
        g in net(4..=14, 4..=21, 3.1),
        spread in prop_oneof![Just(1e-7), Just(1e-4), Just(1e-2), Just(0.3), Just(1.0)],
        nasty_row in nasty(6..=6),
        omega in 0.0f64..2.4,
    ) {
        // shrink the angles between neighbours so every term band is drawn
        let c = g.data()[0];
        let mut data: Vec<DVec3> = g.data().iter().map(|&v| (c + (v - c) * spread).normalize()).collect();
        let cols = g.cols();
        // the nasty row's valid tangents (huge, tiny, antipodal pairs), as the
        // kernel's boundary would normalise them
        for (k, v) in nasty_row.iter().enumerate().take(cols) {
            if let Some(u) = v.try_normalize() {
                data[cols + k] = u;
            }
        }
        let g = Grid::new(g.rows(), cols, data).unwrap();
        let scheme = SurfaceScheme::Kobbelt { omega };
        for order in ORDERS {
            let fast = streamline_kernel::levels::surface::refine_grid(scheme, order, &g);
            // the plain way, curve by curve (columns gathered into buffers)
            let c = scheme.curve();
            let plain = match order {
                BlendOrder::SFirst => refine_cols(c, &refine_rows(c, &g)),
                BlendOrder::TFirst => refine_rows(c, &refine_cols(c, &g)),
            };
            prop_assert_eq!(&fast, &plain, "{:?}", order);
        }
    }
}
