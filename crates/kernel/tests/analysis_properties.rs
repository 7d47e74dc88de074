//! Curvature analysis against closed forms: circles and helices for the
//! streamline curvature and comb; spheres, cylinders, planes and Monge patches
//! `z = f(x, y)` for the Gaussian and mean curvature of a point grid.

use proptest::prelude::*;
use std::f64::consts::PI;
use streamline_kernel::analysis::*;
use streamline_kernel::{DQuat, DVec3, Grid};

fn rotation() -> impl Strategy<Value = DQuat> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, 0.0..(2.0 * PI)).prop_map(|(x, y, z, a)| {
        let axis = DVec3::new(x, y, z).try_normalize().unwrap_or(DVec3::Z);
        DQuat::from_axis_angle(axis, a)
    })
}

/// Increasing arc lengths with random (also very uneven) steps.
fn arc_lengths(n: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(1e-3..1.0f64, n).prop_map(|steps| {
        let mut s = vec![0.0];
        for d in steps {
            s.push(s.last().unwrap() + d);
        }
        s
    })
}

/// Tolerance at grid index `(j, i)`: second-order stencils are exact to
/// `O(h²)` everywhere, but the one-sided ones at the border carry larger
/// constants (measured on these grids: ≤ 1e-2 relative at the border, ≤ 2e-3 inside).
fn tol(j: usize, i: usize, rows: usize, cols: usize) -> f64 {
    let border = j == 0 || i == 0 || j + 1 == rows || i + 1 == cols;
    if border { 1.5e-2 } else { 3e-3 }
}

/// A smooth, non-uniform parameter sequence in `[a, b]` with `n` samples.
fn warped(a: f64, b: f64, n: usize, warp: f64) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let x = i as f64 / (n - 1) as f64;
            let y = x + warp * (PI * x).sin() / PI; // monotone for |warp| < 1
            a + (b - a) * y
        })
        .collect()
}

proptest! {
    /// Tangents of a circle of radius R at any arc lengths: κ = 1/R exactly.
    #[test]
    fn circle_curvature_is_one_over_r(
        r in 1e-3..1e3f64,
        s in arc_lengths(12),
        q in rotation(),
    ) {
        // keep the turn per step below π so that the angle is the turn
        let s: Vec<f64> = s.iter().map(|v| v * r * 0.2).collect();
        let t: Vec<DVec3> = s
            .iter()
            .map(|&v| q * DVec3::new(-(v / r).sin(), (v / r).cos(), 0.0))
            .collect();
        for k in streamline_curvature(&t, &s) {
            prop_assert!((k * r - 1.0).abs() < 1e-9, "κR = {}", k * r);
        }
    }

    /// The comb's teeth stand outside the circle: |tip − centre| = R + scale/R.
    #[test]
    fn circle_comb_points_outward(r in 0.1..10.0f64, scale in 0.01..1.0f64, q in rotation()) {
        let n = 24;
        let s: Vec<f64> = (0..n).map(|i| i as f64 * 0.1 * r).collect();
        let t: Vec<DVec3> = s.iter().map(|&v| q * DVec3::new(-(v / r).sin(), (v / r).cos(), 0.0)).collect();
        // the exact circle's points at the chord joints: use points on the circle
        let pts: Vec<DVec3> = (0..=n).map(|i| {
            let v = if i == 0 { s[0] } else if i == n { s[n - 1] } else { 0.5 * (s[i - 1] + s[i]) };
            q * DVec3::new((v / r).cos() * r, (v / r).sin() * r, 0.0)
        }).collect();
        for tooth in comb(&pts, &t, &s, scale) {
            let d = tooth.tip.length();
            prop_assert!((d - (tooth.base.length() + scale * tooth.kappa)).abs() < 1e-6 * (1.0 + d));
            prop_assert!(tooth.kappa > 0.0);
        }
    }

    /// A helix of radius a and pitch 2πc has κ = a/(a² + c²); the discrete
    /// turning speed converges to it as O(Δs²).
    #[test]
    fn helix_curvature_converges(a in 0.2..3.0f64, c in -2.0..2.0f64, q in rotation()) {
        let w = (a * a + c * c).sqrt();
        let exact = a / (w * w);
        let ds = 1e-3 * w;
        let s: Vec<f64> = (0..50).map(|i| i as f64 * ds).collect();
        let t: Vec<DVec3> = s.iter().map(|&v| {
            let u = v / w;
            q * DVec3::new(-a * u.sin(), a * u.cos(), c) / w
        }).collect();
        for k in streamline_curvature(&t, &s) {
            prop_assert!((k - exact).abs() < 1e-6 * exact.max(1.0), "{k} vs {exact}");
        }
    }

    /// Straight streamlines (any spacing) have zero curvature.
    #[test]
    fn straight_line_is_flat(s in arc_lengths(8), q in rotation()) {
        let t = vec![q * DVec3::X; s.len()];
        prop_assert!(streamline_curvature(&t, &s).iter().all(|&k| k == 0.0));
    }

    /// A sphere of radius R on a warped (θ, φ) grid: K = 1/R², |H| = 1/R.
    #[test]
    fn sphere_curvature(
        r in 0.05..50.0f64,
        warp_u in -0.5..0.5f64,
        warp_v in -0.5..0.5f64,
        q in rotation(),
        shift in prop::array::uniform3(-10.0..10.0f64),
    ) {
        let (rows, cols) = (61, 71);
        let th = warped(0.6, 2.4, rows, warp_v); // polar angle: across streamlines
        let ph = warped(-1.2, 1.3, cols, warp_u); // azimuth: along
        let shift = DVec3::from_array(shift);
        let mut data = Vec::new();
        for &t in &th {
            for &p in &ph {
                data.push(shift + q * (r * DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())));
            }
        }
        let c = surface_curvature(&Grid::new(rows, cols, data).unwrap());
        for (at, (&k, &h)) in c.gaussian.iter().zip(&c.mean).enumerate() {
            let e = tol(at / cols, at % cols, rows, cols);
            prop_assert!((k * r * r - 1.0).abs() < e, "KR² = {} at {at}", k * r * r);
            prop_assert!((h.abs() * r - 1.0).abs() < e, "|H|R = {} at {at}", h.abs() * r);
        }
    }

    /// A cylinder of radius R: K = 0, |H| = 1/(2R), streamlines along or across its axis.
    #[test]
    fn cylinder_curvature(r in 0.05..50.0f64, along_axis in any::<bool>(), warp in -0.5..0.5f64, q in rotation()) {
        let (rows, cols) = (61, 51);
        let ang = warped(0.0, 2.0, rows, warp);
        let z = warped(-1.0, 2.0, cols, -warp);
        let mut data = Vec::new();
        for &a in &ang {
            for &h in &z {
                let p = DVec3::new(r * a.cos(), r * a.sin(), h * r);
                data.push(q * p);
            }
        }
        let mut g = Grid::new(rows, cols, data).unwrap();
        if along_axis { g = g.transpose(); }
        let (rows, cols) = (g.rows(), g.cols());
        let c = surface_curvature(&g);
        for (at, (&k, &h)) in c.gaussian.iter().zip(&c.mean).enumerate() {
            let e = tol(at / cols, at % cols, rows, cols);
            prop_assert!((k * r * r).abs() < e, "KR² = {}", k * r * r);
            prop_assert!((h.abs() * 2.0 * r - 1.0).abs() < e, "2|H|R = {}", 2.0 * h.abs() * r);
        }
    }

    /// A plane on any smooth grid: K = H = 0.
    #[test]
    fn plane_is_flat(warp in -0.5..0.5f64, q in rotation(), scale in 1e-6..1e6f64) {
        let (rows, cols) = (9, 13);
        let u = warped(0.0, 1.0, cols, warp);
        let v = warped(0.0, 2.0, rows, -warp);
        let mut data = Vec::new();
        for &b in &v {
            for &a in &u {
                data.push(q * DVec3::new(a + 0.3 * b, b + b * b, 0.0) * scale);
            }
        }
        let c = surface_curvature(&Grid::new(rows, cols, data).unwrap());
        for (&k, &h) in c.gaussian.iter().zip(&c.mean) {
            prop_assert!((k * scale * scale).abs() < 1e-8 && (h * scale).abs() < 1e-8, "K {k} H {h}");
        }
    }

    /// A Monge patch z = f(x, y) with a random quadratic f: the closed forms
    /// K = (f_xx f_yy − f_xy²)/W⁴, H = ((1+f_x²) f_yy − 2 f_x f_y f_xy + (1+f_y²) f_xx)/(2W³),
    /// W² = 1 + f_x² + f_y², with the normal (−f_x, −f_y, 1) = P_x × P_y (sign of H included).
    #[test]
    fn monge_patch_matches_closed_form(
        a in -2.0..2.0f64, b in -2.0..2.0f64, cc in -2.0..2.0f64,
        d in -1.0..1.0f64, e in -1.0..1.0f64,
    ) {
        let f = |x: f64, y: f64| a * x * x + b * x * y + cc * y * y + d * x + e * y;
        let (rows, cols) = (81, 81);
        let xs = warped(-0.5, 0.5, cols, 0.3);
        let ys = warped(-0.5, 0.5, rows, -0.2);
        let mut data = Vec::new();
        for &y in &ys {
            for &x in &xs {
                data.push(DVec3::new(x, y, f(x, y)));
            }
        }
        let c = surface_curvature(&Grid::new(rows, cols, data).unwrap());
        let (fxx, fxy, fyy) = (2.0 * a, b, 2.0 * cc);
        for (j, &y) in ys.iter().enumerate() {
            for (i, &x) in xs.iter().enumerate() {
                let (fx, fy) = (2.0 * a * x + b * y + d, b * x + 2.0 * cc * y + e);
                let w2 = 1.0 + fx * fx + fy * fy;
                let k = (fxx * fyy - fxy * fxy) / (w2 * w2);
                let h = ((1.0 + fx * fx) * fyy - 2.0 * fx * fy * fxy + (1.0 + fy * fy) * fxx) / (2.0 * w2.powf(1.5));
                let at = j * cols + i;
                let e = tol(j, i, rows, cols);
                prop_assert!((c.gaussian[at] - k).abs() < e * (1.0 + k.abs()), "K {} vs {k} at ({i},{j})", c.gaussian[at]);
                prop_assert!((c.mean[at] - h).abs() < e * (1.0 + h.abs()), "H {} vs {h} at ({i},{j})", c.mean[at]);
            }
        }
    }

    /// Nasty grids (huge, tiny, repeated points): every value is finite.
    #[test]
    fn nasty_grids_give_finite_curvature(
        pts in prop::collection::vec(prop::array::uniform3(prop_oneof![
            Just(0.0), Just(1e-300), Just(-1e300), Just(1e300), -1.0..1.0f64,
        ]), 12),
    ) {
        let data: Vec<DVec3> = pts.iter().map(|p| DVec3::from_array(*p)).collect();
        let c = surface_curvature(&Grid::new(3, 4, data.clone()).unwrap());
        prop_assert!(c.gaussian.iter().chain(&c.mean).all(|v| v.is_finite()));
        let t: Vec<DVec3> = data.iter().map(|v| v.try_normalize().unwrap_or(DVec3::X)).collect();
        let s: Vec<f64> = (0..t.len()).map(|i| i as f64 * 1e-300).collect();
        prop_assert!(streamline_curvature(&t, &s).iter().all(|v| v.is_finite()));
        for n in &t {
            let z = zebra_coordinate(*n, DVec3::new(0.0, 0.6, -0.8), DVec3::Z, 12.0);
            prop_assert!(z.is_finite() && (0.0..=12.0).contains(&z));
        }
    }
}

/// The error is second order, at the border too: doubling the samples of a
/// sphere cuts the largest error (a corner) about four times.
#[test]
fn sphere_error_is_second_order() {
    let max_err = |n: usize| {
        let th = warped(0.6, 2.4, n, 0.3);
        let ph = warped(-1.2, 1.3, n, -0.4);
        let mut data = Vec::new();
        for &t in &th {
            for &p in &ph {
                data.push(DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos()));
            }
        }
        let c = surface_curvature(&Grid::new(n, n, data).unwrap());
        c.gaussian
            .iter()
            .map(|k| (k - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (max_err(21), max_err(41));
    assert!(coarse / fine > 3.0, "errors {coarse:e} → {fine:e}");
    assert!(fine < 2e-2, "{fine:e}");
}

/// Zebra stripes: a horizontal mirror seen from above reflects straight up
/// (the top stripe); tilting the normal moves the stripe coordinate.
#[test]
fn zebra_reflects_the_view_ray() {
    let down = DVec3::new(0.0, 0.0, -1.0);
    assert!((zebra_coordinate(DVec3::Z, down, DVec3::Z, 10.0) - 10.0).abs() < 1e-12);
    let n = DVec3::new(0.0, 1.0, 1.0).normalize(); // 45°: reflects horizontally
    assert!((zebra_coordinate(n, down, DVec3::Z, 10.0) - 5.0).abs() < 1e-12);
}
