//! Streamline integration (paper 000, Eq. 65; docs/math.md §4).
//!
//! For tangents `t₀ … t_n` at arc lengths `s₀ … s_n` the streamline has `n+2` points:
//! `p₁ = p₀ + ½(s₁ − s₀) t₀`, `p_{i+1} = p_i + ½(s_{i+1} − s_{i−1}) t_i` for
//! `i = 1 … n−1`, `p_{n+1} = p_n + ½(s_n − s_{n−1}) t_n`. Point `k` sits at arc
//! length `s₀` (k = 0), `(s_{k−1} + s_k)/2` (1 ≤ k ≤ n) or `s_n` (k = n+1): the
//! segment around `s_i` has direction `t_i`, so the length is exactly `s_n − s₀`.
//!
//! Placement (Eqs. 1–2): the point at the anchor arc length `σ` is put on the
//! initial curve. `σ` outside `[s₀, s_n]` (approximating schemes shrink the `s`
//! range) continues the end segment's direction.

use crate::error::{KernelError, Place};
use crate::sphere::tangent::normalize_all;
use crate::streamline::surface_mesh::{PARALLEL_MIN_POINTS, slice_bounds};
use glam::DVec3;

/// Eq. 65 from `p₀ = 0`, appending `n+2` points to `out` (cleared first).
/// `tangents.len() == s.len() ≥ 2`, tangents unit, `s` increasing (not re-checked).
#[inline]
#[cfg(test)]
pub(crate) fn integrate_into(tangents: &[DVec3], s: &[f64], out: &mut Vec<DVec3>) {
    out.clear();
    out.resize(tangents.len() + 1, DVec3::ZERO);
    integrate_slice(tangents, s, out);
}

/// Eq. 65 from `p₀ = 0` into `out`, which holds exactly `n+2` points.
#[inline]
#[cfg(test)]
pub(crate) fn integrate_slice(tangents: &[DVec3], s: &[f64], out: &mut [DVec3]) {
    // the sums start at +0 and never become −0, so adding a zero shift keeps their bits
    integrate_shifted(tangents, s, DVec3::ZERO, out);
}

/// Eq. 65 from `p₀ = shift`: the sums carry the shift from the start, so
/// the points from any column on depend only on the point there and the
/// tangents after it ([`integrate_from`]).
#[inline]
fn integrate_shifted(tangents: &[DVec3], s: &[f64], shift: DVec3, out: &mut [DVec3]) {
    let n = tangents.len() - 1;
    assert!(s.len() == n + 1 && out.len() == n + 2 && n >= 1);
    out[0] = shift;
    integrate_from(tangents, s, 0, out);
}

/// Eq. 65 from point `from` (`≤ n`) on: `out[from]` holds `p_from`, and
/// `p_{i+1} = p_i + ½(s_{i+1} − s_{i−1}) t_i` is written for `i ≥ from`
/// (with the end rules at `i = 0` and `i = n`), the same sums in the same
/// order as from the first point.
#[inline]
fn integrate_from(tangents: &[DVec3], s: &[f64], from: usize, out: &mut [DVec3]) {
    let n = tangents.len() - 1;
    debug_assert!(from <= n && s.len() == n + 1 && out.len() == n + 2);
    let mut p = out[from];
    let mut i = from;
    if i == 0 {
        p += tangents[0] * (0.5 * (s[1] - s[0]));
        out[1] = p;
        i = 1;
    }
    // p_{i+1} = p_i + ½(s_{i+1} − s_{i−1}) t_i, i = 1 … n−1
    for ((t, w), o) in tangents[i.min(n)..n]
        .iter()
        .zip(s[i - 1..].windows(3))
        .zip(out[i + 1..=n].iter_mut())
    {
        p += *t * (0.5 * (w[2] - w[0]));
        *o = p;
    }
    p += tangents[n] * (0.5 * (s[n] - s[n - 1]));
    out[n + 1] = p;
}

/// [`integrate_from`] on four rows of `n + 1` tangents at once, from the
/// same point `from` (`1 ≤ from ≤ n`): per row the same sums in the same
/// order, so the same bits. One row's running sum is a chain of additions
/// that leaves most of the CPU's adders idle; four rows are four chains it
/// overlaps.
#[inline]
fn integrate_from_x4(tangents: [&[DVec3]; 4], s: [&[f64]; 4], from: usize, out: [&mut [DVec3]; 4]) {
    let n = tangents[0].len() - 1;
    for k in 0..4 {
        assert!(tangents[k].len() == n + 1 && s[k].len() == n + 1 && out[k].len() == n + 2);
    }
    assert!((1..=n).contains(&from));
    let [o0, o1, o2, o3] = out;
    let mut p = [o0[from], o1[from], o2[from], o3[from]];
    // p_{i+1} = p_i + ½(s_{i+1} − s_{i−1}) t_i, i = from … n−1
    for i in from..n {
        for k in 0..4 {
            p[k] += tangents[k][i] * (0.5 * (s[k][i + 1] - s[k][i - 1]));
        }
        o0[i + 1] = p[0];
        o1[i + 1] = p[1];
        o2[i + 1] = p[2];
        o3[i + 1] = p[3];
    }
    for k in 0..4 {
        p[k] += tangents[k][n] * (0.5 * (s[k][n] - s[k][n - 1]));
    }
    (o0[n + 1], o1[n + 1], o2[n + 1], o3[n + 1]) = (p[0], p[1], p[2], p[3]);
}

/// One row of [`place_slices_from`]: [`place_slice_from`]'s arguments and,
/// after the call, what it returned.
#[derive(Debug)]
pub struct SliceJob<'a> {
    /// The row's tangents `t₀ … t_n`.
    pub tangents: &'a [DVec3],
    /// Their arc lengths `s₀ … s_n`.
    pub s: &'a [f64],
    /// The anchor's arc length `σ`.
    pub sigma: f64,
    /// Where the anchor is placed.
    pub origin: DVec3,
    /// The first tangent that changed.
    pub from: usize,
    /// The row's `n + 2` points, as placed before the change.
    pub out: &'a mut [DVec3],
    /// Written by the call: the first point rewritten (`0`: all of them).
    pub moved_from: usize,
    /// Written by the call: the box `[min, max]` of the row's points
    /// ([`slice_bounds`]), made while they are at hand.
    pub bounds: [DVec3; 2],
}

/// [`place_slice_from`] for every job, with the same bits: the rows that
/// are only summed again from a point (the anchor before the change) go
/// four at a time when they share that point and their length
/// ([`integrate_from_x4`]); on the car at depth 6 a drag's every row does.
/// Each job's box is made too. Many rows (from [`PARALLEL_MIN_POINTS`]
/// points and 8 rows on) go in two halves, one on the helper thread
/// ([`crate::parallel::join`]), with the same numbers.
pub fn place_slices_from(jobs: &mut [SliceJob<'_>]) {
    let points: usize = jobs.iter().map(|j| j.out.len()).sum();
    if points >= PARALLEL_MIN_POINTS && jobs.len() >= 8 {
        let (a, b) = jobs.split_at_mut(jobs.len() / 2);
        crate::parallel::join(|| place_slices_here(a), || place_slices_here(b));
    } else {
        place_slices_here(jobs);
    }
}

/// [`place_slices_from`] on the calling thread.
fn place_slices_here(jobs: &mut [SliceJob<'_>]) {
    sum_slices(jobs);
    for j in jobs {
        j.bounds = slice_bounds(j.out);
    }
}

/// [`place_slices_from`] on the calling thread, without the boxes (each
/// job's `bounds` left as it was): the points and `moved_from` alone.
pub(crate) fn sum_slices(jobs: &mut [SliceJob<'_>]) {
    let mut summed: Vec<usize> = Vec::with_capacity(jobs.len());
    for (i, j) in jobs.iter_mut().enumerate() {
        let n = j.tangents.len() - 1;
        assert!(j.s.len() == n + 1 && j.out.len() == n + 2 && n >= 1);
        if j.from == 0 || j.from > n || segment_at(j.s, j.sigma) >= j.from {
            place_slice(j.tangents, j.s, j.sigma, j.origin, j.out);
            j.moved_from = 0;
        } else {
            j.moved_from = j.from + 1;
            summed.push(i);
        }
    }
    let key = |j: &SliceJob<'_>| (j.from, j.tangents.len());
    summed.sort_by_key(|&i| key(&jobs[i]));
    let mut rest = &summed[..];
    while !rest.is_empty() {
        let k = key(&jobs[rest[0]]);
        if rest.len() >= 4 && rest[..4].iter().all(|&i| key(&jobs[i]) == k) {
            let q = [rest[0], rest[1], rest[2], rest[3]];
            let [a, b, c, d] = jobs.get_disjoint_mut(q).expect("distinct jobs");
            integrate_from_x4(
                [a.tangents, b.tangents, c.tangents, d.tangents],
                [a.s, b.s, c.s, d.s],
                k.0,
                [&mut *a.out, &mut *b.out, &mut *c.out, &mut *d.out],
            );
            rest = &rest[4..];
        } else {
            let j = &mut jobs[rest[0]];
            integrate_from(j.tangents, j.s, j.from, j.out);
            rest = &rest[1..];
        }
    }
}

/// Arc length of point `k` of the polyline.
#[inline]
pub fn point_arclength(s: &[f64], k: usize) -> f64 {
    let n = s.len() - 1;
    match k {
        0 => s[0],
        k if k > n => s[n],
        k => 0.5 * (s[k - 1] + s[k]),
    }
}

/// The point of the polyline `points` (from `integrate_into`) at arc length `sigma`.
pub fn point_at(points: &[DVec3], tangents: &[DVec3], s: &[f64], sigma: f64) -> DVec3 {
    let n = s.len() - 1;
    if sigma <= s[0] {
        return points[0] + tangents[0] * (sigma - s[0]);
    }
    if sigma >= s[n] {
        return points[n + 1] + tangents[n] * (sigma - s[n]);
    }
    let k = segment_at(s, sigma);
    points[k] + tangents[k] * (sigma - point_arclength(s, k))
}

/// The point whose segment holds arc length `sigma`: 0 at or before `s₀`,
/// `n+1` at or past `s_n`; between, segment `k → k+1` (direction `t_k`,
/// spanning `[arclen(k), arclen(k+1)]`).
pub(crate) fn segment_at(s: &[f64], sigma: f64) -> usize {
    let n = s.len() - 1;
    if sigma <= s[0] {
        return 0;
    }
    if sigma >= s[n] {
        return n + 1;
    }
    match s.binary_search_by(|x| x.total_cmp(&sigma)) {
        Ok(i) => i,
        Err(i) => {
            // sigma in (s[i-1], s[i]): segment i-1 covers up to (s[i-1]+s[i])/2,
            // segment i after (the clamp keeps a NaN inside the row)
            let i = i.clamp(1, n);
            if sigma < 0.5 * (s[i - 1] + s[i]) {
                i - 1
            } else {
                i
            }
        }
    }
}

/// Integrates and places one streamline so that its point at arc length
/// `sigma` is `origin`, writing `n+2` points into `out`.
pub fn place_into(tangents: &[DVec3], s: &[f64], sigma: f64, origin: DVec3, out: &mut Vec<DVec3>) {
    out.clear();
    out.resize(tangents.len() + 1, DVec3::ZERO);
    place_slice(tangents, s, sigma, origin, out);
}

/// [`place_into`] into a slice of exactly `n+2` points: the points up to the
/// anchor are summed once to find the shift, then Eq. 65 writes every point
/// already shifted (the same sums and the same shift, so the same bits as
/// integrating first and shifting after).
pub fn place_slice(tangents: &[DVec3], s: &[f64], sigma: f64, origin: DVec3, out: &mut [DVec3]) {
    let n = tangents.len() - 1;
    assert!(s.len() == n + 1 && out.len() == n + 2 && n >= 1);
    // the segment that holds σ (as in `point_at`), and its start point p_k
    let k = segment_at(s, sigma);
    let mut p = DVec3::ZERO;
    for i in 0..k {
        p += tangents[i] * (0.5 * (s[(i + 1).min(n)] - s[i.saturating_sub(1)]));
    }
    let anchor = if sigma <= s[0] {
        DVec3::ZERO + tangents[0] * (sigma - s[0])
    } else if sigma >= s[n] {
        p + tangents[n] * (sigma - s[n])
    } else {
        p + tangents[k] * (sigma - point_arclength(s, k))
    };
    integrate_shifted(tangents, s, origin - anchor, out);
}

/// [`place_slice`] after a change of the row's tangents from index `from`
/// on, `out` holding the row as placed before it (same `s`, σ and origin):
/// the points up to `from` do not move when the anchor's segment lies
/// before `from`, so only the points after it are summed again, with the
/// same bits as placing the whole row. Returns the first point rewritten
/// (`0`: the whole row, when the anchor reads a changed tangent or `from`
/// is 0).
pub fn place_slice_from(
    tangents: &[DVec3],
    s: &[f64],
    sigma: f64,
    origin: DVec3,
    from: usize,
    out: &mut [DVec3],
) -> usize {
    let n = tangents.len() - 1;
    assert!(s.len() == n + 1 && out.len() == n + 2 && n >= 1);
    // the anchor reads the tangents up to its segment's (all of them past s_n)
    if from == 0 || from > n || segment_at(s, sigma) >= from {
        place_slice(tangents, s, sigma, origin, out);
        return 0;
    }
    integrate_from(tangents, s, from, out);
    from + 1
}

/// The kernel's boundary for one streamline: validates and normalises the input,
/// then integrates with anchor column `anchor` placed at `origin` (the point at
/// arc length `s[anchor]` is `origin`).
pub fn streamline(
    tangents: &[DVec3],
    s: &[f64],
    anchor: usize,
    origin: DVec3,
) -> Result<Vec<DVec3>, KernelError> {
    let t = normalize_all(tangents)?;
    if t.len() < 2 {
        return Err(KernelError::TooFewTangents {
            what: "a streamline",
            got: t.len(),
            need: 2,
        });
    }
    if s.len() != t.len() {
        return Err(KernelError::LengthMismatch {
            what: "s",
            got: s.len(),
            expected: t.len(),
        });
    }
    for (i, &v) in s.iter().enumerate() {
        if !v.is_finite() {
            return Err(KernelError::NonFiniteParameter {
                what: "arc-length parameter s",
                at: Place::Curve(i),
            });
        }
        if i > 0 && v <= s[i - 1] {
            return Err(KernelError::ParamsNotIncreasing {
                level: 0,
                at: Place::Curve(i),
            });
        }
    }
    if anchor >= t.len() {
        return Err(KernelError::IndexOutOfRange {
            what: "anchor",
            index: anchor,
            len: t.len(),
        });
    }
    if !origin.is_finite() {
        return Err(KernelError::NonFiniteParameter {
            what: "origin",
            at: Place::Curve(0),
        });
    }
    let too_large = s
        .iter()
        .map(|&v| ("arc-length parameter s", v))
        .chain(origin.to_array().map(|v| ("origin", v)))
        .find(|(_, v)| !crate::limits::in_range(*v));
    if let Some((what, value)) = too_large {
        return Err(KernelError::TooLargeValue { what, value });
    }
    let mut out = Vec::with_capacity(t.len() + 2);
    place_into(&t, s, s[anchor], origin, &mut out);
    Ok(out)
}

/// Length of a polyline.
pub fn polyline_length(points: &[DVec3]) -> f64 {
    points.windows(2).map(|w| (w[1] - w[0]).length()).sum()
}

#[cfg(test)]
mod tests {
    fn wavy(k: usize, phase: f64) -> (Vec<DVec3>, Vec<f64>) {
        let t: Vec<DVec3> = (0..k)
            .map(|i| {
                let a = i as f64 * 0.4 + phase;
                DVec3::new(a.cos(), a.sin(), -0.3).normalize()
            })
            .collect();
        let s: Vec<f64> = (0..k)
            .map(|i| i as f64 * 0.7 + (i as f64 * 1.3).sin() * 0.2)
            .collect();
        (t, s)
    }

    #[test]
    fn placing_in_one_pass_is_integrating_then_shifting() {
        let (t, s) = wavy(9, 0.0);
        let origin = DVec3::new(-0.0, 2.5, 1e-3);
        for sigma in [-3.0, s[0], 0.1, 0.35, s[3], 2.9, s[8], 9.0, f64::NAN] {
            let mut plain = Vec::new();
            integrate_into(&t, &s, &mut plain);
            let shift = origin - point_at(&plain, &t, &s, sigma);
            let mut fast = vec![DVec3::ZERO; t.len() + 1];
            place_slice(&t, &s, sigma, origin, &mut fast);
            for (p, q) in plain.iter().zip(&fast) {
                // the shift rides in the sums: the same points up to rounding
                let want = *p + shift;
                assert!(
                    (want - *q).length() <= 1e-14 * (1.0 + want.length()) || want.is_nan(),
                    "sigma = {sigma}: {want} vs {q}"
                );
            }
        }
    }

    #[test]
    fn placing_from_a_column_is_placing_the_whole_row_bitwise() {
        let bits = |v: &[DVec3]| {
            v.iter()
                .map(|p| p.to_array().map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        let origin = DVec3::new(0.3, -1.0, 2.0);
        for k in [2, 3, 9] {
            let (t, s) = wavy(k, 0.0);
            let n = k - 1;
            let sigmas = [
                s[0] - 1.0,
                s[0],
                0.5 * (s[0] + s[1]),
                s[n / 2],
                s[n],
                s[n] + 1.0,
            ];
            for sigma in sigmas {
                for from in 0..=n + 1 {
                    // the row as placed before, then its tangents from `from` on turned
                    let mut row = vec![DVec3::ZERO; k + 1];
                    place_slice(&t, &s, sigma, origin, &mut row);
                    let (turned, _) = wavy(k, 0.9);
                    let mut t2 = t.clone();
                    t2[from.min(k)..].copy_from_slice(&turned[from.min(k)..]);
                    let mut whole = vec![DVec3::ZERO; k + 1];
                    place_slice(&t2, &s, sigma, origin, &mut whole);
                    let first = place_slice_from(&t2, &s, sigma, origin, from, &mut row);
                    assert_eq!(bits(&row), bits(&whole), "k {k} σ {sigma} from {from}");
                    let anchored_before = segment_at(&s, sigma) < from;
                    if from >= 1 && from <= n && anchored_before {
                        assert_eq!(first, from + 1, "k {k} σ {sigma} from {from}");
                        // the points up to `from` did not move
                        let mut old = vec![DVec3::ZERO; k + 1];
                        place_slice(&t, &s, sigma, origin, &mut old);
                        assert_eq!(bits(&old[..=from]), bits(&whole[..=from]));
                    } else {
                        assert_eq!(first, 0, "k {k} σ {sigma} from {from}");
                    }
                }
            }
        }
    }

    use super::*;

    #[test]
    fn streamline_length_is_s_range() {
        let t = [DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 1.0), DVec3::Z];
        let s = [0.0, 0.5, 2.0, 2.25];
        let p = streamline(&t, &s, 0, DVec3::ZERO).unwrap();
        assert_eq!(p.len(), 5, "4 tangents (n = 3) give n + 2 = 5 points");
        assert!((polyline_length(&p) - 2.25).abs() < 1e-14);
        let q = streamline(&t, &s, 2, DVec3::new(1.0, 2.0, 3.0)).unwrap();
        let mut raw = Vec::new();
        integrate_into(&normalize_all(&t).unwrap(), &s, &mut raw);
        let at = point_at(&q, &normalize_all(&t).unwrap(), &s, 2.0);
        assert!(
            (at - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-14,
            "anchor placed: {at:?}"
        );
    }
}
