//! Progressive interpolation on the Gaussian sphere (docs/math.md §7, on the Gaussian sphere):
//! make the approximating tangent schemes — Catmull–Clark (cubic B-spline ⊗
//! cubic B-spline) and Doo–Sabin (Chaikin ⊗ Chaikin) — pass through the
//! designer's control tangents at the limit.
//!
//! **Limit tangents.** Near an interior control tangent a step of either scheme
//! only reads the 3×3 block around it, and produces the block around the same
//! parameter point at the next level:
//! - cubic B-spline, per direction: `(a, b, c) → (mid(a, b), mid(¾(a,b), ¼(b,c)), mid(b, c))`
//!   (edge, vertex, edge point of Eqs. 57–58), a map of the triple to itself;
//! - Chaikin: `(a, b, c) → (¾(a,b), ¼(b,c))`, a pair straddling the point,
//!   and then `(p, q) → (¼(p,q), ¾(p,q))` (Eq. 53), whose midpoint stays put on
//!   the great circle.
//!
//! Iterating the local map (`LIMIT_STEPS` times, in the scene's blend order)
//! is exactly subdividing the whole net that many times and reading the tangent
//! at that parameter, so it gives the limit to rounding. With the open-end
//! rules of these schemes the limit surface does not reach the border
//! tangents (its edge is the limit of the second row and column), so the
//! border tangents stay as the designer set them and the interior ones are
//! moved.
//!
//! **Iteration.** Like 002's `V ← V + (V⁰ − V∞)`, with rotations: each interior
//! tangent is turned by the rotation that takes its current limit tangent to
//! the designer's tangent (`RELAXATION` times its angle), until the largest
//! angle is below the tolerance.

use crate::grid::Grid;
use crate::levels::surface::{BlendOrder, SurfaceScheme};
use crate::sphere::blend::{mid, quarter, quarters, three_quarters};
use glam::{DQuat, DVec3};

/// Local subdivision steps taken for a limit tangent (the error shrinks by about
/// 4 per step: 32 steps is far below rounding).
pub(crate) const LIMIT_STEPS: usize = 32;

/// Over-relaxation of each turn. In the planar analogue the limit operator's
/// eigenvalues lie in `[1/9, 1]` (cubic ⊗ cubic; `[1/4, 1]` for Chaikin ⊗
/// Chaikin), so plain steps shrink the slowest error by only `8/9`; turning by
/// `w` times the angle, `w = 2/(1/9 + 1) ≈ 1.8`, balances both ends (any
/// `0 < w < 2` converges). 1.6 is used, safe for both schemes.
pub(crate) const RELAXATION: f64 = 1.6;

/// Whether `scheme` is approximating (and so has something to interpolate).
pub fn applies(scheme: SurfaceScheme) -> bool {
    matches!(
        scheme,
        SurfaceScheme::CatmullClark | SurfaceScheme::DooSabin
    )
}

fn cubic_triple(a: DVec3, b: DVec3, c: DVec3) -> [DVec3; 3] {
    [
        mid(a, b),
        mid(three_quarters(a, b), quarter(b, c)),
        mid(b, c),
    ]
}

/// The limit tangent at interior control tangent `(r, c)` of `net`
/// (`1 ≤ r ≤ rows − 2`, `1 ≤ c ≤ cols − 2`), or `None` on the border or for a
/// scheme that interpolates anyway.
pub fn limit_tangent(
    scheme: SurfaceScheme,
    order: BlendOrder,
    net: &Grid<DVec3>,
    r: usize,
    c: usize,
) -> Option<DVec3> {
    if r == 0 || c == 0 || r + 1 >= net.rows() || c + 1 >= net.cols() {
        return None;
    }
    let mut b = [[DVec3::ZERO; 3]; 3];
    for (i, row) in b.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = net.get(r + i - 1, c + j - 1);
        }
    }
    match scheme {
        SurfaceScheme::CatmullClark => {
            for _ in 0..LIMIT_STEPS {
                b = tensor_step(b, order, cubic_triple);
            }
            Some(b[1][1])
        }
        SurfaceScheme::DooSabin => {
            // first step: the 3×3 block becomes the 2×2 block around the point
            let first = |a: DVec3, m: DVec3, z: DVec3| [three_quarters(a, m), quarter(m, z)];
            let mut q: [[DVec3; 2]; 2] = match order {
                BlendOrder::SFirst => {
                    let rows = b.map(|row| first(row[0], row[1], row[2]));
                    let cols = [0, 1].map(|j| first(rows[0][j], rows[1][j], rows[2][j]));
                    [[cols[0][0], cols[1][0]], [cols[0][1], cols[1][1]]]
                }
                BlendOrder::TFirst => {
                    let cols = [0, 1, 2].map(|j| first(b[0][j], b[1][j], b[2][j]));
                    [0, 1].map(|i| first(cols[0][i], cols[1][i], cols[2][i]))
                }
            };
            let pair = |p: DVec3, s: DVec3| {
                let (x, y) = quarters(p, s);
                [x, y]
            };
            for _ in 0..LIMIT_STEPS {
                q = match order {
                    BlendOrder::SFirst => {
                        let rows = q.map(|row| pair(row[0], row[1]));
                        let cols = [0, 1].map(|j| pair(rows[0][j], rows[1][j]));
                        [[cols[0][0], cols[1][0]], [cols[0][1], cols[1][1]]]
                    }
                    BlendOrder::TFirst => {
                        let cols = [0, 1].map(|j| pair(q[0][j], q[1][j]));
                        [0, 1].map(|i| pair(cols[0][i], cols[1][i]))
                    }
                };
            }
            Some(match order {
                BlendOrder::SFirst => mid(mid(q[0][0], q[0][1]), mid(q[1][0], q[1][1])),
                BlendOrder::TFirst => mid(mid(q[0][0], q[1][0]), mid(q[0][1], q[1][1])),
            })
        }
        SurfaceScheme::Kobbelt { .. } => None,
    }
}

/// One tensor step of a 3×3 block with a triple map, in the blend order.
fn tensor_step(
    b: [[DVec3; 3]; 3],
    order: BlendOrder,
    f: impl Fn(DVec3, DVec3, DVec3) -> [DVec3; 3],
) -> [[DVec3; 3]; 3] {
    match order {
        BlendOrder::SFirst => {
            let rows = b.map(|row| f(row[0], row[1], row[2]));
            let cols = [0, 1, 2].map(|j| f(rows[0][j], rows[1][j], rows[2][j]));
            [0, 1, 2].map(|i| [cols[0][i], cols[1][i], cols[2][i]])
        }
        BlendOrder::TFirst => {
            let cols = [0, 1, 2].map(|j| f(b[0][j], b[1][j], b[2][j]));
            let t = [0, 1, 2].map(|i| [cols[0][i], cols[1][i], cols[2][i]]);
            t.map(|row| f(row[0], row[1], row[2]))
        }
    }
}

/// The result of [`interpolate_net`].
#[derive(Debug, Clone, PartialEq)]
pub struct NetInterpolation {
    /// The control net whose limit passes through the designer's interior tangents.
    pub net: Grid<DVec3>,
    /// Iterations taken.
    pub iterations: usize,
    /// The largest angle (radians) between a designer's interior tangent and its limit.
    pub max_angle: f64,
}

/// The angle between two unit vectors, stable for small and large angles.
fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// Moves the interior tangents of `design` until the limit of `scheme` passes
/// through every interior design tangent within `tolerance` radians (or
/// `max_iterations` is reached). Border tangents are kept.
pub fn interpolate_net(
    scheme: SurfaceScheme,
    order: BlendOrder,
    design: &Grid<DVec3>,
    tolerance: f64,
    max_iterations: usize,
) -> NetInterpolation {
    let mut net = design.clone();
    let (rows, cols) = (net.rows(), net.cols());
    let mut max_angle = 0.0;
    for k in 0..=max_iterations {
        let mut turns = Vec::new();
        max_angle = 0.0f64;
        for r in 1..rows.saturating_sub(1) {
            for c in 1..cols.saturating_sub(1) {
                let Some(l) = limit_tangent(scheme, order, &net, r, c) else {
                    continue;
                };
                let d = design.get(r, c);
                max_angle = max_angle.max(angle(l, d));
                // axis and angle straight from the pair (a quaternion's
                // `acos(w)` loses small angles below 1e-8)
                let x = l.cross(d);
                if let Some(axis) = x.try_normalize() {
                    let a = x.length().atan2(l.dot(d));
                    turns.push((r, c, DQuat::from_axis_angle(axis, RELAXATION * a)));
                }
            }
        }
        if max_angle <= tolerance || k == max_iterations {
            return NetInterpolation {
                net,
                iterations: k,
                max_angle,
            };
        }
        for (r, c, q) in turns {
            let t = (q * net.get(r, c)).normalize();
            net.set(r, c, t);
        }
    }
    NetInterpolation {
        net,
        iterations: max_iterations,
        max_angle,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levels::surface::subdivide;

    fn net(rows: usize, cols: usize, seed: f64) -> Grid<DVec3> {
        let data = (0..rows * cols)
            .map(|i| {
                let (r, c) = ((i / cols) as f64, (i % cols) as f64);
                DVec3::new(
                    1.0,
                    0.35 * (0.9 * r + seed).sin() + 0.1 * c,
                    0.4 * (0.7 * c - seed).cos(),
                )
                .normalize()
            })
            .collect();
        Grid::new(rows, cols, data).unwrap()
    }

    #[test]
    fn sphere_limit_matches_whole_net_subdivision() {
        // the local recursion against 7 levels of the whole net's subdivision
        let depth = 7;
        for order in [BlendOrder::SFirst, BlendOrder::TFirst] {
            let g = net(5, 6, 0.3);
            let cc = subdivide(SurfaceScheme::CatmullClark, order, &g, depth).unwrap();
            let ds = subdivide(SurfaceScheme::DooSabin, order, &g, depth).unwrap();
            for r in 1..4 {
                for c in 1..5 {
                    // cubic: vertex i sits at 2i − 1, then 2i − 1 again each level
                    let (mut ir, mut ic) = (r, c);
                    for _ in 0..depth {
                        ir = 2 * ir - 1;
                        ic = 2 * ic - 1;
                    }
                    let l = limit_tangent(SurfaceScheme::CatmullClark, order, &g, r, c).unwrap();
                    let d = angle(l, cc.get(ir, ic));
                    assert!(d < 2e-4, "{order:?} CC ({r},{c}): {d:e}");
                    // Chaikin: the point between indices m and m + 1, m = 2i − 1, then 2m
                    let (mut mr, mut mc) = (2 * r - 1, 2 * c - 1);
                    for _ in 1..depth {
                        mr *= 2;
                        mc *= 2;
                    }
                    let centre = mid(
                        mid(ds.get(mr, mc), ds.get(mr, mc + 1)),
                        mid(ds.get(mr + 1, mc), ds.get(mr + 1, mc + 1)),
                    );
                    let l = limit_tangent(SurfaceScheme::DooSabin, order, &g, r, c).unwrap();
                    let d = angle(l, centre);
                    assert!(d < 2e-4, "{order:?} DS ({r},{c}): {d:e}");
                }
            }
        }
    }

    #[test]
    fn sphere_interpolation_reaches_the_design() {
        for scheme in [SurfaceScheme::CatmullClark, SurfaceScheme::DooSabin] {
            for order in [BlendOrder::SFirst, BlendOrder::TFirst] {
                let g = net(6, 9, 1.1);
                let res = interpolate_net(scheme, order, &g, 1e-12, 1000);
                assert!(res.max_angle <= 1e-12, "{scheme:?} {order:?}: {res:?}");
                for r in 0..6 {
                    for c in 0..9 {
                        match limit_tangent(scheme, order, &res.net, r, c) {
                            Some(l) => {
                                let d = angle(l, g.get(r, c));
                                assert!(d < 1e-9, "{scheme:?} ({r},{c}) limit off by {d:e}");
                            }
                            None => assert_eq!(res.net.get(r, c), g.get(r, c), "border kept"),
                        }
                    }
                }
                assert!(
                    res.iterations > 0 && res.iterations < 200,
                    "{}",
                    res.iterations
                );
            }
        }
    }
}
