//! `docs/math.md §9`: templates, structure edits, the initial curve and
//! streamline lengths as handles, mirror symmetry. Every claim is checked
//! against an independent computation: closed forms (rectangle, cylinder,
//! great circles), the full subdivision step, a point-to-triangle distance.

mod common;

use common::*;
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::authoring::{Axis, MAX_NET_SIDE, Template};
use streamline_kernel::curve::scheme::CurveScheme;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::presets;
use streamline_kernel::levels::surface::refine_cols;
use streamline_kernel::streamline::integrate::polyline_length;
use streamline_kernel::streamline::surface_mesh::bounds;
use streamline_kernel::{BlendOrder, Design, KernelError, SurfaceScheme};

const SCHEMES: [SurfaceScheme; 3] = [
    SurfaceScheme::Kobbelt { omega: 1.0 },
    SurfaceScheme::CatmullClark,
    SurfaceScheme::DooSabin,
];

fn points(d: &Design, depth: u32) -> Grid<DVec3> {
    let level = d.level(depth).unwrap();
    d.streamlines(&level)
}

/// A random design: a gently turning net with uneven positive intervals.
fn design() -> impl Strategy<Value = Design> {
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

fn same_bits(a: &Design, b: &Design) -> bool {
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

// ---------------------------------------------------------------- templates

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn template_flat_is_the_rectangle(rows in 2usize..12, cols in 2usize..12, len in 0.01f64..50.0, width in 0.01f64..50.0, which in 0usize..3, depth in 0u32..4) {
        let scheme = SCHEMES[which];
        prop_assume!(rows.min(cols) >= scheme.curve().min_len() || depth == 0);
        let d = Design::from_template(rows, cols, len, Template::Flat { width }, scheme, BlendOrder::SFirst).unwrap();
        let p = points(&d, depth);
        let tol = 1e-12 * len.max(width);
        for v in p.data() {
            prop_assert!(v.z == 0.0, "z = {} at {v:?}", v.z);
            prop_assert!(v.x >= -tol && v.x <= len + tol && v.y >= -tol && v.y <= width + tol, "{v:?} outside [0,{len}]x[0,{width}]");
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

// ---------------------------------------------------------------- structure

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
        let s_anchor: Vec<f64> = (0..e.net().rows()).map(|r| e.params().s.get(r, e.anchor())).collect();
        prop_assert_eq!(&e.params().sigma, &s_anchor, "σ is s of the anchor column");
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

// ---------------------------------------------------------------- the initial curve, the anchor, lengths

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

// ---------------------------------------------------------------- mirror

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn mirror_mesh_equals_its_reflection(d in design(), depth in 0u32..4) {
        let m = d.mirrored().unwrap();
        let plane = d.mirror_plane();
        prop_assert!((plane.normal - d.initial().tangent(d.params().t[0])).length() < 1e-15);
        let p = points(&m, depth);
        let [lo, hi] = bounds(p.data().iter().copied());
        let tol = 1e-11 * (1.0 + (hi - lo).length());
        let n = p.rows();
        for r in 0..n {
            for k in 0..p.cols() {
                let e = (plane.reflect_point(p.get(r, k)) - p.get(n - 1 - r, k)).length();
                prop_assert!(e < tol, "row {r} point {k}: reflection off by {e:e}");
            }
        }
        // the half's rows are the design's rows (row m − 1 + r)
        let rows = d.net().rows();
        for r in 1..rows {
            prop_assert!(m.net().row(rows - 1 + r) == d.net().row(r));
        }
        // Kobbelt keeps the seam row: it lies in the plane at every depth
        if d.scheme().is_interpolatory() {
            let seam = (n - 1) / 2;
            for k in 0..p.cols() {
                prop_assert!(plane.distance(p.get(seam, k)).abs() < tol, "seam point {k} off the plane by {:e}", plane.distance(p.get(seam, k)));
            }
        }
    }

    #[test]
    fn mirror_toggle_restores_exactly(d in design()) {
        let a = d.mirrored().unwrap();
        let on = d.with_seam_in_plane().unwrap();
        prop_assert!(same_bits(&on.with_seam_in_plane().unwrap(), &on), "projecting twice changes the seam");
        let b = on.mirrored().unwrap();
        prop_assert!(same_bits(&a, &b), "mirroring the projected half differs from mirroring the half");
        prop_assert!(same_bits(&d.mirrored().unwrap(), &a), "mirroring is a pure function");
        let seam = on.mirror_plane();
        for &v in on.net().row(0) {
            prop_assert!(v.dot(seam.normal).abs() < 1e-14, "seam tangent off the plane: {:e}", v.dot(seam.normal));
        }
    }
}

/// Angle between the unit normals of two triangles.
fn face_normal(a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    (b - a).cross(c - a).normalize()
}

#[test]
fn mirror_seam_is_smooth_like_the_rest() {
    // At the seam, the crease between a face and its mirror image is twice
    // the angle between the face's normal and the plane. For a G1 (and G2)
    // seam it shrinks with depth like the angle between the neighbouring faces
    // next to it on the same half, and stays comparable to it.
    // half of car 1: its rows 3–5, from the centre line out, mirrored about
    // the plane across the initial curve at row 3
    let mut d = presets::car1();
    for _ in 0..3 {
        d = d.deleted(Axis::Row, 0).unwrap();
    }
    let plane = d.mirror_plane();
    let m = d.mirrored().unwrap();
    let mut prev: Option<(f64, f64)> = None;
    for depth in 1..=6 {
        let p = points(&m, depth);
        let seam = (p.rows() - 1) / 2;
        let quad = |r: usize, k: usize| face_normal(p.get(r, k), p.get(r, k + 1), p.get(r + 1, k));
        let (mut crease, mut neighbour) = (0.0_f64, 0.0_f64);
        for k in 1..p.cols() - 2 {
            let (a, b) = (quad(seam, k), quad(seam + 1, k));
            crease = crease.max(2.0 * a.dot(plane.normal).abs().asin());
            neighbour = neighbour.max(a.cross(b).length().atan2(a.dot(b)));
        }
        let ratio = crease / neighbour;
        eprintln!(
            "depth {depth}: crease at the seam {crease:.3e} rad, between the next faces {neighbour:.3e} rad, ratio {ratio:.3}"
        );
        assert!(
            (0.5..=2.0).contains(&ratio),
            "depth {depth}: the seam's crease {crease:e} is not like its neighbours' {neighbour:e}"
        );
        if let Some((c0, n0)) = prev {
            assert!(
                crease < 0.75 * c0,
                "depth {depth}: crease {crease:e} did not shrink from {c0:e}"
            );
            assert!(
                neighbour < 0.75 * n0,
                "depth {depth}: face angle {neighbour:e} did not shrink from {n0:e}"
            );
        }
        prev = Some((crease, neighbour));
    }
}

#[test]
fn mirror_seam_tangent_along_the_normal_is_an_error() {
    let mut d = presets::car1();
    let n = d.mirror_plane().normal;
    d.set_tangent(0, 3, n).unwrap();
    let e = d.mirrored().unwrap_err();
    assert_eq!(e, KernelError::SeamTangentAlongNormal { col: 3 });
    assert!(
        e.to_string()
            .contains("turn it away from the initial curve's first tangent"),
        "{e}"
    );
    assert!(d.with_seam_in_plane().is_err());
}

#[test]
fn mirror_initial_curve_is_reflected_below_t0() {
    let d = presets::car1();
    let m = d.mirrored().unwrap();
    let plane = d.mirror_plane();
    for j in 1..=10 {
        let t = 0.2 * j as f64;
        let a = m.initial().point(-t);
        let b = plane.reflect_point(d.initial().point(t));
        assert!((a - b).length() < 1e-14, "C(−{t}) = R C({t})");
        assert_eq!(m.initial().point(t), d.initial().point(t));
    }
    // C¹ across t₀ = 0: the one-sided tangents agree
    let (l, r) = (m.initial().tangent(-1e-9), m.initial().tangent(0.0));
    assert!((l - r).length() < 1e-8, "{l:?} vs {r:?}");
}
