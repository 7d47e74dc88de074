//! Curvature analysis: the numbers behind the editor's curvature comb,
//! Gaussian and mean curvature maps and zebra stripes.
//!
//! * Streamlines: a streamline is integrated from unit tangents `t_k` at arc
//!   lengths `s_k` (Eq. 65), so its curvature is the turning speed of the
//!   tangent, `κ = |dT/ds|`. Between `t_k` and `t_{k+1}` the tangent turns by
//!   the angle `θ_k` over `s_{k+1} − s_k`: `κ_k = θ_k / (s_{k+1} − s_k)`, at the
//!   streamline point `p_{k+1}` where the two segments meet. On a circle of
//!   radius `R` this is exactly `1/R` for any spacing.
//! * Surfaces: the point grid (one row per streamline) is a parametric surface
//!   `P(u, v)` over the grid indices. Its first and second derivatives come from
//!   second-order finite differences (central inside, one-sided at the border;
//!   the mixed one is the derivative of `P_u` across),
//!   and the fundamental forms give `K = (LN − M²)/(EG − F²)` and
//!   `H = (EN − 2FM + GL) / (2(EG − F²))`. Both are invariant under a smooth
//!   change of parameters, so the index parametrisation is as good as any, and
//!   the error is `O(h²)` in the grid spacing. The normal is
//!   `P_u × P_v` (along the streamline × across), the mesh's normal
//!   ([`crate::streamline::surface_mesh`]); `H > 0` where the surface bends towards it.
//!
//! Degenerate places (a zero-length step, a collapsed row) give curvature `0`,
//! never NaN.

use crate::grid::Grid;
use glam::DVec3;

/// The angle between two vectors in `[0, π]`, accurate for small and large angles.
pub fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// Curvature of a streamline integrated from `tangents` at arc lengths `s`
/// (Eq. 65): `κ_k = θ(t_k, t_{k+1}) / (s_{k+1} − s_k)` for `k = 0..n−1`, the
/// curvature at streamline point `k + 1`. Degenerate steps give 0.
pub fn streamline_curvature(tangents: &[DVec3], s: &[f64]) -> Vec<f64> {
    let n = tangents.len().min(s.len());
    (0..n.saturating_sub(1))
        .map(|k| {
            let ds = s[k + 1] - s[k];
            let a = angle_between(tangents[k], tangents[k + 1]);
            let kappa = a / ds;
            if kappa.is_finite() && ds > 0.0 {
                kappa
            } else {
                0.0
            }
        })
        .collect()
}

/// One tooth of a curvature comb: from `base` (a streamline point) to `tip`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CombTooth {
    /// The streamline point.
    pub base: DVec3,
    /// `base − scale · κ · N`, with `N` the principal normal (towards the centre
    /// of curvature): teeth stand on the convex side, as in CAD programs.
    pub tip: DVec3,
    /// The curvature there.
    pub kappa: f64,
}

/// The curvature comb of a streamline: `points` are its `n + 2` points from
/// Eq. 65, `tangents` and `s` what it was integrated from; one tooth per
/// interior point `p_{k+1}`, `k = 0..n−1`.
pub fn comb(points: &[DVec3], tangents: &[DVec3], s: &[f64], scale: f64) -> Vec<CombTooth> {
    let kappa = streamline_curvature(tangents, s);
    kappa
        .iter()
        .enumerate()
        .filter_map(|(k, &kappa)| {
            let base = *points.get(k + 1)?;
            let normal = (tangents[k + 1] - tangents[k])
                .try_normalize()
                .unwrap_or(DVec3::ZERO);
            Some(CombTooth {
                base,
                tip: base - normal * (scale * kappa),
                kappa,
            })
        })
        .collect()
}

/// Gaussian and mean curvature at every point of a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceCurvature {
    /// `K` per point, row-major like the grid.
    pub gaussian: Vec<f64>,
    /// `H` per point (positive where the surface bends towards `P_u × P_v`).
    pub mean: Vec<f64>,
}

impl SurfaceCurvature {
    /// `(min, max)` of a field, ignoring nothing (every value is finite).
    pub fn range(values: &[f64]) -> (f64, f64) {
        values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    /// A robust symmetric range for a colour map: the `q`-quantile of `|v|`
    /// (`q` in `[0, 1]`, e.g. 0.98 so a few spikes at the border do not wash
    /// the map out). Never 0 (a flat field gets `1e-12`).
    pub fn robust_limit(values: &[f64], q: f64) -> f64 {
        if values.is_empty() {
            return 1e-12;
        }
        let mut a: Vec<f64> = values.iter().map(|v| v.abs()).collect();
        let k = ((a.len() - 1) as f64 * q.clamp(0.0, 1.0)).round() as usize;
        let (_, v, _) = a.select_nth_unstable_by(k, f64::total_cmp);
        v.max(1e-12)
    }
}

/// Second-order first derivative of `f` along one direction at index `i` of `n`
/// samples (central inside, one-sided at the ends; linear for `n = 2`).
fn d1(f: impl Fn(usize) -> DVec3, i: usize, n: usize) -> DVec3 {
    match n {
        0 | 1 => DVec3::ZERO,
        2 => f(1) - f(0),
        _ if i == 0 => (-3.0 * f(0) + 4.0 * f(1) - f(2)) * 0.5,
        _ if i == n - 1 => (3.0 * f(n - 1) - 4.0 * f(n - 2) + f(n - 3)) * 0.5,
        _ => (f(i + 1) - f(i - 1)) * 0.5,
    }
}

/// Second-order second derivative at index `i` of `n ≥ 4` samples (`n = 3`:
/// the one central stencil everywhere).
fn d2(f: impl Fn(usize) -> DVec3, i: usize, n: usize) -> DVec3 {
    match n {
        0..=2 => DVec3::ZERO,
        3 => f(0) - 2.0 * f(1) + f(2),
        _ if i == 0 => 2.0 * f(0) - 5.0 * f(1) + 4.0 * f(2) - f(3),
        _ if i == n - 1 => 2.0 * f(n - 1) - 5.0 * f(n - 2) + 4.0 * f(n - 3) - f(n - 4),
        _ => f(i + 1) - 2.0 * f(i) + f(i - 1),
    }
}

/// Gaussian and mean curvature of the surface through a point grid (rows:
/// streamlines; see the module doc). Grids with fewer than 3 points in a
/// direction have no second derivative there: their curvature is 0.
pub fn surface_curvature(points: &Grid<DVec3>) -> SurfaceCurvature {
    let (rows, cols) = (points.rows(), points.cols());
    let n = rows * cols;
    let idx = |r: usize, c: usize| r * cols + c;
    let mut pu = vec![DVec3::ZERO; n];
    let mut pv = vec![DVec3::ZERO; n];
    for r in 0..rows {
        for c in 0..cols {
            pu[idx(r, c)] = d1(|k| points.get(r, k), c, cols);
            pv[idx(r, c)] = d1(|k| points.get(k, c), r, rows);
        }
    }
    let mut gaussian = vec![0.0; n];
    let mut mean = vec![0.0; n];
    if rows < 3 || cols < 3 {
        return SurfaceCurvature { gaussian, mean };
    }
    for r in 0..rows {
        for c in 0..cols {
            let i = idx(r, c);
            let (a, b) = (pu[i], pv[i]);
            let puu = d2(|k| points.get(r, k), c, cols);
            let puv = d1(|k| pu[idx(k, c)], r, rows);
            let pvv = d2(|k| points.get(k, c), r, rows);
            let cross = a.cross(b);
            let Some(normal) = cross.try_normalize() else {
                continue;
            };
            let (e, f, g) = (a.dot(a), a.dot(b), b.dot(b));
            let (l, m, nn) = (puu.dot(normal), puv.dot(normal), pvv.dot(normal));
            let det = e * g - f * f;
            // a parametrisation that folds (P_u ∥ P_v) has no normal to measure against
            if det.is_nan() || det <= 1e-12 * e * g {
                continue;
            }
            let k = (l * nn - m * m) / det;
            let h = (e * nn - 2.0 * f * m + g * l) / (2.0 * det);
            if k.is_finite() && h.is_finite() {
                gaussian[i] = k;
                mean[i] = h;
            }
        }
    }
    SurfaceCurvature { gaussian, mean }
}

/// Zebra stripes (reflection lines): the stripe coordinate of a surface point
/// with unit normal `normal` seen from `eye` along the view ray `view`
/// (unit, from the eye to the point), for light stripes parallel to the
/// horizontal plane with normal `up`: the elevation angle of the reflected ray,
/// in units of `π / stripes`. Its integer part's parity picks black or white.
pub fn zebra_coordinate(normal: DVec3, view: DVec3, up: DVec3, stripes: f64) -> f64 {
    let r = view - 2.0 * view.dot(normal) * normal;
    let e = r.dot(up).clamp(-1.0, 1.0).asin(); // elevation in [−π/2, π/2]
    (e / std::f64::consts::PI + 0.5) * stripes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_point_grid_is_flat() {
        let g = Grid::new(2, 2, vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE]).unwrap();
        let c = surface_curvature(&g);
        assert!(c.gaussian.iter().chain(&c.mean).all(|&v| v == 0.0));
    }

    #[test]
    fn collapsed_grid_gives_zero_not_nan() {
        let g = Grid::filled(4, 5, DVec3::new(1.0, 2.0, 3.0));
        let c = surface_curvature(&g);
        assert!(c.gaussian.iter().chain(&c.mean).all(|&v| v == 0.0));
        let k = streamline_curvature(&[DVec3::X, DVec3::Y], &[0.0, 0.0]);
        assert_eq!(k, vec![0.0]);
    }
}
