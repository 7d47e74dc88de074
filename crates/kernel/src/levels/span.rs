//! [`Span`]: an inclusive index range of a grid's rows or columns, and the
//! range one curve subdivision step makes of it ([`Span::refine`]).
//!
//! Below both `scheme.rs` (the per-entry rules refine a span of a row) and
//! `dirty_window.rs` (a window is two spans); it was in `dirty_window.rs`,
//! which re-exports it at its old path `levels::dirty_window::Span`.

use crate::curve::scheme::CurveScheme;

/// An inclusive, non-empty index range `lo ..= hi`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Span {
    /// First index.
    pub lo: usize,
    /// Last index (inclusive).
    pub hi: usize,
}

impl Span {
    /// `lo ..= hi` (swapped if given the wrong way round).
    pub fn new(lo: usize, hi: usize) -> Self {
        Span {
            lo: lo.min(hi),
            hi: lo.max(hi),
        }
    }

    /// One index.
    pub fn single(i: usize) -> Self {
        Span { lo: i, hi: i }
    }

    /// Every index of `n` (`n ≥ 1`).
    pub fn all(n: usize) -> Self {
        Span {
            lo: 0,
            hi: n.saturating_sub(1),
        }
    }

    /// Number of indices.
    pub fn len(self) -> usize {
        self.hi - self.lo + 1
    }

    /// Never empty; present for clippy's `len_without_is_empty`.
    pub fn is_empty(self) -> bool {
        false
    }

    /// The smallest span holding both.
    pub fn union(self, o: Span) -> Span {
        Span {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    /// Widened by `by` on each side, clipped to `0 ..= n−1`.
    pub fn widen(self, by: usize, n: usize) -> Span {
        Span {
            lo: self.lo.saturating_sub(by),
            hi: (self.hi + by).min(n.saturating_sub(1)),
        }
    }

    /// The indices iterated.
    pub fn iter(self) -> std::ops::RangeInclusive<usize> {
        self.lo..=self.hi
    }

    /// The outputs of one step of `scheme` on `n` inputs that read any input in
    /// `self` (Chaikin: `[2a−2, 2b+1]`, cubic B-spline: `[2a−3, 2b+1]`,
    /// 4-point: `[2a−3, 2b+3]`, clipped).
    pub fn refine(self, scheme: CurveScheme, n: usize) -> Span {
        let m = scheme.refined_len(n);
        let (a, b) = (2 * self.lo, 2 * self.hi);
        let (lo, hi) = match scheme {
            CurveScheme::Chaikin => (a.saturating_sub(2), b + 1),
            CurveScheme::CubicBSpline => (a.saturating_sub(3), b + 1),
            CurveScheme::FourPoint { .. } => (a.saturating_sub(3), b + 3),
        };
        Span {
            lo: lo.min(m - 1),
            hi: hi.min(m - 1),
        }
    }
}
