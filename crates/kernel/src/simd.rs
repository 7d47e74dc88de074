//! The two hot loops of a surface build, four entries at a time: the 4-point
//! insert (Eq. 61) of the surface steps and the vertex normals of the mesh.
//!
//! AVX2 on x86-64 CPUs that have it (checked at run time: the default target
//! is SSE2 only). Every lane does the scalar code's operations in the same
//! order (no fused multiply-add: the compiler never contracts), so results
//! are **bit for bit** the scalar results; lanes the vector code does not
//! cover (an insert past the series' range `h > FixedBlend::H_MAX` or with an
//! antipodal midpoint, a degenerate normal) are recomputed by the scalar code.
//! Elsewhere, and after [`set_enabled`]`(false)`, everything is scalar.
//!
//! The insert is `mid(blend(a, b, (8+ω)/8), blend(c, d, −ω/8))` with the
//! trig-free blend of [`crate::sphere::FixedBlend`]: `cos(uθ)` and
//! `sin(uθ)/sin θ` as series in `h = sin²(θ/2)`, with as many terms as the
//! lane's `h` needs ([`crate::sphere::TERM_THRESHOLDS`]).

use crate::curve::FourPointRule;
use glam::DVec3;
use std::sync::atomic::{AtomicBool, Ordering};

static ENABLED: AtomicBool = AtomicBool::new(true);

/// Whether the loops here use the vector path (the CPU has AVX2 and it is
/// not switched off). Results are the same either way.
pub fn active() -> bool {
    ENABLED.load(Ordering::Relaxed) && cpu_has_avx2()
}

/// Switches the vector path on or off (for benchmarks and tests that compare
/// the two; the results are bitwise equal).
pub fn set_enabled(on: bool) {
    ENABLED.store(on, Ordering::Relaxed);
}

fn cpu_has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// `out[k] = rule.interior(a[k], b[k], c[k], d[k])` for every `k` (the column
/// pass: four input rows, one output row). All slices have `out`'s length.
pub fn interior_across(rule: &FourPointRule, [a, b, c, d]: [&[DVec3]; 4], out: &mut [DVec3]) {
    let n = out.len();
    assert!(a.len() == n && b.len() == n && c.len() == n && d.len() == n);
    #[allow(unused_mut)]
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if active() {
        // SAFETY: AVX2 was detected; the slices have `n` entries each and the
        // vector path touches entries `0 .. n − n % 4` only.
        done = unsafe { x86::across(rule, [a, b, c, d], out) };
    }
    for k in done..n {
        out[k] = rule.interior(a[k], b[k], c[k], d[k]);
    }
}

/// `out[2i + 1] = rule.interior(t[i−1], t[i], t[i+1], t[i+2])` for `i` in
/// `lo ..= hi` (the row pass: inserts along one row). Needs `1 ≤ lo`,
/// `hi + 2 < t.len()` and `2 hi + 1 < out.len()`.
pub fn interior_along(rule: &FourPointRule, t: &[DVec3], lo: usize, hi: usize, out: &mut [DVec3]) {
    if hi < lo {
        return;
    }
    assert!(lo >= 1 && hi + 2 < t.len() && 2 * hi + 1 < out.len());
    #[allow(unused_mut)]
    let mut next = lo;
    #[cfg(target_arch = "x86_64")]
    if active() {
        // SAFETY: AVX2 was detected; the bounds were asserted above and the
        // vector path reads `t[i−1 ..= i+5]` only for `i + 3 ≤ hi`.
        next = unsafe { x86::along(rule, t, lo, hi, out) };
    }
    for i in next..=hi {
        out[2 * i + 1] = rule.interior(t[i - 1], t[i], t[i + 1], t[i + 2]);
    }
}

/// The unit normal of the point grid at column `c` of the row `here`
/// (SPEC §4): `∂/∂s × ∂/∂t` by central differences, one-sided at the ends;
/// a degenerate point takes `last`, the normal before it (never NaN).
#[inline]
pub fn normal_at(above: &[DVec3], here: &[DVec3], below: &[DVec3], c: usize, last: DVec3) -> DVec3 {
    let cols = here.len();
    let (c0, c1) = (c.saturating_sub(1), (c + 1).min(cols - 1));
    let ds = here[c1] - here[c0];
    let dt = below[c] - above[c];
    let n = ds.cross(dt);
    let len2 = n.length_squared();
    if len2 > 0.0 && len2.is_finite() {
        n * (1.0 / len2.sqrt())
    } else {
        last
    }
}

/// The normals of one row of the point grid into `out`: [`normal_at`] for
/// every column, four at a time where the vector path is active.
pub fn normals_row(above: &[DVec3], here: &[DVec3], below: &[DVec3], out: &mut [DVec3]) {
    let cols = here.len();
    assert!(above.len() == cols && below.len() == cols && out.len() == cols);
    let vector = active();
    let mut last = DVec3::Z;
    let mut c = 0;
    while c < cols {
        // columns c ..= c+3 with both neighbours inside the row
        if vector && c >= 1 && c + 4 < cols {
            #[cfg(target_arch = "x86_64")]
            {
                // SAFETY: AVX2 was detected; reads columns c−1 ..= c+4 < cols
                // of `here` and c ..= c+3 of the others, writes out[c ..= c+3].
                if unsafe { x86::normals4(above, here, below, c, out) } {
                    last = out[c + 3];
                    c += 4;
                    continue;
                }
            }
        }
        last = normal_at(above, here, below, c, last);
        out[c] = last;
        c += 1;
    }
}

#[cfg(target_arch = "x86_64")]
mod x86 {
    use crate::curve::FourPointRule;
    use crate::sphere::{FixedBlend, MID_MIN_NORM2, TERM_THRESHOLDS, terms_for};
    use glam::DVec3;
    use std::arch::x86_64::*;

    /// Four tangents, one coordinate per register.
    #[derive(Clone, Copy)]
    struct V3 {
        x: __m256d,
        y: __m256d,
        z: __m256d,
    }

    /// Four consecutive `DVec3`s (12 doubles) at `p`, split into coordinates.
    ///
    /// # Safety
    /// `p .. p + 4` must be readable; AVX2 must be present.
    #[inline(always)]
    unsafe fn load4(p: *const DVec3) -> V3 {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            let f = p.cast::<f64>();
            // the caller guarantees 12 readable doubles (DVec3 is repr(C))
            let (v0, v1, v2) = (
                _mm256_loadu_pd(f),
                _mm256_loadu_pd(f.add(4)),
                _mm256_loadu_pd(f.add(8)),
            );
            // v0 = [x0 y0 | z0 x1], v1 = [y1 z1 | x2 y2], v2 = [z2 x3 | y3 z3]
            let p = _mm256_permute2f128_pd(v0, v1, 0x30); // [x0 y0 | x2 y2]
            let q = _mm256_permute2f128_pd(v0, v2, 0x21); // [z0 x1 | z2 x3]
            let r = _mm256_permute2f128_pd(v1, v2, 0x30); // [y1 z1 | y3 z3]
            V3 {
                x: _mm256_blend_pd(p, q, 0b1010),
                y: _mm256_shuffle_pd(p, r, 0b0101),
                z: _mm256_blend_pd(q, r, 0b1010),
            }
        }
    }

    /// The inverse of [`load4`]: four `DVec3`s written at `p`.
    ///
    /// # Safety
    /// `p .. p + 4` must be writable; AVX2 must be present.
    #[inline(always)]
    unsafe fn store4(p: *mut DVec3, v: V3) {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            let pp = _mm256_shuffle_pd(v.x, v.y, 0b0000); // [x0 y0 | x2 y2]
            let q = _mm256_shuffle_pd(v.z, v.x, 0b1010); // [z0 x1 | z2 x3]
            let r = _mm256_shuffle_pd(v.y, v.z, 0b1111); // [y1 z1 | y3 z3]
            let f = p.cast::<f64>();
            // the caller guarantees 12 writable doubles
            _mm256_storeu_pd(f, _mm256_permute2f128_pd(pp, q, 0x20));
            _mm256_storeu_pd(f.add(4), _mm256_permute2f128_pd(r, pp, 0x30));
            _mm256_storeu_pd(f.add(8), _mm256_permute2f128_pd(q, r, 0x31));
        }
    }

    #[inline(always)]
    unsafe fn lanes(v: __m256d) -> [f64; 4] {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            let mut out = [0.0; 4];
            _mm256_storeu_pd(out.as_mut_ptr(), v); // `out` holds four doubles
            out
        }
    }

    #[inline(always)]
    unsafe fn dot(a: V3, b: V3) -> __m256d {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            // glam's order: (x·x + y·y) + z·z
            _mm256_add_pd(
                _mm256_add_pd(_mm256_mul_pd(a.x, b.x), _mm256_mul_pd(a.y, b.y)),
                _mm256_mul_pd(a.z, b.z),
            )
        }
    }

    /// `a − b` lane by lane.
    #[inline(always)]
    unsafe fn sub3(a: V3, b: V3) -> V3 {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            V3 {
                x: _mm256_sub_pd(a.x, b.x),
                y: _mm256_sub_pd(a.y, b.y),
                z: _mm256_sub_pd(a.z, b.z),
            }
        }
    }

    /// `h = |a − b|²/4` lane by lane, as [`FixedBlend::apply`] computes it.
    #[inline(always)]
    unsafe fn half_chord2(a: V3, b: V3) -> __m256d {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            let d = sub3(a, b);
            _mm256_mul_pd(_mm256_set1_pd(0.25), dot(d, d))
        }
    }

    /// Whether every lane's `h` takes exactly [`BAND_TERMS`] series terms.
    #[inline(always)]
    unsafe fn in_band(h: __m256d) -> __m256d {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            _mm256_and_pd(
                _mm256_cmp_pd::<_CMP_GE_OQ>(h, _mm256_set1_pd(TERM_THRESHOLDS[BAND_TERMS - 1])),
                _mm256_cmp_pd::<_CMP_LT_OQ>(h, _mm256_set1_pd(TERM_THRESHOLDS[BAND_TERMS])),
            )
        }
    }

    /// The series terms of the band where the finer levels' neighbours sit.
    const BAND_TERMS: usize = 6;

    /// The two series (`cos uθ`, `sin uθ / sin θ`) with [`BAND_TERMS`] terms
    /// in every lane: straight-line Horner, so both blends of an insert overlap.
    #[inline(always)]
    unsafe fn series_band(fb: &FixedBlend, h: __m256d) -> (__m256d, __m256d) {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            let (cc, sc) = fb.coefficients();
            let mut cu = _mm256_set1_pd(cc[BAND_TERMS - 1]);
            let mut su = _mm256_set1_pd(sc[BAND_TERMS - 1]);
            for k in (0..BAND_TERMS - 1).rev() {
                cu = _mm256_add_pd(_mm256_mul_pd(cu, h), _mm256_set1_pd(cc[k]));
                su = _mm256_add_pd(_mm256_mul_pd(su, h), _mm256_set1_pd(sc[k]));
            }
            (cu, su)
        }
    }

    /// The two series with each lane's own number of terms ([`terms_for`]).
    #[inline(always)]
    unsafe fn series_any(fb: &FixedBlend, h: __m256d) -> (__m256d, __m256d) {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            // the lanes' smallest and largest h
            let swap = _mm256_permute2f128_pd(h, h, 0x01);
            let (lo2, hi2) = (_mm256_min_pd(h, swap), _mm256_max_pd(h, swap));
            let lo = lanes(_mm256_min_pd(lo2, _mm256_permute_pd(lo2, 0b0101)))[0];
            let hi = lanes(_mm256_max_pd(hi2, _mm256_permute_pd(hi2, 0b0101)))[0];
            let (n_lo, n_hi) = (terms_for(lo), terms_for(hi));
            let (cc, sc) = fb.coefficients();
            let (mut cu, mut su);
            if n_lo == n_hi {
                // every lane takes the same number of terms: plain Horner
                cu = _mm256_set1_pd(cc[n_hi - 1]);
                su = _mm256_set1_pd(sc[n_hi - 1]);
                for k in (0..n_hi - 1).rev() {
                    cu = _mm256_add_pd(_mm256_mul_pd(cu, h), _mm256_set1_pd(cc[k]));
                    su = _mm256_add_pd(_mm256_mul_pd(su, h), _mm256_set1_pd(sc[k]));
                }
            } else {
                // a lane starts when k < its term count; before that it holds +0,
                // and 0·h + c = c exactly, so each lane is the scalar Horner sum
                cu = _mm256_setzero_pd();
                su = _mm256_setzero_pd();
                for k in (0..n_hi).rev() {
                    let on = _mm256_cmp_pd::<_CMP_GE_OQ>(h, _mm256_set1_pd(TERM_THRESHOLDS[k]));
                    cu = _mm256_and_pd(
                        on,
                        _mm256_add_pd(_mm256_mul_pd(cu, h), _mm256_set1_pd(cc[k])),
                    );
                    su = _mm256_and_pd(
                        on,
                        _mm256_add_pd(_mm256_mul_pd(su, h), _mm256_set1_pd(sc[k])),
                    );
                }
            }
            (cu, su)
        }
    }

    /// The end of [`FixedBlend::apply`]: `a (cu − c·su) + b·su`, `c = 1 − 2h`.
    #[inline(always)]
    unsafe fn combine(a: V3, b: V3, h: __m256d, (cu, su): (__m256d, __m256d)) -> V3 {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            let c = _mm256_sub_pd(_mm256_set1_pd(1.0), _mm256_mul_pd(_mm256_set1_pd(2.0), h));
            let wa = _mm256_sub_pd(cu, _mm256_mul_pd(c, su));
            V3 {
                x: _mm256_add_pd(_mm256_mul_pd(a.x, wa), _mm256_mul_pd(b.x, su)),
                y: _mm256_add_pd(_mm256_mul_pd(a.y, wa), _mm256_mul_pd(b.y, su)),
                z: _mm256_add_pd(_mm256_mul_pd(a.z, wa), _mm256_mul_pd(b.z, su)),
            }
        }
    }

    /// [`crate::sphere::mid`] on four lanes; antipodal lanes are flagged.
    #[inline(always)]
    unsafe fn mid(a: V3, b: V3, bad: &mut __m256d) -> V3 {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        unsafe {
            let m = V3 {
                x: _mm256_add_pd(a.x, b.x),
                y: _mm256_add_pd(a.y, b.y),
                z: _mm256_add_pd(a.z, b.z),
            };
            let n2 = dot(m, m);
            *bad = _mm256_or_pd(
                *bad,
                _mm256_cmp_pd::<_CMP_NGT_UQ>(n2, _mm256_set1_pd(MID_MIN_NORM2)),
            );
            let inv = _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_sqrt_pd(n2));
            V3 {
                x: _mm256_mul_pd(m.x, inv),
                y: _mm256_mul_pd(m.y, inv),
                z: _mm256_mul_pd(m.z, inv),
            }
        }
    }

    /// `G` groups of four inserts (`q[g] = [a, b, c, d]`); returns them and,
    /// per group, the mask of lanes to redo in scalar (an `h` past
    /// [`FixedBlend::H_MAX`], an antipodal midpoint). With every lane in the
    /// series band the groups run as one straight line of independent chains,
    /// which the CPU overlaps (one group alone waits on its Horner sums and
    /// its square root).
    #[inline(always)]
    unsafe fn interior<const G: usize>(
        rule: &FourPointRule,
        q: [[V3; 4]; G],
    ) -> ([V3; G], [i32; G]) {
        // SAFETY: AVX2 is enabled in every caller (the `avx2` entry points).
        // (No closures here: a closure would not inherit the target feature.)
        unsafe {
            let limit = _mm256_set1_pd(FixedBlend::H_MAX);
            let zero = _mm256_setzero_pd();
            let mut h = [(zero, zero); G];
            let mut bad = [zero; G];
            let mut band = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
            for g in 0..G {
                let [a, b, c, d] = q[g];
                let (h1, h2) = (half_chord2(a, b), half_chord2(c, d));
                h[g] = (h1, h2);
                bad[g] = _mm256_or_pd(
                    _mm256_cmp_pd::<_CMP_NLE_UQ>(h1, limit),
                    _mm256_cmp_pd::<_CMP_NLE_UQ>(h2, limit),
                );
                band = _mm256_and_pd(band, _mm256_and_pd(in_band(h1), in_band(h2)));
            }
            let (outer, inner) = (rule.outer(), rule.inner());
            let mut series = [((zero, zero), (zero, zero)); G];
            if _mm256_movemask_pd(band) == 0b1111 {
                for g in 0..G {
                    series[g] = (series_band(outer, h[g].0), series_band(inner, h[g].1));
                }
            } else {
                for g in 0..G {
                    series[g] = (series_any(outer, h[g].0), series_any(inner, h[g].1));
                }
            }
            let mut out = [q[0][0]; G];
            let mut redo = [0; G];
            for g in 0..G {
                let [a, b, c, d] = q[g];
                let ((h1, h2), (s1, s2)) = (h[g], series[g]);
                out[g] = mid(combine(a, b, h1, s1), combine(c, d, h2, s2), &mut bad[g]);
                redo[g] = _mm256_movemask_pd(bad[g]);
            }
            (out, redo)
        }
    }

    /// `[a, b, c, d]`: four tangents from each of four rows at entry `k`.
    ///
    /// # Safety
    /// Entries `k .. k + 4` of each pointer must be readable.
    #[inline(always)]
    unsafe fn quad([a, b, c, d]: [*const DVec3; 4], k: usize) -> [V3; 4] {
        // SAFETY: AVX2 is enabled in every caller; the caller checks the bounds.
        unsafe {
            [
                load4(a.add(k)),
                load4(b.add(k)),
                load4(c.add(k)),
                load4(d.add(k)),
            ]
        }
    }

    /// Normals of columns `c ..= c+3` (all with both neighbours) into `out`;
    /// `false`, writing nothing, when one of them is degenerate (the scalar
    /// code then carries the previous normal forward).
    ///
    /// # Safety
    /// AVX2 must be present; `1 ≤ c`, `c + 4 < here.len()`, all rows as long.
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn normals4(
        above: &[DVec3],
        here: &[DVec3],
        below: &[DVec3],
        c: usize,
        out: &mut [DVec3],
    ) -> bool {
        // SAFETY: the bounds above keep every load and store inside the rows.
        unsafe {
            let ds = sub3(
                load4(here.as_ptr().add(c + 1)),
                load4(here.as_ptr().add(c - 1)),
            );
            let dt = sub3(load4(below.as_ptr().add(c)), load4(above.as_ptr().add(c)));
            // glam's cross: (y·z' − y'·z, z·x' − z'·x, x·y' − x'·y)
            let n = V3 {
                x: _mm256_sub_pd(_mm256_mul_pd(ds.y, dt.z), _mm256_mul_pd(dt.y, ds.z)),
                y: _mm256_sub_pd(_mm256_mul_pd(ds.z, dt.x), _mm256_mul_pd(dt.z, ds.x)),
                z: _mm256_sub_pd(_mm256_mul_pd(ds.x, dt.y), _mm256_mul_pd(dt.x, ds.y)),
            };
            let len2 = dot(n, n);
            let ok = _mm256_and_pd(
                _mm256_cmp_pd::<_CMP_GT_OQ>(len2, _mm256_setzero_pd()),
                _mm256_cmp_pd::<_CMP_LT_OQ>(len2, _mm256_set1_pd(f64::INFINITY)),
            );
            if _mm256_movemask_pd(ok) != 0b1111 {
                return false;
            }
            let inv = _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_sqrt_pd(len2));
            store4(
                out.as_mut_ptr().add(c),
                V3 {
                    x: _mm256_mul_pd(n.x, inv),
                    y: _mm256_mul_pd(n.y, inv),
                    z: _mm256_mul_pd(n.z, inv),
                },
            );
            true
        }
    }

    /// The vector part of [`super::interior_across`]; returns how many
    /// entries it wrote (a multiple of 4).
    ///
    /// # Safety
    /// AVX2 must be present; all slices as long as `out`.
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn across(
        rule: &FourPointRule,
        [a, b, c, d]: [&[DVec3]; 4],
        out: &mut [DVec3],
    ) -> usize {
        let n = out.len() - out.len() % 4;
        let rows = [a.as_ptr(), b.as_ptr(), c.as_ptr(), d.as_ptr()];
        let mut k = 0;
        while k < n {
            // two groups while eight entries are left, then one
            let g = if k + 8 <= n { 2 } else { 1 };
            // SAFETY: AVX2 is enabled here; k + 4g ≤ n ≤ every slice's length.
            let (r, redo) = unsafe {
                if g == 2 {
                    interior::<2>(rule, [quad(rows, k), quad(rows, k + 4)])
                } else {
                    let (r, redo) = interior::<1>(rule, [quad(rows, k)]);
                    ([r[0], r[0]], [redo[0], 0])
                }
            };
            for j in 0..g {
                let k = k + 4 * j;
                // SAFETY: k + 4 ≤ n ≤ out.len().
                unsafe { store4(out.as_mut_ptr().add(k), r[j]) };
                for l in 0..4 {
                    if redo[j] & (1 << l) != 0 {
                        let e = k + l;
                        out[e] = rule.interior(a[e], b[e], c[e], d[e]);
                    }
                }
            }
            k += 4 * g;
        }
        n
    }

    /// The vector part of [`super::interior_along`]; returns the first `i` it
    /// did not do.
    ///
    /// # Safety
    /// AVX2 must be present; the bounds of [`super::interior_along`] hold.
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn along(
        rule: &FourPointRule,
        t: &[DVec3],
        lo: usize,
        hi: usize,
        out: &mut [DVec3],
    ) -> usize {
        let p = t.as_ptr();
        // inserts i .. i+3 read t[i−1 ..= i+5]
        let rows = [p.wrapping_sub(1), p, p.wrapping_add(1), p.wrapping_add(2)];
        let mut i = lo;
        while i + 3 <= hi {
            let g = if i + 7 <= hi { 2 } else { 1 };
            // SAFETY: AVX2 is enabled here; i ≥ 1 and the last read,
            // t[i + 4g + 1], has i + 4g + 1 ≤ hi + 2 < t.len().
            let (r, redo) = unsafe {
                if g == 2 {
                    interior::<2>(rule, [quad(rows, i), quad(rows, i + 4)])
                } else {
                    let (r, redo) = interior::<1>(rule, [quad(rows, i)]);
                    ([r[0], r[0]], [redo[0], 0])
                }
            };
            for j in 0..g {
                let i = i + 4 * j;
                // SAFETY: AVX2 is enabled here.
                let (x, y, z) = unsafe { (lanes(r[j].x), lanes(r[j].y), lanes(r[j].z)) };
                for l in 0..4 {
                    let e = i + l;
                    out[2 * e + 1] = if redo[j] & (1 << l) != 0 {
                        rule.interior(t[e - 1], t[e], t[e + 1], t[e + 2])
                    } else {
                        DVec3::new(x[l], y[l], z[l])
                    };
                }
            }
            i += 4 * g;
        }
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wobble(n: usize, seed: f64, spread: f64) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = i as f64 * spread + seed;
                DVec3::new(a.cos(), a.sin(), (0.7 * a + seed).sin() * 0.5).normalize()
            })
            .collect()
    }

    #[test]
    fn vector_normals_are_bitwise_scalar() {
        for cols in [2, 5, 9, 14, 31] {
            let row = |r: f64| -> Vec<DVec3> {
                (0..cols)
                    .map(|c| {
                        let a = c as f64 * 0.37 + r;
                        DVec3::new(c as f64, (a * 1.3).sin() * r, a.cos() + r * 0.9)
                    })
                    .collect()
            };
            let (above, here, mut below) = (row(0.0), row(1.0), row(2.0));
            if cols > 6 {
                below[6] = above[6]; // dt = 0: a degenerate normal
            }
            let mut fast = vec![DVec3::ZERO; cols];
            normals_row(&above, &here, &below, &mut fast);
            let mut last = DVec3::Z;
            for (c, got) in fast.iter().enumerate() {
                last = normal_at(&above, &here, &below, c, last);
                assert_eq!(*got, last, "{cols} columns, column {c}");
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
            let t = wobble(23, s as f64, spread);
            let mut mixed = wobble(23, 0.5, spread);
            mixed[5] = -mixed[6]; // an antipodal pair inside a run
            for src in [&t, &mixed] {
                let n = src.len() - 3;
                let (a, b, c, d) = (&src[0..n], &src[1..n + 1], &src[2..n + 2], &src[3..n + 3]);
                let mut v = vec![DVec3::ZERO; n];
                interior_across(&rule, [a, b, c, d], &mut v);
                let mut w = vec![DVec3::ZERO; 2 * src.len()];
                interior_along(&rule, src, 1, src.len() - 3, &mut w);
                for k in 0..n {
                    let want = rule.interior(a[k], b[k], c[k], d[k]);
                    assert_eq!(v[k], want, "across spread {spread} k {k}");
                    assert_eq!(w[2 * k + 3], want, "along spread {spread} k {k}");
                }
            }
        }
    }
}
