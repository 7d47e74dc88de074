//! The vector kernels, written once over [`Lanes`] and compiled twice: for
//! AVX2 (4 lanes) and AVX-512F (8 lanes). Each lane does the operations of
//! the scalar code in the same order ([`FourPointRule::interior`],
//! [`super::normal_at`]); lanes that the vector code does not cover are
//! flagged and redone by the scalar code.

use super::Rule4;
use super::lanes::{Lanes, V3};
use crate::curve::scheme::FourPointRule;
use crate::sphere::blend::{FixedBlend, MID_MIN_NORM2, MIN_TERMS, TERM_THRESHOLDS, terms_for};
use glam::DVec3;
use std::arch::x86_64::{__m256d, __m512d};

/// `h = |a − b|²/4`, as [`FixedBlend::apply`] computes it.
#[inline(always)]
unsafe fn half_chord2<L: Lanes>(a: V3<L>, b: V3<L>) -> L {
    // SAFETY (all functions here): the caller runs with L's target feature.
    unsafe {
        let d = a.sub(b);
        L::splat(0.25).mul(d.dot(d))
    }
}

/// The two series (`cos uθ`, `sin uθ / sin θ`), each lane with its own number
/// of terms ([`terms_for`]): the terms past [`MIN_TERMS`] that some lane needs
/// are summed masked (a lane holds +0 until its first term, and `0·h + c = c`
/// exactly, so each lane is the scalar Horner sum), the first [`MIN_TERMS`]
/// in every lane.
#[inline(always)]
unsafe fn series<L: Lanes>(fb: &FixedBlend, h: L) -> (L, L) {
    unsafe {
        let (cc, sc) = fb.coefficients();
        // the most terms a lane needs, from three compares
        let mut n = MIN_TERMS;
        for limit in [1e-3, 1e-2, 0.05] {
            if L::bits(h.ge(L::splat(limit))) != 0 {
                n = terms_for(limit);
            }
        }
        let (mut cu, mut su) = (L::splat(0.0), L::splat(0.0));
        for k in (MIN_TERMS..n).rev() {
            let on = h.ge(L::splat(TERM_THRESHOLDS[k]));
            cu = cu.mul(h).add(L::splat(cc[k])).keep(on);
            su = su.mul(h).add(L::splat(sc[k])).keep(on);
        }
        for k in (0..MIN_TERMS).rev() {
            cu = cu.mul(h).add(L::splat(cc[k]));
            su = su.mul(h).add(L::splat(sc[k]));
        }
        (cu, su)
    }
}

/// The end of [`FixedBlend::apply`]: `a (cu − c·su) + b·su`, `c = 1 − 2h`.
#[inline(always)]
unsafe fn combine<L: Lanes>(a: V3<L>, b: V3<L>, h: L, (cu, su): (L, L)) -> V3<L> {
    unsafe {
        let c = L::splat(1.0).sub(L::splat(2.0).mul(h));
        let wa = cu.sub(c.mul(su));
        a.scale(wa).add(b.scale(su))
    }
}

/// [`crate::sphere::blend::mid`]; antipodal lanes are flagged in `bad`.
#[inline(always)]
unsafe fn mid<L: Lanes>(a: V3<L>, b: V3<L>, bad: &mut L::Mask) -> V3<L> {
    unsafe {
        let m = a.add(b);
        let n2 = m.dot(m);
        *bad = L::or(*bad, n2.ngt(L::splat(MID_MIN_NORM2)));
        m.scale(L::splat(1.0).div(n2.sqrt()))
    }
}

/// `G` groups of `N` inserts (`q[g] = [a, b, c, d]`) and, per group, the
/// lanes to redo in scalar (an `h` past [`FixedBlend::H_MAX`], an antipodal
/// midpoint). (No closures: they would not inherit the target feature.)
#[inline(always)]
unsafe fn interior<L: Lanes, const G: usize>(
    rule: Rule4<'_>,
    q: [[V3<L>; 4]; G],
) -> ([V3<L>; G], [u32; G]) {
    unsafe {
        let limit = L::splat(FixedBlend::H_MAX);
        let zero = L::splat(0.0);
        let mut h = [(zero, zero); G];
        let mut bad = [zero.lt(zero); G]; // all clear (set below)
        for g in 0..G {
            let [a, b, c, d] = q[g];
            let (h1, h2) = (half_chord2(a, b), half_chord2(c, d));
            h[g] = (h1, h2);
            bad[g] = L::or(h1.nle(limit), h2.nle(limit));
        }
        let (outer, inner) = rule.blends();
        let mut sums = [((zero, zero), (zero, zero)); G];
        for g in 0..G {
            sums[g] = (series(outer, h[g].0), series(inner, h[g].1));
        }
        let mut out = [q[0][0]; G];
        let mut redo = [0; G];
        for g in 0..G {
            let [a, b, c, d] = q[g];
            let ((h1, h2), (s1, s2)) = (h[g], sums[g]);
            out[g] = mid(combine(a, b, h1, s1), combine(c, d, h2, s2), &mut bad[g]);
            redo[g] = L::bits(bad[g]);
        }
        (out, redo)
    }
}

/// `[a, b, c, d]`: `N` tangents from each of four rows at entry `k`.
#[inline(always)]
unsafe fn quad<L: Lanes>([a, b, c, d]: [*const DVec3; 4], k: usize) -> [V3<L>; 4] {
    unsafe {
        [
            L::load3(a.add(k)),
            L::load3(b.add(k)),
            L::load3(c.add(k)),
            L::load3(d.add(k)),
        ]
    }
}

/// The vector part of [`super::interior_across`]; returns how many entries
/// it wrote (all of them when there are at least `N`: the last group is
/// moved back to end at the last entry, recomputing a few with the same bits).
#[inline(always)]
unsafe fn across<L: Lanes>(rule: Rule4<'_>, rows: [&[DVec3]; 4], out: &mut [DVec3]) -> usize {
    let len = out.len();
    if len < L::N {
        return 0;
    }
    let ptrs = rows.map(<[DVec3]>::as_ptr);
    let [a, b, c, d] = rows;
    let mut k = 0;
    while k < len {
        // two groups while 2N entries are left, else one ending at the last
        let (g, at) = if k + 2 * L::N <= len {
            (2, [k, k + L::N])
        } else {
            let k = k.min(len - L::N);
            (1, [k, k])
        };
        // SAFETY: every group reads and writes entries below len, the
        // length of every slice.
        let (r, redo) = unsafe {
            if g == 2 {
                interior::<L, 2>(rule, [quad(ptrs, at[0]), quad(ptrs, at[1])])
            } else {
                let (r, redo) = interior::<L, 1>(rule, [quad(ptrs, at[0])]);
                ([r[0], r[0]], [redo[0], 0])
            }
        };
        for j in 0..g {
            let k = at[j];
            // SAFETY: k + N ≤ len.
            unsafe { L::store3(out.as_mut_ptr().add(k), r[j]) };
            for l in 0..L::N {
                if redo[j] & (1 << l) != 0 {
                    let e = k + l;
                    out[e] = rule.scalar([a[e], b[e], c[e], d[e]]);
                }
            }
        }
        k = at[g - 1] + L::N;
    }
    len
}

/// The vector part of [`super::interior_along`]: writes `out[2i] = t[i]` and
/// `out[2i + 1]` = insert `i` for `i` in `lo ..= hi` when there are at least
/// `N` (the last group moved back as in [`across`]); returns the first `i`
/// it did not do.
#[inline(always)]
unsafe fn along<L: Lanes>(
    rule: &FourPointRule,
    t: &[DVec3],
    lo: usize,
    hi: usize,
    out: &mut [DVec3],
) -> usize {
    if hi + 1 < lo + L::N {
        return lo;
    }
    let p = t.as_ptr();
    // inserts i .. i+N−1 read t[i−1 ..= i+N+1]
    let rows = [p.wrapping_sub(1), p, p.wrapping_add(1), p.wrapping_add(2)];
    let mut i = lo;
    while i <= hi {
        let (g, at) = if i + 2 * L::N - 1 <= hi {
            (2, [i, i + L::N])
        } else {
            let i = i.min(hi + 1 - L::N);
            (1, [i, i])
        };
        // SAFETY: i ≥ lo ≥ 1, and the last read, t[at + N + 1], has
        // at + N + 1 ≤ hi + 2 < t.len().
        let (quad, (r, redo)) = unsafe {
            let q = [quad(rows, at[0]), quad(rows, at[1])];
            if g == 2 {
                (q, interior::<L, 2>(Rule4::Interior(rule), q))
            } else {
                let (r, redo) = interior::<L, 1>(Rule4::Interior(rule), [q[0]]);
                (q, ([r[0], r[0]], [redo[0], 0]))
            }
        };
        for j in 0..g {
            let i = at[j];
            // out[2i .. 2i + 2N] = t[i], insert i, t[i+1], insert i+1, …
            let copies = quad[j][1];
            // SAFETY: the caller runs with L's target feature; the last entry
            // written, 2(i + N − 1) + 1 ≤ 2 hi + 1, is inside `out`.
            unsafe {
                let (x, y, z) = (
                    L::zip(copies.x, r[j].x),
                    L::zip(copies.y, r[j].y),
                    L::zip(copies.z, r[j].z),
                );
                let o = out.as_mut_ptr().add(2 * i);
                L::store3(
                    o,
                    V3 {
                        x: x.0,
                        y: y.0,
                        z: z.0,
                    },
                );
                L::store3(
                    o.add(L::N),
                    V3 {
                        x: x.1,
                        y: y.1,
                        z: z.1,
                    },
                );
            }
            for l in 0..L::N {
                if redo[j] & (1 << l) != 0 {
                    let e = i + l;
                    out[2 * e + 1] = rule.interior(t[e - 1], t[e], t[e + 1], t[e + 2]);
                }
            }
        }
        i = at[g - 1] + L::N;
    }
    hi + 1
}

/// A row of tangents or points as three coordinate arrays (`xs`, `ys`, `zs`,
/// each as long as the row).
#[inline(always)]
unsafe fn split<L: Lanes>(row: &[DVec3], [xs, ys, zs]: [&mut [f64]; 3]) {
    let n = row.len();
    assert!(xs.len() == n && ys.len() == n && zs.len() == n);
    let mut c = 0;
    // SAFETY: c + N ≤ n for every vector access.
    unsafe {
        while c + L::N <= n {
            let v = L::load3(row.as_ptr().add(c));
            v.x.store(xs.as_mut_ptr().add(c));
            v.y.store(ys.as_mut_ptr().add(c));
            v.z.store(zs.as_mut_ptr().add(c));
            c += L::N;
        }
    }
    for k in c..n {
        (xs[k], ys[k], zs[k]) = (row[k].x, row[k].y, row[k].z);
    }
}

/// `N` tangents at entry `c` of coordinate arrays.
#[inline(always)]
unsafe fn at3<L: Lanes>([x, y, z]: [&[f64]; 3], c: usize) -> V3<L> {
    // SAFETY: the caller checked c + N ≤ the arrays' length.
    unsafe {
        V3 {
            x: L::load(x.as_ptr().add(c)),
            y: L::load(y.as_ptr().add(c)),
            z: L::load(z.as_ptr().add(c)),
        }
    }
}

/// Normals of columns `c .. c + N` (all with both neighbours) from the rows
/// above, here and below as coordinate arrays, into `out`; `false`, writing
/// nothing, when one is degenerate (the scalar code then carries the
/// previous normal forward).
#[inline(always)]
unsafe fn normals<L: Lanes>(
    above: [&[f64]; 3],
    here: [&[f64]; 3],
    below: [&[f64]; 3],
    c: usize,
    out: &mut [DVec3],
) -> bool {
    // SAFETY: the caller checked 1 ≤ c and c + N < the rows' length.
    unsafe {
        let ds = at3::<L>(here, c + 1).sub(at3(here, c - 1));
        let dt = at3::<L>(below, c).sub(at3(above, c));
        let n = ds.cross(dt);
        let len2 = n.dot(n);
        let ok = L::and(len2.gt(L::splat(0.0)), len2.lt(L::splat(f64::INFINITY)));
        if L::bits(ok) != (1 << L::N) - 1 {
            return false;
        }
        L::store3(
            out.as_mut_ptr().add(c),
            n.scale(L::splat(1.0).div(len2.sqrt())),
        );
        true
    }
}

/// The normals of rows `lo ..= hi`, columns `c0 ..`, of the point grid
/// (`cols` wide) into `out` (those rows only), each row split into
/// coordinate arrays once (from column `c0 − 1`), in a ring of three rows
/// kept in `ring` (9 · cols doubles).
#[inline(always)]
unsafe fn normals_rows<L: Lanes>(
    points: &[DVec3],
    cols: usize,
    lo: usize,
    hi: usize,
    c0: usize,
    out: &mut [DVec3],
    ring: &mut [f64],
) {
    let a = c0.saturating_sub(1); // the first column read
    let rows = points.len() / cols;
    let mut held = [usize::MAX; 3]; // the row in each slot
    for r in lo..=hi {
        let need = [r.saturating_sub(1), r, (r + 1).min(rows - 1)];
        for &q in &need {
            let slot = q % 3;
            if held[slot] != q {
                let s = &mut ring[slot * 3 * cols..(slot + 1) * 3 * cols];
                let (x, rest) = s.split_at_mut(cols);
                let (y, z) = rest.split_at_mut(cols);
                let row = &points[q * cols + a..(q + 1) * cols];
                // SAFETY: the caller runs with L's target feature.
                unsafe { split::<L>(row, [&mut x[a..], &mut y[a..], &mut z[a..]]) };
                held[slot] = q;
            }
        }
        let coords = |q: usize| {
            let s = &ring[(q % 3) * 3 * cols..(q % 3 + 1) * 3 * cols];
            [&s[..cols], &s[cols..2 * cols], &s[2 * cols..]]
        };
        let (above, here, below) = (coords(need[0]), coords(need[1]), coords(need[2]));
        let row = |q: usize| &points[q * cols..(q + 1) * cols];
        let o = &mut out[(r - lo) * cols..(r - lo + 1) * cols];
        let mut c = c0;
        while c < cols {
            // SAFETY: 1 ≤ c and c + N < cols; the caller runs with L's feature.
            if c >= 1 && c + L::N < cols && unsafe { normals::<L>(above, here, below, c, o) } {
                c += L::N;
                continue;
            }
            // the normal carried into a degenerate point is the one just
            // written (read back only then: a load right after the vector
            // store would stall on forwarding)
            o[c] = match super::unit_normal(row(need[0]), row(r), row(need[2]), c) {
                Some(n) => n,
                None => super::carried(o, c),
            };
            c += 1;
        }
    }
}

/// The vector part of [`super::dots_at_least`]: over the first entries of
/// `a` and `b` (`n`, their common length, rounded down to `N`), whether a
/// dot product `a[k] · b[k]` (glam's order) is below `th` (a NaN one is not);
/// returns the entries done and that answer.
#[inline(always)]
unsafe fn dots_below<L: Lanes>(a: &[DVec3], b: &[DVec3], th: f64) -> (usize, bool) {
    let n = a.len().min(b.len());
    // SAFETY: the caller runs with L's target feature.
    let t = unsafe { L::splat(th) };
    let mut k = 0;
    while k + L::N <= n {
        // SAFETY: k + N ≤ n, the length of both slices.
        let below = unsafe {
            let d = L::load3(a.as_ptr().add(k)).dot(L::load3(b.as_ptr().add(k)));
            L::bits(d.lt(t)) != 0
        };
        if below {
            return (k, true);
        }
        k += L::N;
    }
    (k, false)
}

/// The entry points: each kernel compiled with AVX2 and with AVX-512F.
macro_rules! entry_points {
    ($feature:literal, $lanes:ty, $across:ident, $along:ident, $normals:ident, $dots:ident) => {
        /// # Safety
        /// The CPU must have the target feature; slices as in the generic kernel.
        #[target_feature(enable = $feature)]
        pub(super) unsafe fn $across(
            rule: Rule4<'_>,
            rows: [&[DVec3]; 4],
            out: &mut [DVec3],
        ) -> usize {
            // SAFETY: the feature is enabled here; the caller checked the lengths.
            unsafe { across::<$lanes>(rule, rows, out) }
        }

        /// # Safety
        /// The CPU must have the target feature; bounds as in [`super::interior_along`].
        #[target_feature(enable = $feature)]
        pub(super) unsafe fn $along(
            rule: &FourPointRule,
            t: &[DVec3],
            lo: usize,
            hi: usize,
            out: &mut [DVec3],
        ) -> usize {
            // SAFETY: the feature is enabled here; the caller checked the bounds.
            unsafe { along::<$lanes>(rule, t, lo, hi, out) }
        }

        /// # Safety
        /// The CPU must have the target feature; `lo ≤ hi < rows`, `c0 < cols`,
        /// `out` holds rows `lo ..= hi`, `ring` holds `9 · cols` doubles.
        #[target_feature(enable = $feature)]
        pub(super) unsafe fn $normals(
            points: &[DVec3],
            cols: usize,
            lo: usize,
            hi: usize,
            c0: usize,
            out: &mut [DVec3],
            ring: &mut [f64],
        ) {
            // SAFETY: the feature is enabled here; the caller checked the sizes.
            unsafe { normals_rows::<$lanes>(points, cols, lo, hi, c0, out, ring) }
        }

        /// # Safety
        /// The CPU must have the target feature.
        #[target_feature(enable = $feature)]
        pub(super) unsafe fn $dots(a: &[DVec3], b: &[DVec3], th: f64) -> (usize, bool) {
            // SAFETY: the feature is enabled here; the kernel stays in bounds.
            unsafe { dots_below::<$lanes>(a, b, th) }
        }
    };
}

entry_points!(
    "avx2",
    __m256d,
    across_avx2,
    along_avx2,
    normals_avx2,
    dots_avx2
);
entry_points!(
    "avx512f",
    __m512d,
    across_avx512,
    along_avx512,
    normals_avx512,
    dots_avx512
);
