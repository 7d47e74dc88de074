//! How a later face's poles next to its seam are held (docs/math.md §11.5):
//! the seam curve as its first column of poles, its second column on the
//! lines through the earlier face's last two (a chain), and moved along the
//! earlier face's normal so that its cross derivative lies in the earlier
//! face's tangent plane (Eq. 76: a side seam, and a chain after the lines).

use super::curve::Curve;
use super::surface::BSplineSurface;
use crate::joins::Edge;
use glam::DVec3;

/// `a`'s cross derivative along its side edge `edge` (up to a constant
/// positive factor), over `range` as the shell cuts the seam's piece: the
/// curve in `u` whose poles are the differences of `a`'s edge row of poles
/// and the row next to it (the `v` derivative of a clamped surface at its
/// boundary, Piegl & Tiller Eq. 3.17, is `q / v_{q+1}` times it).
pub(super) fn side_cross(a: &BSplineSurface, edge: Edge, (u0, u1): (f64, f64)) -> Curve {
    let rows = a.poles.rows();
    let (edge, next) = if edge == Edge::First {
        (0, 1)
    } else {
        (rows - 1, rows - 2)
    };
    let poles = a
        .poles
        .row(next)
        .iter()
        .zip(a.poles.row(edge))
        .map(|(n, e)| *n - *e)
        .collect();
    let d = Curve::new(&a.knots_u, poles);
    if u0 < u1 {
        d.piece(u0, u1)
    } else {
        d.piece(u1, u0).reversed()
    }
}

/// The unit normal of the earlier face along a side seam at `w`: the seam
/// curve's tangent crossed with the earlier face's cross derivative
/// (`None` where either vanishes).
fn side_normal(seam: &Curve, cross: &Curve, w: f64) -> Option<DVec3> {
    let h = 1e-6;
    let (lo, hi) = ((w - h).max(0.0), (w + h).min(1.0));
    let tangent = seam.eval(hi) - seam.eval(lo);
    let n = tangent.cross(cross.eval(w));
    let len = n.length();
    (len > 1e-300 && len.is_finite()).then(|| n / len)
}

/// Moves each pole of `surface`'s second column along the earlier face's
/// normal at its Greville abscissa so that the face's cross derivative at
/// the seam (`u = 0`) lies in the earlier face's tangent plane: the least
/// squares of its normal component at `8 n + 16` points along the seam
/// (`n` the poles in `v`), a tiny ridge keeping the moves small where a
/// pole is barely seen. With the first column the seam curve, the face's
/// normal along the seam is then the earlier face's (G1, docs/math.md §11.2).
pub(super) fn hold_side(surface: &mut BSplineSurface, seam: &Curve, cross: &Curve) {
    let kv = surface.knots_v.clone();
    let (q, n) = (kv.degree(), kv.count());
    let knots = kv.knots();
    let greville: Vec<f64> = (0..n)
        .map(|l| knots[l + 1..=l + q].iter().sum::<f64>() / q as f64)
        .collect();
    let normals: Vec<DVec3> = greville
        .iter()
        .map(|&g| side_normal(seam, cross, g).unwrap_or(DVec3::ZERO))
        .collect();
    let d: Vec<DVec3> = (0..n)
        .map(|l| surface.poles.get(l, 1) - surface.poles.get(l, 0))
        .collect();
    // normal equations (Aᵀ A + λ I) c = −Aᵀ r, A banded (q + 1 per row)
    let mut ata = vec![0.0f64; n * n];
    let mut atr = vec![0.0f64; n];
    let samples = 8 * n + 16;
    for k in 0..=samples {
        let w = k as f64 / samples as f64;
        let Some(nk) = side_normal(seam, cross, w) else {
            continue;
        };
        let (first, basis) = kv.basis(w);
        let mut a = [0.0f64; super::knots::MAX_DEGREE + 1];
        let mut r = 0.0;
        for i in 0..=q {
            let l = first + i;
            a[i] = basis[i] * normals[l].dot(nk);
            r += basis[i] * d[l].dot(nk);
        }
        for i in 0..=q {
            atr[first + i] -= a[i] * r;
            for j in 0..=q {
                ata[(first + i) * n + first + j] += a[i] * a[j];
            }
        }
    }
    let scale = (0..n).map(|i| ata[i * n + i]).fold(0.0f64, f64::max);
    if !(scale > 0.0 && scale.is_finite()) {
        return;
    }
    for i in 0..n {
        ata[i * n + i] += 1e-12 * scale;
    }
    let Some(c) = solve_spd(&mut ata, &mut atr, n) else {
        return;
    };
    for l in 0..n {
        let p = surface.poles.get(l, 1) + normals[l] * c[l];
        surface.poles.set(l, 1, p);
    }
}

/// Solves `M x = b` for a symmetric positive definite `M` (`n × n`, row
/// major) by Cholesky, in place; `None` if a pivot is not positive.
fn solve_spd(m: &mut [f64], b: &mut [f64], n: usize) -> Option<Vec<f64>> {
    for j in 0..n {
        let mut d = m[j * n + j];
        for k in 0..j {
            d -= m[j * n + k] * m[j * n + k];
        }
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        let d = d.sqrt();
        m[j * n + j] = d;
        for i in j + 1..n {
            let mut s = m[i * n + j];
            for k in 0..j {
                s -= m[i * n + k] * m[j * n + k];
            }
            m[i * n + j] = s / d;
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= m[i * n + k] * b[k];
        }
        b[i] = s / m[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= m[k * n + i] * b[k];
        }
        b[i] = s / m[i * n + i];
    }
    Some(b.to_vec())
}

/// Puts the seam's poles into `surface`'s first column; with `g1` (`a`'s
/// face and its column next to the seam), each pole of the second column
/// is projected onto the line through `a`'s two poles before it, so the
/// poles next to the seam are collinear across it.
pub(super) fn hold(
    surface: &mut BSplineSurface,
    seam: &[DVec3],
    g1: Option<(&BSplineSurface, usize)>,
) {
    for (l, p) in seam.iter().enumerate() {
        surface.poles.set(l, 0, *p);
    }
    if let Some((a, inner)) = g1 {
        for l in 0..surface.poles.rows() {
            let p0 = surface.poles.get(l, 0);
            let dir = (p0 - a.poles.get(l, inner)).normalize_or_zero();
            let p1 = surface.poles.get(l, 1);
            surface.poles.set(l, 1, p0 + dir * (p1 - p0).dot(dir));
        }
    }
}

/// The largest angle (degrees) between the later face's normal along its
/// seam (`u = 0`, its cross derivative `Σ_l M_l (Q_{l,1} − Q_{l,0})` crossed
/// with the seam curve's tangent) and the earlier face's ([`side_normal`]),
/// per `v` span of `surface`, at 9 points a span: the residual Eq. 76 leaves.
pub(super) fn seam_angles(surface: &BSplineSurface, seam: &Curve, cross: &Curve) -> Vec<f64> {
    let kv = &surface.knots_v;
    let q = kv.degree();
    let h = 1e-6;
    (0..kv.spans())
        .map(|j| {
            let (lo, hi) = kv.span_range(j);
            (0..=8)
                .map(|k| {
                    let w = lo + (hi - lo) * k as f64 / 8.0;
                    let Some(n) = side_normal(seam, cross, w) else {
                        return 0.0;
                    };
                    let (first, basis) = kv.basis(w);
                    let e: DVec3 = (0..=q)
                        .map(|a| {
                            let l = first + a;
                            (surface.poles.get(l, 1) - surface.poles.get(l, 0)) * basis[a]
                        })
                        .sum();
                    let (a, b) = ((w - h).max(0.0), (w + h).min(1.0));
                    let m = e.cross(seam.eval(b) - seam.eval(a));
                    let len = m.length();
                    if !(len > 1e-300 && len.is_finite()) {
                        return 0.0;
                    }
                    let c = (m / len).dot(n).abs().min(1.0);
                    c.acos().to_degrees()
                })
                .fold(0.0f64, f64::max)
        })
        .collect()
}
