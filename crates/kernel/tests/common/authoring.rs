//! Strategies and helpers shared by the authoring property tests
//! (`authoring_*.rs`, docs/math.md §9).

use super::unit;
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::grid::Grid;
use streamline_kernel::{BlendOrder, Design, SurfaceScheme};

pub const SCHEMES: [SurfaceScheme; 3] = [
    SurfaceScheme::Kobbelt { omega: 1.0 },
    SurfaceScheme::CatmullClark,
    SurfaceScheme::DooSabin,
];

pub fn points(d: &Design, depth: u32) -> Grid<DVec3> {
    let level = d.level(depth).unwrap();
    d.streamlines(&level)
}

/// `σ` of row `r` (docs/math.md §4, "The anchor"): `s` of the anchor
/// column, or at a first or last column of an approximating scheme the
/// limit mask there (Chaikin's ½ ½, the cubic B-spline's ⅙ ⅔ ⅙).
pub fn anchor_s(d: &Design, r: usize) -> f64 {
    let (s, a) = (d.params().s.row(r), d.anchor());
    let n = s.len();
    // a row too short for the mask keeps its ends
    match (d.scheme(), a == 0, a + 1 == n) {
        (SurfaceScheme::CatmullClark, true, _) if n >= 3 => (s[0] + 4.0 * s[1] + s[2]) / 6.0,
        (SurfaceScheme::CatmullClark, _, true) if n >= 3 => {
            (s[n - 3] + 4.0 * s[n - 2] + s[n - 1]) / 6.0
        }
        (SurfaceScheme::DooSabin, true, _) if n >= 2 => 0.5 * (s[0] + s[1]),
        (SurfaceScheme::DooSabin, _, true) if n >= 2 => 0.5 * (s[n - 2] + s[n - 1]),
        _ => s[a],
    }
}

/// A random design: a gently turning net with uneven positive intervals.
pub fn design() -> impl Strategy<Value = Design> {
    (
        2usize..7,
        3usize..8,
        0usize..3,
        prop::collection::vec((unit(), 0.3f64..1.0), 49),
        0usize..8,
        (unit(), 0.5f64..3.0, 0.0f64..0.8),
    )
        .prop_map(|(rows, cols, which, raw, anchor, (c0, len, bend))| {
            let scheme = SCHEMES[which];
            let rows = rows.max(scheme.curve().min_len());
            let net = (0..rows * cols)
                .map(|i| (DVec3::X * 2.0 + raw[i % 49].0 * 0.6).normalize())
                .collect();
            let s = (0..rows * cols)
                .map(|i| {
                    let (r, c) = (i / cols, i % cols);
                    (0..c).map(|k| raw[(r * 7 + k) % 49].1).sum::<f64>() + 0.1 * r as f64
                })
                .collect();
            let t = (0..rows).map(|r| 0.4 * r as f64).collect();
            let start = (DVec3::Y * 2.0 + c0 * 0.5).normalize();
            let turn = DQuat::from_axis_angle(DVec3::X, bend);
            let initial = streamline_kernel::streamline::initial_curve::InitialCurve::new(
                &[start, turn * start, turn * turn * start],
                3,
                len,
                DVec3::new(0.1, -0.2, 0.3),
            )
            .unwrap();
            Design::new(
                &Grid::new(rows, cols, net).unwrap(),
                Grid::new(rows, cols, s).unwrap(),
                t,
                anchor % cols,
                scheme,
                BlendOrder::SFirst,
                initial,
            )
            .unwrap()
        })
        .prop_filter("refines to depth 3", |d| d.level(3).is_ok())
}

pub fn same_bits(a: &Design, b: &Design) -> bool {
    let bits = |d: &Design| {
        (
            d.net()
                .data()
                .iter()
                .map(|v| v.to_array().map(f64::to_bits))
                .collect::<Vec<_>>(),
            d.params()
                .s
                .data()
                .iter()
                .map(|v| v.to_bits())
                .collect::<Vec<_>>(),
            d.params().t.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            d.params()
                .sigma
                .iter()
                .map(|v| v.to_bits())
                .collect::<Vec<_>>(),
            (d.net().rows(), d.net().cols(), d.anchor()),
        )
    };
    bits(a) == bits(b)
}
