//! The two hot loops of a surface build, four entries at a time: the 4-point
//! insert (Eq. 61) of the surface steps and the vertex normals of the mesh.
//!
//! AVX-512F (8 lanes) or AVX2 (4 lanes) on x86-64 CPUs that have them
//! (checked at run time: the default target is SSE2 only); the kernels are
//! written once (`kernels`) over the registers of `lanes`. Every lane does the scalar code's operations in the same
//! order (no fused multiply-add: the compiler never contracts), so results
//! are **bit for bit** the scalar results; lanes the vector code does not
//! cover (an insert past the series' range `h > FixedBlend::H_MAX` or with an
//! antipodal midpoint, a degenerate normal) are recomputed by the scalar code.
//! Elsewhere, and with [`set_limit`]`(Width::Scalar)`, everything is scalar.
//!
//! The insert is `mid(blend(a, b, (8+ω)/8), blend(c, d, −ω/8))` with the
//! trig-free blend of `crate::sphere::blend::FixedBlend`: `cos(uθ)` and
//! `sin(uθ)/sin θ` as series in `h = sin²(θ/2)`, with as many terms as the
//! lane's `h` needs (`crate::sphere::blend::TERM_THRESHOLDS`).

use crate::curve::scheme::FourPointRule;
use crate::sphere::blend::FixedBlend;
use glam::DVec3;
use std::sync::atomic::{AtomicU8, Ordering};

#[cfg(target_arch = "x86_64")]
mod kernels;
#[cfg(target_arch = "x86_64")]
mod lanes;

/// The 4-point rule a run of outputs takes: the interior insert
/// `mid(outer(a, b), inner(c, d))` (Eq. 61) or the 3-point end rule
/// `mid(¼(a, b), −¼(b, c))`, read as `[a, b, b, c]`.
#[derive(Clone, Copy)]
pub(crate) enum Rule4<'a> {
    Interior(&'a FourPointRule),
    End(&'a FourPointRule),
}

impl<'a> Rule4<'a> {
    /// The blends of the two halves.
    #[inline(always)]
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    pub(crate) fn blends(self) -> (&'a FixedBlend, &'a FixedBlend) {
        match self {
            Rule4::Interior(r) => (r.outer(), r.inner()),
            Rule4::End(r) => (r.quarter(), r.minus_quarter()),
        }
    }

    /// The scalar rule on `[a, b, c, d]` (for the lanes the vector code leaves).
    #[inline]
    fn scalar(self, [a, b, c, d]: [DVec3; 4]) -> DVec3 {
        match self {
            Rule4::Interior(r) => r.interior(a, b, c, d),
            Rule4::End(r) => r.end(a, b, d),
        }
    }
}

/// The vector paths, narrowest first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Width {
    /// No vector path: the scalar code.
    Scalar,
    /// AVX2, four lanes.
    Avx2,
    /// AVX-512F, eight lanes.
    Avx512,
}

static LIMIT: AtomicU8 = AtomicU8::new(Width::Avx512 as u8);

/// The widest path the CPU has.
pub(crate) fn cpu_width() -> Width {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx512f") {
            return Width::Avx512;
        }
        if std::is_x86_feature_detected!("avx2") {
            return Width::Avx2;
        }
    }
    Width::Scalar
}

/// The path the loops here take: the CPU's widest, within [`set_limit`].
/// Results are the same, bit for bit, on every path.
pub fn active() -> Width {
    let limit = match LIMIT.load(Ordering::Relaxed) {
        0 => Width::Scalar,
        1 => Width::Avx2,
        _ => Width::Avx512,
    };
    cpu_width().min(limit)
}

/// The widest path allowed (for benchmarks and tests that compare paths).
pub fn set_limit(w: Width) {
    LIMIT.store(w as u8, Ordering::Relaxed);
}

/// `out[k] = rule.interior(a[k], b[k], c[k], d[k])` for every `k` (the column
/// pass: four input rows, one output row). All slices have `out`'s length.
pub(crate) fn interior_across(rule: &FourPointRule, rows: [&[DVec3]; 4], out: &mut [DVec3]) {
    across_with(active(), Rule4::Interior(rule), rows, out);
}

/// `out[k] = rule.end(a[k], b[k], c[k])` for every `k` (the 3-point end rule
/// of the column pass). All slices have `out`'s length.
pub(crate) fn end_across(rule: &FourPointRule, [a, b, c]: [&[DVec3]; 3], out: &mut [DVec3]) {
    across_with(active(), Rule4::End(rule), [a, b, b, c], out);
}

/// [`interior_across`] or [`end_across`] on the path `width` (at most [`cpu_width`]).
fn across_with(width: Width, rule: Rule4<'_>, [a, b, c, d]: [&[DVec3]; 4], out: &mut [DVec3]) {
    assert!(width <= cpu_width());
    let n = out.len();
    assert!(a.len() == n && b.len() == n && c.len() == n && d.len() == n);
    // SAFETY: the CPU has the feature of `width` (asserted); the slices have
    // `n` entries each, and the kernels touch entries below n only.
    #[cfg(target_arch = "x86_64")]
    let done = unsafe {
        match width {
            Width::Avx512 => kernels::across_avx512(rule, [a, b, c, d], out),
            Width::Avx2 => kernels::across_avx2(rule, [a, b, c, d], out),
            Width::Scalar => 0,
        }
    };
    #[cfg(not(target_arch = "x86_64"))]
    let done = 0;
    for k in done..n {
        out[k] = rule.scalar([a[k], b[k], c[k], d[k]]);
    }
}

/// Whether `a[k] · b[k] ≥ th` for every `k` below both lengths, a NaN dot
/// product passed over (as `f64::min` passes it over): the test that rules
/// a row out of the antipodal scan (`crate::levels::antipodal`), on
/// [`active`]'s path.
pub(crate) fn dots_at_least(a: &[DVec3], b: &[DVec3], th: f64) -> bool {
    dots_at_least_with(active(), a, b, th)
}

/// [`dots_at_least`] on the path `width` (at most [`cpu_width`]).
fn dots_at_least_with(width: Width, a: &[DVec3], b: &[DVec3], th: f64) -> bool {
    assert!(width <= cpu_width());
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    // SAFETY: the CPU has the feature of `width` (asserted); the kernels read
    // entries below the slices' common length only.
    #[cfg(target_arch = "x86_64")]
    let (done, below) = unsafe {
        match width {
            Width::Avx512 => kernels::dots_avx512(a, b, th),
            Width::Avx2 => kernels::dots_avx2(a, b, th),
            Width::Scalar => (0, false),
        }
    };
    #[cfg(not(target_arch = "x86_64"))]
    let (done, below) = (0, false);
    // NaN passes (it is not below), as it does past `f64::min`
    !below && (done..n).all(|k| a[k].dot(b[k]).partial_cmp(&th) != Some(std::cmp::Ordering::Less))
}

/// `out[2i] = t[i]` and `out[2i + 1] = rule.interior(t[i−1], t[i], t[i+1],
/// t[i+2])` for `i` in `lo ..= hi` (the row pass of the 4-point scheme: the
/// copies and inserts along one row). Needs `1 ≤ lo`, `hi + 2 < t.len()` and
/// `2 hi + 1 < out.len()`.
pub(crate) fn interior_along(
    rule: &FourPointRule,
    t: &[DVec3],
    lo: usize,
    hi: usize,
    out: &mut [DVec3],
) {
    along_with(active(), rule, t, lo, hi, out);
}

/// [`interior_along`] on the path `width` (at most [`cpu_width`]).
fn along_with(
    width: Width,
    rule: &FourPointRule,
    t: &[DVec3],
    lo: usize,
    hi: usize,
    out: &mut [DVec3],
) {
    assert!(width <= cpu_width());
    if hi < lo {
        return;
    }
    assert!(lo >= 1 && hi + 2 < t.len() && 2 * hi + 1 < out.len());
    // SAFETY: the CPU has the feature of `width` (asserted); the bounds were
    // asserted above, and the kernels read t[i−1 ..= i+N+1] only for
    // i + N − 1 ≤ hi.
    #[cfg(target_arch = "x86_64")]
    let next = unsafe {
        match width {
            Width::Avx512 => kernels::along_avx512(rule, t, lo, hi, out),
            Width::Avx2 => kernels::along_avx2(rule, t, lo, hi, out),
            Width::Scalar => lo,
        }
    };
    #[cfg(not(target_arch = "x86_64"))]
    let next = lo;
    for i in next..=hi {
        out[2 * i] = t[i];
        out[2 * i + 1] = rule.interior(t[i - 1], t[i], t[i + 1], t[i + 2]);
    }
}

/// The unit normal of the point grid at column `c` of the row `here`
/// (docs/math.md §4): `∂/∂s × ∂/∂t` by central differences, one-sided at the ends;
/// a degenerate point takes `last`, the normal before it (never NaN).
#[inline]
#[cfg(test)]
pub(crate) fn normal_at(
    above: &[DVec3],
    here: &[DVec3],
    below: &[DVec3],
    c: usize,
    last: DVec3,
) -> DVec3 {
    unit_normal(above, here, below, c).unwrap_or(last)
}

/// [`normal_at`] without the fallback: `None` at a degenerate point.
#[inline]
fn unit_normal(above: &[DVec3], here: &[DVec3], below: &[DVec3], c: usize) -> Option<DVec3> {
    let cols = here.len();
    let (c0, c1) = (c.saturating_sub(1), (c + 1).min(cols - 1));
    let ds = here[c1] - here[c0];
    let dt = below[c] - above[c];
    let n = ds.cross(dt);
    let len2 = n.length_squared();
    (len2 > 0.0 && len2.is_finite()).then(|| n * (1.0 / len2.sqrt()))
}

/// The normal carried into a degenerate point: the one written before it.
/// Cold, so that the loop branches instead of making every normal wait for
/// the previous one's square root.
#[cold]
fn carried(out: &[DVec3], c: usize) -> DVec3 {
    if c == 0 { DVec3::Z } else { out[c - 1] }
}

/// The normals of rows `lo ..= hi`, columns `c0 ..`, of the row-major point
/// grid `points` (`cols` wide) into `out`, which holds those rows:
/// [`normal_at`] for every point, `N` at a time on a vector path. The other
/// columns of `out` are kept (a normal carried into a degenerate point at
/// `c0` is read there).
pub(crate) fn normals_rows(
    points: &[DVec3],
    cols: usize,
    lo: usize,
    hi: usize,
    c0: usize,
    out: &mut [DVec3],
) {
    normals_with(active(), points, cols, lo, hi, c0, out);
}

/// [`normals_rows`] on the path `width` (at most [`cpu_width`]).
fn normals_with(
    width: Width,
    points: &[DVec3],
    cols: usize,
    lo: usize,
    hi: usize,
    c0: usize,
    out: &mut [DVec3],
) {
    assert!(width <= cpu_width());
    if cols == 0 || hi < lo || c0 >= cols {
        return;
    }
    let rows = points.len() / cols;
    assert!(points.len() == rows * cols && hi < rows && out.len() == (hi - lo + 1) * cols);
    #[cfg(target_arch = "x86_64")]
    if width != Width::Scalar {
        thread_local! {
            static RING: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
        }
        RING.with(|ring| {
            let mut ring = ring.borrow_mut();
            ring.resize(9 * cols, 0.0);
            // SAFETY: the CPU has the feature of `width` (asserted); the sizes
            // were asserted above and `ring` holds 9 · cols doubles.
            unsafe {
                match width {
                    Width::Avx512 => {
                        kernels::normals_avx512(points, cols, lo, hi, c0, out, &mut ring)
                    }
                    _ => kernels::normals_avx2(points, cols, lo, hi, c0, out, &mut ring),
                }
            }
        });
        return;
    }
    let row = |q: usize| &points[q * cols..(q + 1) * cols];
    for (r, o) in (lo..=hi).zip(out.chunks_mut(cols)) {
        let (above, here, below) = (row(r.saturating_sub(1)), row(r), row((r + 1).min(rows - 1)));
        for c in c0..cols {
            o[c] = match unit_normal(above, here, below, c) {
                Some(n) => n,
                None => carried(o, c),
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every path this CPU has.
    fn widths() -> Vec<Width> {
        [Width::Scalar, Width::Avx2, Width::Avx512]
            .into_iter()
            .filter(|&w| w <= cpu_width())
            .collect()
    }

    fn wobble(n: usize, seed: f64, spread: f64) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = i as f64 * spread + seed;
                DVec3::new(a.cos(), a.sin(), (0.7 * a + seed).sin() * 0.5).normalize()
            })
            .collect()
    }

    /// The antipodal scan's row test on every path equals the fold of
    /// `f64::min` over the dot products (NaN passed over, `+∞` when empty)
    /// compared with the threshold: pairs 120° and 90° apart, antipodal,
    /// NaN, infinite and zero vectors, at every position of a run of up to
    /// 41 (both tails of the vector part).
    #[test]
    fn the_scan_test_is_the_fold_of_min_on_every_path() {
        let odd = [
            DVec3::new(-0.5, 3f64.sqrt() / 2.0, 0.0), // 120° from x: dot −0.5
            DVec3::Y,
            -DVec3::X,
            DVec3::new(f64::NAN, 0.0, 0.0),
            DVec3::new(f64::INFINITY, 0.0, 0.0),
            DVec3::new(f64::NEG_INFINITY, 1.0, 0.0),
            DVec3::ZERO,
            DVec3::new(-0.5000001, 0.8660254, 0.0),
        ];
        for n in [0, 1, 3, 4, 7, 8, 9, 15, 16, 17, 41] {
            let a: Vec<DVec3> = (0..n)
                .map(|i| DVec3::new(1.0, 0.0, 1e-3 * i as f64).normalize())
                .collect();
            for at in 0..n.max(1) {
                for (k, v) in odd.iter().enumerate() {
                    let mut b = a.clone();
                    if n > 0 {
                        b[at] = *v;
                    }
                    // a second odd entry further on, now and then
                    if n > 2 && k % 3 == 0 {
                        b[(at + n / 2) % n] = odd[(k + 3) % odd.len()];
                    }
                    for th in [-0.5, 0.0, -1.0, 1.0] {
                        let min = (a.iter().zip(&b))
                            .map(|(x, y)| x.dot(*y))
                            .fold(f64::INFINITY, f64::min);
                        let want = min >= th;
                        for width in widths() {
                            assert_eq!(
                                dots_at_least_with(width, &a, &b, th),
                                want,
                                "{width:?}: n {n}, entry {at} = {v:?}, threshold {th}"
                            );
                            // a longer second slice: the common length counts
                            let mut longer = b.clone();
                            longer.push(-DVec3::X);
                            assert_eq!(dots_at_least_with(width, &a, &longer, th), want);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn vector_normals_are_bitwise_scalar() {
        for cols in [2, 5, 9, 14, 31, 40] {
            let rows = 5;
            let mut points: Vec<DVec3> = (0..rows * cols)
                .map(|i| {
                    let (r, c) = ((i / cols) as f64, (i % cols) as f64);
                    let a = c * 0.37 + r;
                    DVec3::new(c, (a * 1.3).sin() * r, a.cos() + r * 0.9)
                })
                .collect();
            if cols > 6 {
                points[2 * cols + 6] = points[6]; // row 1's dt = 0 at column 6: degenerate
            }
            let mut plain = vec![DVec3::ZERO; rows * cols];
            normals_with(Width::Scalar, &points, cols, 0, rows - 1, 0, &mut plain);
            for r in 0..rows {
                let row = |q: usize| &points[q * cols..(q + 1) * cols];
                let mut last = DVec3::Z;
                for c in 0..cols {
                    let (a, b) = (row(r.saturating_sub(1)), row((r + 1).min(rows - 1)));
                    last = normal_at(a, row(r), b, c, last);
                    assert_eq!(
                        plain[r * cols + c],
                        last,
                        "scalar {cols} columns, ({r}, {c})"
                    );
                }
            }
            for width in widths() {
                // all rows, then rows 1 ..= 3 alone
                let mut fast = vec![DVec3::ZERO; rows * cols];
                normals_with(width, &points, cols, 0, rows - 1, 0, &mut fast);
                assert_eq!(fast, plain, "{width:?}: {cols} columns");
                let mut part = vec![DVec3::ZERO; 3 * cols];
                normals_with(width, &points, cols, 1, 3, 0, &mut part);
                assert_eq!(part[..], plain[cols..4 * cols], "{width:?}: rows 1–3");
                // from a column on: those columns written, the others kept
                for c0 in [1, 5, 6, 7, cols - 1, cols] {
                    let marker = DVec3::new(9.0, 9.0, 9.0);
                    let mut tail: Vec<DVec3> = plain[cols..4 * cols].to_vec();
                    for row in tail.chunks_mut(cols) {
                        row[c0.min(cols)..].fill(marker);
                    }
                    normals_with(width, &points, cols, 1, 3, c0, &mut tail);
                    assert_eq!(
                        tail[..],
                        plain[cols..4 * cols],
                        "{width:?}: rows 1–3 from {c0}"
                    );
                }
            }
        }
    }

    #[test]
    fn vector_path_is_bitwise_scalar() {
        let rule = FourPointRule::new(1.0);
        // spreads from 1e-9 rad (2 terms) to 1.3 rad (past the series: scalar redo)
        for (s, spread) in [1e-9, 1e-5, 3e-3, 0.02, 0.1, 0.3, 0.7, 1.3, 3.0]
            .into_iter()
            .enumerate()
        {
            let t = wobble(45, s as f64, spread);
            let mut mixed = wobble(45, 0.5, spread);
            mixed[5] = -mixed[6]; // an antipodal pair inside a run
            for src in [&t, &mixed] {
                let n = src.len() - 3;
                let (a, b, c, d) = (&src[0..n], &src[1..n + 1], &src[2..n + 2], &src[3..n + 3]);
                for width in widths() {
                    let mut v = vec![DVec3::ZERO; n];
                    across_with(width, Rule4::Interior(&rule), [a, b, c, d], &mut v);
                    let mut e = vec![DVec3::ZERO; n];
                    across_with(width, Rule4::End(&rule), [a, b, b, c], &mut e);
                    for k in 0..n {
                        let want = rule.end(a[k], b[k], c[k]);
                        assert_eq!(e[k], want, "{width:?} end spread {spread} k {k}");
                    }
                    let mut w = vec![DVec3::ZERO; 2 * src.len()];
                    along_with(width, &rule, src, 1, src.len() - 3, &mut w);
                    for k in 0..n {
                        let want = rule.interior(a[k], b[k], c[k], d[k]);
                        assert_eq!(v[k], want, "{width:?} across spread {spread} k {k}");
                        assert_eq!(w[2 * k + 3], want, "{width:?} along spread {spread} k {k}");
                        assert_eq!(w[2 * k + 2], src[k + 1], "{width:?} along copy k {k}");
                    }
                }
            }
        }
    }
}
