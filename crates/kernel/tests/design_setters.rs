//! `Design`'s setters keep its invariants (docs/architecture.md, "The
//! kernel's modules and public API"): random edits with nasty values (NaN, ±∞, zero and subnormal
//! vectors, coordinates past the cap, non-increasing parameters, wrong
//! shapes, out-of-range indices and scheme parameters) either succeed and
//! leave a design that holds every invariant [`Design::new`] checks, or fail
//! and leave the design exactly as it was.

mod common;

use common::unit;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::presets;
use streamline_kernel::limits::MAX_COORDINATE;
use streamline_kernel::{BlendOrder, Design, SurfaceScheme};

#[derive(Debug, Clone)]
enum Op {
    Tangent {
        r: usize,
        c: usize,
        v: DVec3,
    },
    Net {
        extra: (usize, usize),
        v: Vec<DVec3>,
    },
    S {
        r: usize,
        k: Vec<f64>,
        bad: Option<(usize, f64)>,
        len: i8,
    },
    Scheme(SurfaceScheme),
    Order(BlendOrder),
}

/// A vector: unit, scaled far up or down, or not a direction at all.
fn vector() -> impl Strategy<Value = DVec3> {
    (
        unit(),
        prop::sample::select(vec![
            1.0,
            3.0,
            1e-300,
            1e-310,
            1e300,
            0.0,
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
        ]),
    )
        .prop_map(|(u, k)| u * k)
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        (0usize..9, 0usize..11, vector()).prop_map(|(r, c, v)| Op::Tangent { r, c, v }),
        (
            prop::sample::select(vec![(0, 0), (0, 0), (0, 0), (1, 0), (0, 1)]),
            prop::collection::vec(vector(), 100)
        )
            .prop_map(|(extra, v)| Op::Net { extra, v }),
        (
            0usize..9,
            prop::collection::vec(0.01f64..3.0, 12),
            prop::option::of((
                0usize..12,
                prop::sample::select(vec![
                    f64::NAN,
                    f64::INFINITY,
                    -1.0,
                    0.0,
                    2.0 * MAX_COORDINATE
                ])
            )),
            -1i8..=1
        )
            .prop_map(|(r, k, bad, len)| Op::S { r, k, bad, len }),
        prop::sample::select(vec![
            SurfaceScheme::Kobbelt { omega: 1.0 },
            SurfaceScheme::Kobbelt { omega: 0.0 },
            SurfaceScheme::Kobbelt { omega: 2.4 },
            SurfaceScheme::Kobbelt { omega: -0.5 },
            SurfaceScheme::Kobbelt { omega: f64::NAN },
            SurfaceScheme::CatmullClark,
            SurfaceScheme::DooSabin,
        ])
        .prop_map(Op::Scheme),
        prop::sample::select(vec![BlendOrder::SFirst, BlendOrder::TFirst]).prop_map(Op::Order),
    ]
}

/// Applies `op`; `Ok(true)` when the design accepted it.
fn apply(d: &mut Design, op: &Op) -> bool {
    let (rows, cols) = (d.net().rows(), d.net().cols());
    match op {
        Op::Tangent { r, c, v } => d.set_tangent(*r, *c, *v).is_ok(),
        Op::Net { extra, v } => {
            let (nr, nc) = (rows + extra.0, cols + extra.1);
            let net = Grid::new(nr, nc, v.iter().cycle().take(nr * nc).copied().collect())
                .expect("sizes agree");
            d.set_net(&net).is_ok()
        }
        Op::S { r, k, bad, len } => {
            // each interval scaled by k[i] (positive), then maybe one bad value
            let row = d.params().s.row(r % rows).to_vec();
            let mut s = row.clone();
            for i in 1..s.len() {
                s[i] = s[i - 1] + (row[i] - row[i - 1]) * k[i % k.len()];
            }
            if let Some((i, x)) = bad {
                let i = i % s.len();
                s[i] = if *x == 0.0 {
                    s[i.saturating_sub(1)]
                } else {
                    *x
                };
            }
            match len {
                -1 => {
                    s.pop();
                }
                1 => s.push(s[s.len() - 1] + 1.0),
                _ => {}
            }
            // an out-of-range row now and then
            let r = if *len == 1 && bad.is_none() {
                rows
            } else {
                r % rows
            };
            d.set_s_row(r, &s).is_ok()
        }
        Op::Scheme(s) => d.set_scheme(*s).is_ok(),
        Op::Order(o) => {
            d.set_order(*o);
            true
        }
    }
}

/// Every invariant `Design::new` establishes.
fn check_invariants(d: &Design) -> Result<(), TestCaseError> {
    let (rows, cols) = (d.net().rows(), d.net().cols());
    for v in d.net().data() {
        prop_assert!(v.is_finite() && (v.length() - 1.0).abs() < 1e-15, "{v}");
    }
    let p = d.params();
    prop_assert_eq!((p.s.rows(), p.s.cols()), (rows, cols));
    prop_assert_eq!(p.t.len(), rows);
    prop_assert_eq!(p.sigma.len(), rows);
    prop_assert!(d.anchor() < cols);
    for r in 0..rows {
        let s = p.s.row(r);
        prop_assert!(s.iter().all(|x| x.is_finite() && x.abs() <= MAX_COORDINATE));
        prop_assert!(s.windows(2).all(|w| w[1] > w[0]), "row {r}: {s:?}");
        prop_assert_eq!(
            p.sigma[r].to_bits(),
            common::authoring::anchor_s(d, r).to_bits()
        );
    }
    prop_assert!(d.scheme().validate().is_ok());
    // and it builds, or says why, with finite output
    if let Ok(b) = d.build(2) {
        prop_assert!(b.points.data().iter().all(|p| p.is_finite()));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn setters_keep_the_invariants_or_change_nothing(
        base in prop::sample::select(vec!["car1", "minimal", "wavy"]),
        ops in prop::collection::vec(op(), 1..12),
    ) {
        let mut d = match base {
            "car1" => presets::car1(),
            "minimal" => presets::minimal(),
            _ => presets::wavy(5, 7),
        };
        let (mut taken, mut refused) = (0, 0);
        for op in &ops {
            let before = format!("{d:?}");
            if apply(&mut d, op) {
                taken += 1;
                check_invariants(&d)?;
                if let Op::Tangent { r, c, v } = op {
                    // scaled first: |v|² of 1e-300 or 1e300 under- or overflows
                    let want = (*v / v.abs().max_element()).normalize();
                    prop_assert!((d.net().get(*r, *c) - want).length() < 1e-15);
                }
            } else {
                refused += 1;
                // Debug prints every f64 exactly (shortest round trip), so
                // equal text is an unchanged design, bit for bit
                prop_assert_eq!(&format!("{d:?}"), &before, "a refused {:?} changed the design", op);
            }
        }
        prop_assert_eq!(taken + refused, ops.len());
    }
}

/// The setters do refuse what they must (a test of the test above).
#[test]
fn setters_refuse_what_breaks_an_invariant() {
    let mut d = presets::car1();
    let before = format!("{d:?}");
    assert!(d.set_tangent(0, 0, DVec3::NAN).is_err());
    assert!(d.set_tangent(0, 0, DVec3::ZERO).is_err());
    assert!(d.set_tangent(99, 0, DVec3::X).is_err());
    let (rows, cols) = (d.net().rows(), d.net().cols());
    assert!(d.set_net(&Grid::filled(rows + 1, cols, DVec3::X)).is_err());
    assert!(d.set_net(&Grid::filled(rows, cols, DVec3::ZERO)).is_err());
    let mut s = d.params().s.row(1).to_vec();
    s[3] = s[2];
    assert!(d.set_s_row(1, &s).is_err(), "not increasing");
    s[3] = f64::NAN;
    assert!(d.set_s_row(1, &s).is_err(), "NaN");
    assert!(d.set_s_row(1, &s[1..]).is_err(), "too short");
    let row0 = d.params().s.row(0).to_vec();
    assert!(d.set_s_row(rows, &row0).is_err(), "no such row");
    assert!(d.set_scheme(SurfaceScheme::Kobbelt { omega: 2.5 }).is_err());
    assert_eq!(format!("{d:?}"), before);
    // and accept what keeps them
    let mut s = d.params().s.row(1).to_vec();
    s.iter_mut().for_each(|x| *x *= 2.0);
    d.set_s_row(1, &s).unwrap();
    assert_eq!(d.params().s.row(1), &s[..]);
    assert_eq!(d.params().sigma[1], s[d.anchor()]);
    d.set_net(&Grid::filled(rows, cols, DVec3::new(3.0, 0.0, 0.0)))
        .unwrap();
    assert!(d.net().data().iter().all(|&v| v == DVec3::X));
}
