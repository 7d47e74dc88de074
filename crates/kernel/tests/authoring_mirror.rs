//! `docs/math.md §9`, mirror symmetry: the mirrored mesh equals its reflection, the toggle
//! restores the bits, the seam is as smooth as the rest, the initial curve is
//! reflected below t₀.

mod common;

use common::authoring::*;
use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::KernelError;
use streamline_kernel::authoring::Axis;
use streamline_kernel::levels::presets;
use streamline_kernel::streamline::surface_mesh::bounds;

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
