//! docs/math.md §4: streamline integration (Eq. 65), placement, flat strips and circular arcs.

mod common;

use common::*;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::design::Design;
use streamline_kernel::levels::surface::{BlendOrder, SurfaceScheme};
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::streamline::integrate::{point_at, polyline_length, streamline};

fn intervals(n: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Vec<f64>> {
    (-5.0f64..5.0, prop::collection::vec(1e-3f64..3.0, n)).prop_map(|(s0, d)| {
        let mut s = vec![s0];
        for x in d {
            let last = *s.last().unwrap();
            s.push(last + x);
        }
        s
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn streamline_length_equals_s_range(s in intervals(1..=12), seed in walk(13..=13, 2.0), anchor in 0usize..13, origin in unit()) {
        let n = s.len();
        let t = &seed[..n];
        let anchor = anchor % n;
        let p = streamline(t, &s, anchor, origin * 3.0).unwrap();
        prop_assert_eq!(p.len(), n + 1, "n+1 tangents → n+2 points");
        let len = polyline_length(&p);
        let want = s[n - 1] - s[0];
        prop_assert!((len - want).abs() < 1e-12 * want.max(1.0), "length {len} vs s_n − s_0 = {want}");
        let ut: Vec<DVec3> = t.iter().map(|v| v.normalize()).collect();
        let at = point_at(&p, &ut, &s, s[anchor]);
        prop_assert!((at - origin * 3.0).length() < 1e-12, "anchor point {at:?} vs origin");
    }

    #[test]
    fn flat_strip_from_constant_net(x in unit(), rows in 2usize..6, cols in 2usize..7, depth in 0u32..4, which in 0usize..3) {
        // All tangents x, straight initial curve along y: a flat strip, closed form
        // p = origin + t·y + (arclen − σ)·x.
        prop_assume!(x.cross(DVec3::Y).length() > 0.1);
        let scheme = [SurfaceScheme::default(), SurfaceScheme::CatmullClark, SurfaceScheme::DooSabin][which];
        prop_assume!(rows >= scheme.curve().min_len() && cols >= scheme.curve().min_len());
        let net = Grid::filled(rows, cols, x);
        let s = Grid::new(rows, cols, (0..rows * cols).map(|i| (i % cols) as f64 * 0.7 + (i / cols) as f64 * 0.1).collect()).unwrap();
        let t: Vec<f64> = (0..rows).map(|r| r as f64 * 0.5).collect();
        let initial = InitialCurve::new(&[DVec3::Y, DVec3::Y], 2, 3.0, DVec3::ZERO).unwrap();
        let d = Design::new(&net, s, t, 0, scheme, BlendOrder::SFirst, initial).unwrap();
        let level = d.level(depth).unwrap();
        let pts = d.streamlines(&level);
        let normal = x.cross(DVec3::Y).normalize();
        for r in 0..pts.rows() {
            let srow = level.params.s.row(r);
            for k in 0..pts.cols() {
                let arclen = streamline_kernel::streamline::integrate::point_arclength(srow, k);
                let want = DVec3::Y * level.params.t[r] + x * (arclen - level.params.sigma[r]);
                let got = pts.get(r, k);
                prop_assert!((got - want).length() < 1e-11, "row {r} point {k}: {got:?} vs {want:?}");
                prop_assert!(got.dot(normal).abs() < 1e-11, "off the plane");
            }
        }
    }
}

#[test]
fn circular_arc_closed_form() {
    // Tangents turning at constant rate κ over uniform spacing h: Eq. 65's interior
    // vertices are those of a regular polygon with edge h and turning angle κh, so
    // they lie on a circle of radius h / (2 sin(κh/2)) = (1/κ)(1 + (κh)²/24 + …).
    for (kappa, n, h) in [(0.5, 9usize, 0.25), (2.0, 30, 0.05), (0.1, 5, 1.0)] {
        let s: Vec<f64> = (0..n).map(|i| i as f64 * h).collect();
        let t: Vec<DVec3> = s
            .iter()
            .map(|&v| DVec3::new((kappa * v).cos(), (kappa * v).sin(), 0.0))
            .collect();
        let p = streamline(&t, &s, 0, DVec3::ZERO).unwrap();
        let radius = h / (2.0 * (kappa * h / 2.0).sin());
        // centre: from vertex 1 along the inward normal of edge 1 rotated back by half a turn
        let centre = {
            let (a, b, c) = (p[1], p[2], p[3]);
            circumcentre(a, b, c)
        };
        for (k, q) in p.iter().enumerate().take(n).skip(1) {
            let r = (*q - centre).length();
            assert!(
                (r - radius).abs() < 1e-12,
                "κ={kappa} h={h}: vertex {k} at radius {r}, closed form {radius}"
            );
        }
        let rel = (radius * kappa - 1.0).abs();
        assert!(
            rel < (kappa * h).powi(2) / 20.0,
            "second order: radius·κ − 1 = {rel:e}"
        );
    }
}

fn circumcentre(a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac) = (b - a, c - a);
    let n = ab.cross(ac);
    a + (n.cross(ab) * ac.length_squared() + ac.cross(n) * ab.length_squared())
        / (2.0 * n.length_squared())
}

#[test]
fn kobbelt_surface_of_arcs_stays_circular() {
    // Every row turns at the same constant rate in the xz-plane: Kobbelt refinement
    // reproduces the uniform angles (4-point reproduces cubics), so every refined
    // row is still a regular polygon on a circle of radius h'/(2 sin(κh'/2)).
    let (rows, cols, h, kappa) = (4usize, 7usize, 0.5, 0.6);
    let mut net = Vec::new();
    let mut s = Vec::new();
    for _ in 0..rows {
        for c in 0..cols {
            let a = kappa * c as f64 * h;
            net.push(DVec3::new(a.cos(), 0.0, a.sin()));
            s.push(c as f64 * h);
        }
    }
    let initial = InitialCurve::new(&[DVec3::Y, DVec3::Y], 2, 3.0, DVec3::ZERO).unwrap();
    let d = Design::new(
        &Grid::new(rows, cols, net).unwrap(),
        Grid::new(rows, cols, s).unwrap(),
        vec![0.0, 1.0, 2.0, 3.0],
        0,
        SurfaceScheme::default(),
        BlendOrder::SFirst,
        initial,
    )
    .unwrap();
    for depth in 1..=3u32 {
        let level = d.level(depth).unwrap();
        let pts = d.streamlines(&level);
        let hh = h / f64::from(1u32 << depth);
        let radius = hh / (2.0 * (kappa * hh / 2.0).sin());
        for r in 0..pts.rows() {
            let row = pts.row(r);
            let centre = circumcentre(row[1], row[2], row[3]);
            for (k, q) in row.iter().enumerate().take(row.len() - 1).skip(1) {
                let rr = (*q - centre).length();
                assert!(
                    (rr - radius).abs() < 1e-11,
                    "depth {depth} row {r} vertex {k}: radius {rr} vs {radius}"
                );
            }
        }
    }
}

/// A coordinate: ordinary, huge, tiny, signed zeros, infinities or NaN.
fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -1e3f64..1e3,
        1 => prop::sample::select(vec![
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e300,
            -1e300,
            f64::MIN_POSITIVE,
        ]),
    ]
}

proptest! {
    /// The integrate stage's one-pass row box: per coordinate, the fold of
    /// `f64::min` and `f64::max` (a NaN coordinate passed over; the kernel
    /// never makes one), and for points without NaN exactly [`bounds`], the
    /// fold of glam's `min` and `max`; the lengths cover every remainder of
    /// the two-point chunks, and the empty slice.
    #[test]
    fn slice_bounds_is_the_fold_of_min_and_max(
        points in prop::collection::vec(
            (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| DVec3::new(x, y, z)),
            0..=23,
        ),
    ) {
        use streamline_kernel::streamline::surface_mesh::{bounds, slice_bounds};
        let got = slice_bounds(&points);
        let mut want = [DVec3::INFINITY, DVec3::NEG_INFINITY];
        for p in &points {
            for k in 0..3 {
                want[0][k] = want[0][k].min(p[k]);
                want[1][k] = want[1][k].max(p[k]);
            }
        }
        // equal (a zero bound may have either sign)
        prop_assert!(got == want, "{points:?}: {got:?} vs {want:?}");
        if points.iter().all(|p| !p.is_nan()) {
            prop_assert!(got == bounds(points.iter().copied()), "{points:?}");
        }
    }
}

/// One row for `place_slices_from`: tangents before and after an edit from
/// `from` on, `s`, σ and the origin.
#[derive(Debug, Clone)]
struct EditedRow {
    old: Vec<DVec3>,
    new: Vec<DVec3>,
    s: Vec<f64>,
    sigma: f64,
    origin: DVec3,
    from: usize,
}

/// Rows of two lengths, edited from one of a few columns (so that rows
/// share a start and a length, in fours and not), `s` at three scales, the
/// anchor σ mostly near the start (only an anchor before the edit lets a
/// row be summed on from a point) and now and then anywhere.
fn edited_rows() -> impl Strategy<Value = Vec<EditedRow>> {
    let row = (
        prop::sample::select(vec![3usize, 17]),
        prop::sample::select(vec![0usize, 1, 2, 5, 9, 30]),
        prop::sample::select(vec![1e-6, 1.0, 1e6]),
        prop_oneof![
            3 => prop::sample::select(vec![-0.2, 0.0, 0.01, 0.04]),
            1 => -0.2f64..1.2,
        ],
        unit(),
        prop::collection::vec((unit(), unit()), 18),
        intervals(17..=17),
    )
        .prop_map(|(n, from, scale, at, origin, tangents, s)| {
            let s: Vec<f64> = s[..=n].iter().map(|x| x * scale).collect();
            let old: Vec<DVec3> = tangents[..=n].iter().map(|t| t.0).collect();
            let new: Vec<DVec3> = (0..=n)
                .map(|i| if i >= from { tangents[i].1 } else { old[i] })
                .collect();
            let sigma = s[0] + at * (s[n] - s[0]);
            EditedRow {
                old,
                new,
                s,
                sigma,
                origin: origin * scale,
                from,
            }
        });
    prop::collection::vec(row, 1..=21)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Rows placed together (`place_slices_from`, four at a time where they
    /// share a start and a length) are each what `place_slice_from` makes
    /// of the row alone, bit for bit, and say the same first moved point.
    #[test]
    fn rows_placed_together_are_each_row_placed_alone(rows in edited_rows()) {
        use streamline_kernel::streamline::integrate::{
            SliceJob, place_slice, place_slice_from, place_slices_from,
        };
        let before: Vec<Vec<DVec3>> = rows
            .iter()
            .map(|r| {
                let mut out = vec![DVec3::ZERO; r.old.len() + 1];
                place_slice(&r.old, &r.s, r.sigma, r.origin, &mut out);
                out
            })
            .collect();
        let mut alone = before.clone();
        let moved: Vec<usize> = rows
            .iter()
            .zip(&mut alone)
            .map(|(r, out)| place_slice_from(&r.new, &r.s, r.sigma, r.origin, r.from, out))
            .collect();
        let mut together = before.clone();
        let mut jobs: Vec<SliceJob> = rows
            .iter()
            .zip(&mut together)
            .map(|(r, out)| SliceJob {
                tangents: &r.new,
                s: &r.s,
                sigma: r.sigma,
                origin: r.origin,
                from: r.from,
                out,
                moved_from: usize::MAX,
                bounds: [DVec3::ZERO; 2],
            })
            .collect();
        place_slices_from(&mut jobs);
        let got: Vec<usize> = jobs.iter().map(|j| j.moved_from).collect();
        prop_assert_eq!(got, moved);
        let bits = |v: &[DVec3]| -> Vec<[u64; 3]> {
            v.iter().map(|p| p.to_array().map(f64::to_bits)).collect()
        };
        for (k, (a, b)) in together.iter().zip(&alone).enumerate() {
            prop_assert_eq!(bits(a), bits(b), "row {}", k);
        }
    }
}
