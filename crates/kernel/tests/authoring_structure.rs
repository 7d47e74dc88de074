//! `docs/math.md §9`, structure edits: an inside insert is the row of a full subdivision
//! step, an outside insert continues the great circles, inserts move the cars
//! by well under 1 % (an independent point-to-triangle distance), bad values
//! are errors.

mod common;

use common::authoring::*;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::authoring::{Axis, Template};
use streamline_kernel::curve::scheme::CurveScheme;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::presets;
use streamline_kernel::levels::surface::refine_cols;
use streamline_kernel::streamline::surface_mesh::bounds;
use streamline_kernel::{BlendOrder, Design, KernelError, SurfaceScheme};

/// Row `2i − 1` (4-point) or the leg midpoint (approximating schemes) of one
/// across-rows step of the whole net, computed by the plain column refinement.
fn reference_row(
    c: CurveScheme,
    net: &Grid<DVec3>,
    s: &Grid<f64>,
    t: &[f64],
    i: usize,
) -> (Vec<DVec3>, Vec<f64>, f64) {
    let fine = refine_cols(c, net);
    let fine_s = refine_cols(c, s);
    let mut t_fine = Vec::new();
    c.refine_scalars(t, &mut t_fine);
    let t = t_fine;
    match c {
        CurveScheme::FourPoint { .. } => (
            fine.row(2 * i - 1).to_vec(),
            fine_s.row(2 * i - 1).to_vec(),
            t[2 * i - 1],
        ),
        CurveScheme::CubicBSpline => (
            fine.row(2 * (i - 1)).to_vec(),
            fine_s.row(2 * (i - 1)).to_vec(),
            t[2 * (i - 1)],
        ),
        CurveScheme::Chaikin => {
            // the midpoint of the ¼ and ¾ points of the leg
            let (a, b) = (fine.row(2 * (i - 1)), fine.row(2 * (i - 1) + 1));
            let (sa, sb) = (fine_s.row(2 * (i - 1)), fine_s.row(2 * (i - 1) + 1));
            (
                a.iter()
                    .zip(b)
                    .map(|(a, b)| (*a + *b).normalize())
                    .collect(),
                sa.iter().zip(sb).map(|(a, b)| 0.5 * (a + b)).collect(),
                0.5 * (t[2 * (i - 1)] + t[2 * (i - 1) + 1]),
            )
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn insert_inside_takes_the_subdivision_step(d in design(), at in 1usize..7, col in any::<bool>()) {
        let axis = if col { Axis::Column } else { Axis::Row };
        let n = d.count(axis);
        let at = 1 + (at - 1) % (n - 1);
        let e = match d.inserted(axis, at) { Ok(e) => e, Err(KernelError::ParamsNotIncreasing { .. }) => return Ok(()), Err(x) => panic!("{x}") };
        // a column insert is a row insert of the transposed net
        let (tr, tn) = if col {
            let t = vec![0.0; d.net().cols()];
            let (row, s, _) = reference_row(d.scheme().curve(), &d.net().transpose(), &d.params().s.transpose(), &t, at);
            (row, s)
        } else {
            let (row, s, t) = reference_row(d.scheme().curve(), d.net(), &d.params().s, &d.params().t, at);
            prop_assert!((e.params().t[at] - t).abs() <= 1e-12 * (1.0 + t.abs()), "t {} vs {t}", e.params().t[at]);
            (row, s)
        };
        for k in 0..tr.len() {
            let (got, gs) = if col { (e.net().get(k, at), e.params().s.get(k, at)) } else { (e.net().get(at, k), e.params().s.get(at, k)) };
            prop_assert!((got - tr[k]).length() < 1e-13, "tangent {k}: {got:?} vs step {:?}", tr[k]);
            prop_assert!((gs - tn[k]).abs() < 1e-12 * (1.0 + gs.abs()), "s {k}: {gs} vs {}", tn[k]);
        }
        prop_assert_eq!(e.count(axis), n + 1);
        let s_anchor: Vec<f64> = (0..e.net().rows()).map(|r| anchor_s(&e, r)).collect();
        prop_assert_eq!(&e.params().sigma, &s_anchor, "σ is s of the anchor column, or its row's limit end");
        // the anchor stays on the same column
        if col {
            prop_assert_eq!(e.anchor(), d.anchor() + usize::from(d.anchor() >= at));
        }
        // deleting the new line gives back the design bit for bit
        let back = e.deleted(axis, at).unwrap();
        prop_assert!(same_bits(&back, &d), "insert then delete changes the design");
    }

    #[test]
    fn insert_outside_continues_the_great_circles(d in design(), front in any::<bool>(), col in any::<bool>()) {
        let axis = if col { Axis::Column } else { Axis::Row };
        let n = d.count(axis);
        let at = if front { 0 } else { n };
        let e = d.inserted(axis, at).unwrap();
        let get = |g: &Design, line: usize, k: usize| if col { (g.net().get(k, line), g.params().s.get(k, line)) } else { (g.net().get(line, k), g.params().s.get(line, k)) };
        let (near, far) = if front { (0, 1) } else { (n - 1, n - 2) };
        let new = if front { 0 } else { n };
        let shift = usize::from(front);
        let other = d.count(if col { Axis::Row } else { Axis::Column });
        let linear: Vec<f64> = (0..other).map(|k| 2.0 * get(&d, near, k).1 - get(&d, far, k).1).collect();
        let linear_ok = col || linear.windows(2).all(|w| w[1] > w[0]);
        for (k, &lin) in linear.iter().enumerate() {
            let (a, sa) = get(&d, near, k);
            let (b, _) = get(&d, far, k);
            let (x, sx) = get(&e, new, k);
            // same angle again, on the same great circle, beyond `a`
            let ang = |u: DVec3, v: DVec3| u.cross(v).length().atan2(u.dot(v));
            let th = ang(a, b);
            prop_assume!(th < 1.5);
            prop_assert!((ang(x, a) - th).abs() < 1e-12, "step {} vs {th}", ang(x, a));
            prop_assert!((ang(x, b) - 2.0 * th).abs() < 1e-12, "two steps {} vs {}", ang(x, b), 2.0 * th);
            prop_assert!(x.dot(a.cross(b)).abs() < 1e-12, "off the great circle");
            if linear_ok {
                prop_assert!((sx - lin).abs() < 1e-12 * (1.0 + sx.abs()), "s {sx} vs {lin}");
            } else if k > 0 {
                // rows of very different lengths: each interval linear where positive, else the ratio
                let (an, bn) = (sa - get(&d, near, k - 1).1, get(&d, far, k).1 - get(&d, far, k - 1).1);
                let dx = sx - get(&e, new, k - 1).1;
                let want = if 2.0 * an - bn > 0.0 { 2.0 * an - bn } else { an * an / bn };
                prop_assert!(dx > 0.0 && (dx - want).abs() < 1e-12 * (1.0 + sx.abs()), "interval {k}: {dx} vs {want}");
            }
            let (old, _) = get(&e, near + shift, k);
            prop_assert!(old == a, "existing lines keep their bits");
        }
        if !col {
            let (ta, tb) = (d.params().t[near], d.params().t[far]);
            prop_assert!((e.params().t[new] - (2.0 * ta - tb)).abs() < 1e-12 * (1.0 + ta.abs() + tb.abs()));
        }
        prop_assert!(same_bits(&e.deleted(axis, at).unwrap(), &d));
    }
}

#[test]
fn structure_bad_values_are_errors() {
    let d = presets::minimal();
    for axis in [Axis::Row, Axis::Column] {
        let e = d.deleted(axis, 0).unwrap_err();
        assert!(
            matches!(e, KernelError::NetTooSmall { count: 2, .. }),
            "{e:?}"
        );
        assert!(e.to_string().contains("must keep at least 2"), "{e}");
        assert!(matches!(
            d.inserted(axis, 3),
            Err(KernelError::IndexOutOfRange {
                index: 3,
                len: 3,
                ..
            })
        ));
        let d3 = d.inserted(axis, 1).unwrap();
        assert!(matches!(
            d3.deleted(axis, 3),
            Err(KernelError::IndexOutOfRange {
                index: 3,
                len: 3,
                ..
            })
        ));
    }
    let big = Design::from_template(
        64,
        3,
        1.0,
        Template::Flat { width: 1.0 },
        SurfaceScheme::default(),
        BlendOrder::SFirst,
    )
    .unwrap();
    assert!(matches!(
        big.inserted(Axis::Row, 5),
        Err(KernelError::NetTooLarge { rows: 65, .. })
    ));
}

#[test]
fn delete_anchor_column_passes_the_anchor_on() {
    let d = presets::car1().with_anchor(8).unwrap();
    let e = d.deleted(Axis::Column, 8).unwrap();
    assert_eq!(
        e.anchor(),
        7,
        "the last column's anchor goes to the new last"
    );
    let d = presets::car1().with_anchor(4).unwrap();
    assert_eq!(
        d.deleted(Axis::Column, 4).unwrap().anchor(),
        4,
        "the next column takes its place"
    );
    assert_eq!(d.deleted(Axis::Column, 2).unwrap().anchor(), 3);
    assert_eq!(d.deleted(Axis::Column, 6).unwrap().anchor(), 4);
}

// A surface-to-surface distance, computed independently of the kernel's
// subdivision: closest points on triangles (Ericson, Real-Time Collision
// Detection §5.1.5), with the triangles bucketed in a uniform grid.
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Largest distance from the points of `from` to the triangle mesh of `to`
/// (a distance past `reach` is reported as `reach`).
fn one_sided(from: &Grid<DVec3>, to: &Grid<DVec3>, reach: f64) -> f64 {
    use std::collections::HashMap;
    let cell = |p: DVec3| ((p / reach).floor()).as_ivec3();
    let mut buckets: HashMap<glam::IVec3, Vec<[DVec3; 3]>> = HashMap::new();
    for r in 0..to.rows() - 1 {
        for k in 0..to.cols() - 1 {
            let (a, b, c, d) = (
                to.get(r, k),
                to.get(r, k + 1),
                to.get(r + 1, k),
                to.get(r + 1, k + 1),
            );
            for tri in [[a, b, d], [a, d, c]] {
                let [lo, hi] = bounds(tri);
                let (l, h) = (cell(lo), cell(hi));
                for x in l.x..=h.x {
                    for y in l.y..=h.y {
                        for z in l.z..=h.z {
                            buckets
                                .entry(glam::IVec3::new(x, y, z))
                                .or_default()
                                .push(tri);
                        }
                    }
                }
            }
        }
    }
    let mut worst = 0.0_f64;
    for &p in from.data() {
        let c = cell(p);
        let mut best = reach;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(v) = buckets.get(&(c + glam::IVec3::new(dx, dy, dz))) {
                        for t in v {
                            best =
                                best.min((closest_on_triangle(p, t[0], t[1], t[2]) - p).length());
                        }
                    }
                }
            }
        }
        worst = worst.max(best);
    }
    worst
}

#[test]
fn insert_moves_the_cars_by_well_under_one_percent() {
    let depth = 4;
    for (name, d) in [("car1", presets::car1()), ("car2", presets::car2())] {
        let before = points(&d, depth);
        let [lo, hi] = bounds(before.data().iter().copied());
        let diag = (hi - lo).length();
        for axis in [Axis::Row, Axis::Column] {
            let mut worst = (0.0, 0);
            for at in 1..d.count(axis) {
                let after = points(&d.inserted(axis, at).unwrap(), depth);
                let reach = 0.05 * diag;
                let h = one_sided(&after, &before, reach).max(one_sided(&before, &after, reach));
                if h > worst.0 {
                    worst = (h, at);
                }
            }
            let pct = 100.0 * worst.0 / diag;
            eprintln!(
                "{name}: insert {} moves the surface by at most {:.4} ({pct:.3} % of the diagonal {diag:.3}), at {}",
                axis.name(),
                worst.0,
                worst.1
            );
            assert!(
                pct < 0.5,
                "{name}: inserting a {} moves the surface by {pct:.3} % of its diagonal",
                axis.name()
            );
        }
    }
}
