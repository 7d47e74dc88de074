//! Vector registers of f64 lanes for the kernels of [`super::kernels`]: the
//! operations they use, for AVX2 (`__m256d`, 4 lanes) and AVX-512F
//! (`__m512d`, 8 lanes), and tangents split into one register per coordinate.
//!
//! Every function is `#[inline(always)]` and unsafe: it must run inside a
//! function compiled with the register's target feature (the entry points of
//! [`super::kernels`]), where it is inlined.

#![allow(clippy::missing_safety_doc)] // one contract for the module, above

use glam::DVec3;
use std::arch::x86_64::*;

/// `N` f64 lanes and the few operations the kernels need; every arithmetic
/// operation is the IEEE operation of the scalar code, lane by lane.
pub(super) trait Lanes: Copy {
    /// A lane mask (a compare's result).
    type Mask: Copy;
    /// Number of lanes.
    const N: usize;
    unsafe fn splat(x: f64) -> Self;
    unsafe fn add(self, b: Self) -> Self;
    unsafe fn sub(self, b: Self) -> Self;
    unsafe fn mul(self, b: Self) -> Self;
    unsafe fn div(self, b: Self) -> Self;
    unsafe fn sqrt(self) -> Self;
    /// `self ≥ b` (false on NaN).
    unsafe fn ge(self, b: Self) -> Self::Mask;
    /// `self < b` (false on NaN).
    unsafe fn lt(self, b: Self) -> Self::Mask;
    /// `self > b` (false on NaN).
    unsafe fn gt(self, b: Self) -> Self::Mask;
    /// `!(self ≤ b)`: greater or unordered.
    unsafe fn nle(self, b: Self) -> Self::Mask;
    /// `!(self > b)`: not greater, or unordered.
    unsafe fn ngt(self, b: Self) -> Self::Mask;
    /// `self` where `m`, +0 elsewhere.
    unsafe fn keep(self, m: Self::Mask) -> Self;
    unsafe fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    unsafe fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane `l`'s flag at bit `l`.
    unsafe fn bits(m: Self::Mask) -> u32;
    /// `N` doubles at `p`.
    unsafe fn load(p: *const f64) -> Self;
    /// `N` doubles to `p`.
    unsafe fn store(self, p: *mut f64);
    /// `(a0 b0 a1 b1 …, … a(N−1) b(N−1))`: the lanes of `a` and `b` interleaved.
    unsafe fn zip(a: Self, b: Self) -> (Self, Self);
    /// `N` consecutive tangents at `p`, one register per coordinate.
    unsafe fn load3(p: *const DVec3) -> V3<Self>;
    /// The inverse of [`Lanes::load3`].
    unsafe fn store3(p: *mut DVec3, v: V3<Self>);
}

/// `N` tangents, one register per coordinate.
#[derive(Clone, Copy)]
pub(super) struct V3<L> {
    pub x: L,
    pub y: L,
    pub z: L,
}

impl<L: Lanes> V3<L> {
    #[inline(always)]
    pub unsafe fn add(self, b: Self) -> Self {
        // SAFETY: the module's contract (see the module docs).
        unsafe {
            V3 {
                x: self.x.add(b.x),
                y: self.y.add(b.y),
                z: self.z.add(b.z),
            }
        }
    }

    #[inline(always)]
    pub unsafe fn sub(self, b: Self) -> Self {
        // SAFETY: the module's contract.
        unsafe {
            V3 {
                x: self.x.sub(b.x),
                y: self.y.sub(b.y),
                z: self.z.sub(b.z),
            }
        }
    }

    #[inline(always)]
    pub unsafe fn scale(self, s: L) -> Self {
        // SAFETY: the module's contract.
        unsafe {
            V3 {
                x: self.x.mul(s),
                y: self.y.mul(s),
                z: self.z.mul(s),
            }
        }
    }

    /// glam's order: `(x·x' + y·y') + z·z'`.
    #[inline(always)]
    pub unsafe fn dot(self, b: Self) -> L {
        // SAFETY: the module's contract.
        unsafe { self.x.mul(b.x).add(self.y.mul(b.y)).add(self.z.mul(b.z)) }
    }

    /// glam's cross: `(y·z' − y'·z, z·x' − z'·x, x·y' − x'·y)`.
    #[inline(always)]
    pub unsafe fn cross(self, b: Self) -> Self {
        // SAFETY: the module's contract.
        unsafe {
            V3 {
                x: self.y.mul(b.z).sub(b.y.mul(self.z)),
                y: self.z.mul(b.x).sub(b.z.mul(self.x)),
                z: self.x.mul(b.y).sub(b.x.mul(self.y)),
            }
        }
    }
}

impl Lanes for __m256d {
    type Mask = __m256d;
    const N: usize = 4;
    #[inline(always)]
    unsafe fn splat(x: f64) -> Self {
        unsafe { _mm256_set1_pd(x) }
    }
    #[inline(always)]
    unsafe fn add(self, b: Self) -> Self {
        unsafe { _mm256_add_pd(self, b) }
    }
    #[inline(always)]
    unsafe fn sub(self, b: Self) -> Self {
        unsafe { _mm256_sub_pd(self, b) }
    }
    #[inline(always)]
    unsafe fn mul(self, b: Self) -> Self {
        unsafe { _mm256_mul_pd(self, b) }
    }
    #[inline(always)]
    unsafe fn div(self, b: Self) -> Self {
        unsafe { _mm256_div_pd(self, b) }
    }
    #[inline(always)]
    unsafe fn sqrt(self) -> Self {
        unsafe { _mm256_sqrt_pd(self) }
    }
    #[inline(always)]
    unsafe fn ge(self, b: Self) -> Self::Mask {
        unsafe { _mm256_cmp_pd::<_CMP_GE_OQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn lt(self, b: Self) -> Self::Mask {
        unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn gt(self, b: Self) -> Self::Mask {
        unsafe { _mm256_cmp_pd::<_CMP_GT_OQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn nle(self, b: Self) -> Self::Mask {
        unsafe { _mm256_cmp_pd::<_CMP_NLE_UQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn ngt(self, b: Self) -> Self::Mask {
        unsafe { _mm256_cmp_pd::<_CMP_NGT_UQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn keep(self, m: Self::Mask) -> Self {
        unsafe { _mm256_and_pd(m, self) }
    }
    #[inline(always)]
    unsafe fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask {
        unsafe { _mm256_and_pd(a, b) }
    }
    #[inline(always)]
    unsafe fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask {
        unsafe { _mm256_or_pd(a, b) }
    }
    #[inline(always)]
    unsafe fn bits(m: Self::Mask) -> u32 {
        unsafe { _mm256_movemask_pd(m) as u32 }
    }
    #[inline(always)]
    unsafe fn load(p: *const f64) -> Self {
        unsafe { _mm256_loadu_pd(p) }
    }
    #[inline(always)]
    unsafe fn store(self, p: *mut f64) {
        unsafe { _mm256_storeu_pd(p, self) }
    }
    #[inline(always)]
    unsafe fn zip(a: Self, b: Self) -> (Self, Self) {
        unsafe {
            let (u, v) = (_mm256_unpacklo_pd(a, b), _mm256_unpackhi_pd(a, b));
            (
                _mm256_permute2f128_pd(u, v, 0x20),
                _mm256_permute2f128_pd(u, v, 0x31),
            )
        }
    }
    #[inline(always)]
    unsafe fn load3(p: *const DVec3) -> V3<Self> {
        unsafe {
            let f = p.cast::<f64>();
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
    #[inline(always)]
    unsafe fn store3(p: *mut DVec3, v: V3<Self>) {
        unsafe {
            let pp = _mm256_shuffle_pd(v.x, v.y, 0b0000); // [x0 y0 | x2 y2]
            let q = _mm256_shuffle_pd(v.z, v.x, 0b1010); // [z0 x1 | z2 x3]
            let r = _mm256_shuffle_pd(v.y, v.z, 0b1111); // [y1 z1 | y3 z3]
            let f = p.cast::<f64>();
            _mm256_storeu_pd(f, _mm256_permute2f128_pd(pp, q, 0x20));
            _mm256_storeu_pd(f.add(4), _mm256_permute2f128_pd(r, pp, 0x30));
            _mm256_storeu_pd(f.add(8), _mm256_permute2f128_pd(q, r, 0x31));
        }
    }
}

/// A `vpermt2pd` index vector: lane `l` takes element `i[l] & 7` of the
/// first source (`i[l] < 8`) or of the second (`i[l] ≥ 8`).
#[inline(always)]
unsafe fn idx(i: [i64; 8]) -> __m512i {
    unsafe { _mm512_loadu_epi64(i.as_ptr()) }
}

/// Two `vpermt2pd`: `(a, b)` by `first`, then that and `c` by `second`.
#[inline(always)]
unsafe fn pick2(a: __m512d, b: __m512d, c: __m512d, first: [i64; 8], second: [i64; 8]) -> __m512d {
    unsafe { _mm512_permutex2var_pd(_mm512_permutex2var_pd(a, idx(first), b), idx(second), c) }
}

impl Lanes for __m512d {
    type Mask = __mmask8;
    const N: usize = 8;
    #[inline(always)]
    unsafe fn splat(x: f64) -> Self {
        unsafe { _mm512_set1_pd(x) }
    }
    #[inline(always)]
    unsafe fn add(self, b: Self) -> Self {
        unsafe { _mm512_add_pd(self, b) }
    }
    #[inline(always)]
    unsafe fn sub(self, b: Self) -> Self {
        unsafe { _mm512_sub_pd(self, b) }
    }
    #[inline(always)]
    unsafe fn mul(self, b: Self) -> Self {
        unsafe { _mm512_mul_pd(self, b) }
    }
    #[inline(always)]
    unsafe fn div(self, b: Self) -> Self {
        unsafe { _mm512_div_pd(self, b) }
    }
    #[inline(always)]
    unsafe fn sqrt(self) -> Self {
        unsafe { _mm512_sqrt_pd(self) }
    }
    #[inline(always)]
    unsafe fn ge(self, b: Self) -> Self::Mask {
        unsafe { _mm512_cmp_pd_mask::<_CMP_GE_OQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn lt(self, b: Self) -> Self::Mask {
        unsafe { _mm512_cmp_pd_mask::<_CMP_LT_OQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn gt(self, b: Self) -> Self::Mask {
        unsafe { _mm512_cmp_pd_mask::<_CMP_GT_OQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn nle(self, b: Self) -> Self::Mask {
        unsafe { _mm512_cmp_pd_mask::<_CMP_NLE_UQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn ngt(self, b: Self) -> Self::Mask {
        unsafe { _mm512_cmp_pd_mask::<_CMP_NGT_UQ>(self, b) }
    }
    #[inline(always)]
    unsafe fn keep(self, m: Self::Mask) -> Self {
        unsafe { _mm512_maskz_mov_pd(m, self) }
    }
    #[inline(always)]
    unsafe fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask {
        a & b
    }
    #[inline(always)]
    unsafe fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask {
        a | b
    }
    #[inline(always)]
    unsafe fn bits(m: Self::Mask) -> u32 {
        u32::from(m)
    }
    #[inline(always)]
    unsafe fn load(p: *const f64) -> Self {
        unsafe { _mm512_loadu_pd(p) }
    }
    #[inline(always)]
    unsafe fn store(self, p: *mut f64) {
        unsafe { _mm512_storeu_pd(p, self) }
    }
    #[inline(always)]
    unsafe fn zip(a: Self, b: Self) -> (Self, Self) {
        unsafe {
            (
                _mm512_permutex2var_pd(a, idx([0, 8, 1, 9, 2, 10, 3, 11]), b),
                _mm512_permutex2var_pd(a, idx([4, 12, 5, 13, 6, 14, 7, 15]), b),
            )
        }
    }
    #[inline(always)]
    unsafe fn load3(p: *const DVec3) -> V3<Self> {
        unsafe {
            let f = p.cast::<f64>();
            // v0 = [x0 y0 z0 x1 y1 z1 x2 y2], v1 = [z2 x3 y3 z3 x4 y4 z4 x5],
            // v2 = [y5 z5 x6 y6 z6 x7 y7 z7]
            let (v0, v1, v2) = (
                _mm512_loadu_pd(f),
                _mm512_loadu_pd(f.add(8)),
                _mm512_loadu_pd(f.add(16)),
            );
            V3 {
                x: pick2(
                    v0,
                    v1,
                    v2,
                    [0, 3, 6, 9, 12, 15, 0, 0],
                    [0, 1, 2, 3, 4, 5, 10, 13],
                ),
                y: pick2(
                    v0,
                    v1,
                    v2,
                    [1, 4, 7, 10, 13, 0, 0, 0],
                    [0, 1, 2, 3, 4, 8, 11, 14],
                ),
                z: pick2(
                    v0,
                    v1,
                    v2,
                    [2, 5, 8, 11, 14, 0, 0, 0],
                    [0, 1, 2, 3, 4, 9, 12, 15],
                ),
            }
        }
    }
    #[inline(always)]
    unsafe fn store3(p: *mut DVec3, v: V3<Self>) {
        unsafe {
            let f = p.cast::<f64>();
            // [x0 y0 z0 x1 y1 z1 x2 y2]
            _mm512_storeu_pd(
                f,
                pick2(
                    v.x,
                    v.y,
                    v.z,
                    [0, 8, 0, 1, 9, 0, 2, 10],
                    [0, 1, 8, 3, 4, 9, 6, 7],
                ),
            );
            // [z2 x3 y3 z3 x4 y4 z4 x5]
            _mm512_storeu_pd(
                f.add(8),
                pick2(
                    v.x,
                    v.y,
                    v.z,
                    [0, 3, 11, 0, 4, 12, 0, 5],
                    [10, 1, 2, 11, 4, 5, 12, 7],
                ),
            );
            // [y5 z5 x6 y6 z6 x7 y7 z7]
            _mm512_storeu_pd(
                f.add(16),
                pick2(
                    v.x,
                    v.y,
                    v.z,
                    [13, 0, 6, 14, 0, 7, 15, 0],
                    [0, 13, 2, 3, 14, 5, 6, 15],
                ),
            );
        }
    }
}
