//! Shared strategies and independent reference implementations for the property tests.
#![allow(dead_code)]

pub mod authoring;
pub mod joins;
pub mod loop_meshes;
pub mod reference_fit;

use glam::{DQuat, DVec3};
use proptest::prelude::*;

/// A random unit vector (uniform on the sphere).
pub fn unit() -> impl Strategy<Value = DVec3> {
    (-1.0f64..1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

/// A random rotation.
pub fn rotation() -> impl Strategy<Value = DQuat> {
    (unit(), -std::f64::consts::PI..std::f64::consts::PI)
        .prop_map(|(axis, angle)| DQuat::from_axis_angle(axis, angle))
}

/// A random walk of `n` unit tangents whose neighbours are at most `max_angle` apart.
pub fn walk(
    n: std::ops::RangeInclusive<usize>,
    max_angle: f64,
) -> impl Strategy<Value = Vec<DVec3>> {
    (unit(), prop::collection::vec((unit(), 0.0..max_angle), n)).prop_map(|(start, steps)| {
        let mut out = Vec::with_capacity(steps.len());
        let mut cur = start;
        for (axis, angle) in steps {
            let perp = axis
                .reject_from(cur)
                .try_normalize()
                .unwrap_or_else(|| cur.any_orthonormal_vector());
            cur = (DQuat::from_axis_angle(perp, angle) * cur).normalize();
            out.push(cur);
        }
        out
    })
}

/// Tangents with nasty neighbours: exact antipodes, exact repeats, nearly parallel
/// pairs, and magnitudes from subnormal to near `f64::MAX` (normalised by the kernel).
pub fn nasty(n: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec(
        (
            unit(),
            0u8..6,
            prop::sample::select(vec![1.0, 1e-300, 1e-310, 1e300, 1e-9, 3.0]),
        ),
        n,
    )
    .prop_map(|v| {
        let mut out: Vec<DVec3> = Vec::with_capacity(v.len());
        let mut prev = DVec3::X;
        for (i, (u, kind, scale)) in v.into_iter().enumerate() {
            let d = match kind {
                0 if i > 0 => -prev,
                1 if i > 0 => prev,
                2 if i > 0 => (prev + u * 1e-9).normalize(),
                3 if i > 0 => (-prev + u * 1e-9).normalize(),
                _ => u,
            };
            prev = d;
            out.push(d * scale);
        }
        out
    })
}

/// Angles `φ_i` for tangents on one great circle, spread under π.
pub fn circle_angles(n: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Vec<f64>> {
    (-3.0f64..3.0, prop::collection::vec(0.0f64..1.0, n)).prop_map(|(start, raw)| {
        let total: f64 = raw.iter().sum::<f64>().max(1e-9);
        let spread = 3.0; // < π
        let mut acc = start;
        // a random, not necessarily monotone, walk inside [start, start+spread]
        raw.iter()
            .enumerate()
            .map(|(i, r)| {
                if i % 3 == 2 {
                    acc - 0.3 * r * spread / raw.len() as f64
                } else {
                    acc += r / total * spread * 0.9;
                    acc
                }
            })
            .collect()
    })
}

/// The point at angle `a` on the great circle `R · (cos a, sin a, 0)`.
pub fn on_circle(r: DQuat, a: f64) -> DVec3 {
    r * DVec3::new(a.cos(), a.sin(), 0.0)
}

/// The angle of `v` on that great circle, unwrapped near `near`, and its distance off the circle.
pub fn circle_angle(r: DQuat, v: DVec3, near: f64) -> (f64, f64) {
    let w = r.inverse() * v;
    let a = w.y.atan2(w.x);
    let k = ((near - a) / std::f64::consts::TAU).round();
    (a + k * std::f64::consts::TAU, w.z.abs())
}

/// Planar schemes as explicit subdivision matrices built from their stencils
/// (an independent path from the kernel's loops). Returns rows of (index, weight).
pub fn planar_matrix(scheme: &str, n: usize, omega: f64) -> Vec<Vec<(usize, f64)>> {
    let mut m = Vec::new();
    match scheme {
        "chaikin" => {
            for i in 0..n - 1 {
                m.push(vec![(i, 0.75), (i + 1, 0.25)]);
                m.push(vec![(i, 0.25), (i + 1, 0.75)]);
            }
        }
        "cubic" => {
            m.push(vec![(0, 0.5), (1, 0.5)]);
            for i in 1..n - 1 {
                m.push(vec![(i - 1, 1.0 / 8.0), (i, 6.0 / 8.0), (i + 1, 1.0 / 8.0)]);
                m.push(vec![(i, 0.5), (i + 1, 0.5)]);
            }
        }
        "four" => {
            let w = omega / 16.0;
            for i in 0..n {
                m.push(vec![(i, 1.0)]);
                if i + 1 == n {
                    break;
                }
                if n == 2 {
                    m.push(vec![(0, 0.5), (1, 0.5)]);
                } else if i == 0 {
                    m.push(vec![(0, 3.0 / 8.0), (1, 6.0 / 8.0), (2, -1.0 / 8.0)]);
                } else if i == n - 2 {
                    m.push(vec![
                        (n - 1, 3.0 / 8.0),
                        (n - 2, 6.0 / 8.0),
                        (n - 3, -1.0 / 8.0),
                    ]);
                } else {
                    m.push(vec![
                        (i - 1, -w),
                        (i, 0.5 + w),
                        (i + 1, 0.5 + w),
                        (i + 2, -w),
                    ]);
                }
            }
        }
        _ => unreachable!(),
    }
    m
}

/// Applies a planar scheme `depth` times to scalars.
pub fn planar(scheme: &str, p: &[f64], depth: u32, omega: f64) -> Vec<f64> {
    let mut cur = p.to_vec();
    for _ in 0..depth {
        let m = planar_matrix(scheme, cur.len(), omega);
        cur = m
            .iter()
            .map(|row| row.iter().map(|&(j, w)| w * cur[j]).sum())
            .collect();
    }
    cur
}

/// Cox–de Boor recursion straight from the definition (independent of the kernel's A2.2).
pub fn bspline_basis(knots: &[f64], j: usize, k: usize, u: f64, last: bool) -> f64 {
    if k == 1 {
        let (a, b) = (knots[j], knots[j + 1]);
        return if (a <= u && u < b) || (last && u == b && a < b && b == *knots.last().unwrap()) {
            1.0
        } else {
            0.0
        };
    }
    let mut v = 0.0;
    let d1 = knots[j + k - 1] - knots[j];
    if d1 > 0.0 {
        v += (u - knots[j]) / d1 * bspline_basis(knots, j, k - 1, u, last);
    }
    let d2 = knots[j + k] - knots[j + 1];
    if d2 > 0.0 {
        v += (knots[j + k] - u) / d2 * bspline_basis(knots, j + 1, k - 1, u, last);
    }
    v
}

/// A plain `v`/`f` OBJ reader for the test meshes (independent of the
/// app's tobj path): positions and triangles, with the mesh's topology.
pub fn read_obj(
    path: &std::path::Path,
) -> (
    streamline_kernel::loop_subdiv::trimesh::TriMesh,
    streamline_kernel::loop_subdiv::trimesh::Topology,
) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut p = Vec::new();
    let mut f = Vec::new();
    for l in text.lines() {
        let w: Vec<&str> = l.split_whitespace().collect();
        match w.first() {
            Some(&"v") => p.push(DVec3::new(
                w[1].parse().unwrap(),
                w[2].parse().unwrap(),
                w[3].parse().unwrap(),
            )),
            Some(&"f") => f.push(
                [0, 1, 2].map(|k| w[k + 1].split('/').next().unwrap().parse::<u32>().unwrap() - 1),
            ),
            _ => {}
        }
    }
    streamline_kernel::loop_subdiv::trimesh::TriMesh::new(p, f).unwrap()
}
