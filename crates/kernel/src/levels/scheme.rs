//! The tensor-product scheme of the levels and its refinement in one
//! direction: [`SurfaceScheme`], [`BlendOrder`], the per-entry rules of
//! [`Refine`] (tangents and scalars) and [`refine_rows`] / [`refine_cols`].
//!
//! Moved out of `surface.rs` (which re-exports all of it at its old paths,
//! `levels::surface::…`) so that `dirty_window.rs`, the windowed step, sits
//! between the two: `span.rs` ← `scheme.rs` ← `dirty_window.rs` ← `surface.rs`,
//! each file importing the ones before it (the whole-grid step,
//! [`crate::levels::surface::refine_grid`], is the windowed step over the
//! whole grid).

use crate::curve::scheme::{CurveScheme, OMEGA_DEFAULT, Prepared, Stencil};
use crate::error::KernelError;
use crate::grid::Grid;
use crate::levels::span::Span;
use glam::DVec3;

/// Windows of tangents smaller than this many entries are refined on the
/// calling thread; larger ones are split in two halves of rows run on two
/// threads (the work per entry is the same either way, so results are
/// bitwise equal). Scalar grids stay on one thread (their
/// [`Refine::PARALLEL_MIN_ENTRIES`] is `usize::MAX`).
pub(crate) const PARALLEL_MIN_ENTRIES: usize = 16_384;

/// A tensor-product subdivision scheme for regular nets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SurfaceScheme {
    /// Kobbelt's interpolatory scheme: 4-point ⊗ 4-point with tension ω.
    Kobbelt { omega: f64 },
    /// Catmull–Clark on the regular grid: cubic B-spline ⊗ cubic B-spline.
    CatmullClark,
    /// Doo–Sabin on the regular grid: Chaikin ⊗ Chaikin.
    DooSabin,
}

impl Default for SurfaceScheme {
    fn default() -> Self {
        SurfaceScheme::Kobbelt {
            omega: OMEGA_DEFAULT,
        }
    }
}

impl SurfaceScheme {
    /// The curve scheme applied in each direction.
    pub fn curve(self) -> CurveScheme {
        match self {
            SurfaceScheme::Kobbelt { omega } => CurveScheme::FourPoint { omega },
            SurfaceScheme::CatmullClark => CurveScheme::CubicBSpline,
            SurfaceScheme::DooSabin => CurveScheme::Chaikin,
        }
    }

    /// A short lowercase name (`kobbelt`, `catmull-clark`, `doo-sabin`).
    pub fn name(self) -> &'static str {
        match self {
            SurfaceScheme::Kobbelt { .. } => "kobbelt",
            SurfaceScheme::CatmullClark => "catmull-clark",
            SurfaceScheme::DooSabin => "doo-sabin",
        }
    }

    /// The name as a designer reads it (`Kobbelt`, `Catmull–Clark`, `Doo–Sabin`).
    pub fn title(self) -> &'static str {
        match self {
            SurfaceScheme::Kobbelt { .. } => "Kobbelt",
            SurfaceScheme::CatmullClark => "Catmull–Clark",
            SurfaceScheme::DooSabin => "Doo–Sabin",
        }
    }

    /// Whether the scheme keeps the control net at even indices.
    pub fn is_interpolatory(self) -> bool {
        matches!(self, SurfaceScheme::Kobbelt { .. })
    }

    /// Checks ω.
    pub fn validate(self) -> Result<Self, KernelError> {
        self.curve().validate().map(|_| self)
    }

    /// Grid size after `depth` steps from `rows × cols`, with the size cap checked.
    pub fn check_depth(
        self,
        rows: usize,
        cols: usize,
        depth: u32,
    ) -> Result<(usize, usize), KernelError> {
        let c = self.curve();
        let (mut r, mut k) = (rows, cols);
        let base = rows.saturating_mul(cols);
        if base > crate::limits::MAX_TANGENTS_PER_LEVEL {
            return Err(KernelError::TooManyTangents {
                tangents: base,
                cap: crate::limits::MAX_TANGENTS_PER_LEVEL,
            });
        }
        if depth > crate::limits::MAX_DEPTH {
            return Err(KernelError::DepthPastMax {
                depth,
                max: crate::limits::MAX_DEPTH,
            });
        }
        for _ in 0..depth {
            for n in [r, k] {
                if n < c.min_len() {
                    return Err(KernelError::TooFewTangents {
                        what: self.name(),
                        got: n,
                        need: c.min_len(),
                    });
                }
            }
            r = c.refined_len(r);
            k = c.refined_len(k);
            let total = r.saturating_mul(k);
            if total > crate::limits::MAX_TANGENTS_PER_LEVEL {
                return Err(KernelError::DepthTooLarge {
                    depth,
                    tangents: total,
                    cap: crate::limits::MAX_TANGENTS_PER_LEVEL,
                });
            }
        }
        if depth == 0 {
            for n in [r, k] {
                if n < 2 {
                    return Err(KernelError::TooFewTangents {
                        what: self.name(),
                        got: n,
                        need: 2,
                    });
                }
            }
        }
        Ok((r, k))
    }
}

/// Which direction is blended first in each step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BlendOrder {
    /// Every row (along `s`), then every column of the result (along `t`).
    #[default]
    SFirst,
    /// Every column (along `t`), then every row of the result.
    TFirst,
}

impl BlendOrder {
    /// `s-first` or `t-first`.
    pub fn name(self) -> &'static str {
        match self {
            BlendOrder::SFirst => "s-first",
            BlendOrder::TFirst => "t-first",
        }
    }
}

/// A 1D refinement applied along rows and columns of a grid; implemented for
/// tangents (on the sphere) and scalars (parameter grids).
pub trait Refine: Copy + Default {
    /// Windows of at least this many entries are split over two threads
    /// (below it, starting a thread costs more than it saves).
    const PARALLEL_MIN_ENTRIES: usize;
    /// The scheme prepared for entry-by-entry use.
    type Rule: Sync;
    /// Prepares `scheme` (assumed validated).
    fn prepare(scheme: CurveScheme) -> Self::Rule;
    /// One step of `scheme` on `input` into `out`.
    fn refine(scheme: CurveScheme, input: &[Self], out: &mut Vec<Self>);
    /// The output of stencil `st`, reading input `j` as `f(j)`: bit-for-bit
    /// equal to `refine`'s output with that stencil (for windows).
    fn apply(rule: &Self::Rule, st: Stencil, f: impl Fn(usize) -> Self) -> Self;

    /// Entries `cols` of one output row of the step across rows: stencil `st`
    /// over whole input rows, row `j` read as `rows(j)` (entry by entry
    /// unless a type does better).
    #[inline]
    fn apply_across<'a>(
        rule: &Self::Rule,
        st: Stencil,
        rows: impl Fn(usize) -> &'a [Self],
        cols: Span,
        out: &mut [Self],
    ) where
        Self: 'a,
    {
        for k in cols.iter() {
            out[k] = Self::apply(rule, st, |j| rows(j)[k]);
        }
    }

    /// Entries `cols` of one row's step along it, from `input`.
    #[inline]
    fn apply_along(
        rule: &Self::Rule,
        c: CurveScheme,
        input: &[Self],
        cols: Span,
        out: &mut [Self],
    ) {
        let n = input.len();
        for k in cols.iter() {
            out[k] = Self::apply(rule, c.stencil(n, k), |j| input[j]);
        }
    }
}

impl Refine for DVec3 {
    const PARALLEL_MIN_ENTRIES: usize = PARALLEL_MIN_ENTRIES;
    type Rule = Prepared;
    fn prepare(scheme: CurveScheme) -> Prepared {
        Prepared::new(scheme)
    }
    fn refine(scheme: CurveScheme, input: &[Self], out: &mut Vec<Self>) {
        scheme.refine_tangents(input, out);
    }
    #[inline(always)]
    fn apply(rule: &Prepared, st: Stencil, f: impl Fn(usize) -> Self) -> Self {
        rule.tangent(st, f)
    }

    /// 4-point inserts go four at a time ([`crate::simd`], same bits).
    fn apply_across<'a>(
        rule: &Prepared,
        st: Stencil,
        rows: impl Fn(usize) -> &'a [Self],
        cols: Span,
        out: &mut [Self],
    ) {
        match (rule.four_point(), st) {
            (Some(four), Stencil::Insert(i)) => {
                let r = cols.lo..cols.hi + 1;
                let row = |j: usize| &rows(j)[r.clone()];
                crate::simd::interior_across(
                    four,
                    [row(i - 1), row(i), row(i + 1), row(i + 2)],
                    &mut out[r.clone()],
                );
            }
            (Some(four), Stencil::End(a, b, c)) => {
                let r = cols.lo..cols.hi + 1;
                let row = |j: usize| &rows(j)[r.clone()];
                crate::simd::end_across(four, [row(a), row(b), row(c)], &mut out[r.clone()]);
            }
            (_, Stencil::Copy(i)) => {
                let r = cols.lo..cols.hi + 1;
                out[r.clone()].copy_from_slice(&rows(i)[r]);
            }
            _ => {
                for k in cols.iter() {
                    out[k] = rule.tangent(st, |j| rows(j)[k]);
                }
            }
        }
    }

    /// 4-point inserts (odd outputs `3 ..= 2n − 5`) go four at a time.
    fn apply_along(rule: &Prepared, c: CurveScheme, input: &[Self], cols: Span, out: &mut [Self]) {
        let n = input.len();
        let (Some(four), true) = (rule.four_point(), n >= 4) else {
            for k in cols.iter() {
                out[k] = rule.tangent(c.stencil(n, k), |j| input[j]);
            }
            return;
        };
        // the run of copies and inserts goes to the vector path; the rest entry by entry
        let (lo, hi) = four_point_run(cols, n);
        for k in outside(cols, 2 * lo, 2 * hi + 1) {
            out[k] = rule.tangent(c.stencil(n, k), |j| input[j]);
        }
        crate::simd::interior_along(four, input, lo, hi, out);
    }
}

impl Refine for f64 {
    /// A scalar rule is a few multiply-adds: never worth a thread here.
    const PARALLEL_MIN_ENTRIES: usize = usize::MAX;
    type Rule = CurveScheme;
    fn prepare(scheme: CurveScheme) -> CurveScheme {
        scheme
    }
    fn refine(scheme: CurveScheme, input: &[Self], out: &mut Vec<Self>) {
        scheme.refine_scalars(input, out);
    }
    #[inline(always)]
    fn apply(scheme: &CurveScheme, st: Stencil, f: impl Fn(usize) -> Self) -> Self {
        crate::curve::scalar::apply(*scheme, st, f)
    }

    /// Copies and inserts as whole-row loops (the stencil is the same for
    /// every entry of the row), with the operations of `crate::curve::scalar::apply`.
    fn apply_across<'a>(
        scheme: &CurveScheme,
        st: Stencil,
        rows: impl Fn(usize) -> &'a [Self],
        cols: Span,
        out: &mut [Self],
    ) {
        let r = cols.lo..cols.hi + 1;
        let row = |j: usize| &rows(j)[r.clone()];
        match st {
            Stencil::Copy(i) => out[r.clone()].copy_from_slice(row(i)),
            Stencil::Insert(i) => {
                let w = crate::curve::scalar::insert_weight(*scheme);
                let (a, b, c, d) = (row(i - 1), row(i), row(i + 1), row(i + 2));
                for (k, o) in out[r.clone()].iter_mut().enumerate() {
                    *o = crate::curve::scalar::insert(w, a[k], b[k], c[k], d[k]);
                }
            }
            _ => {
                for (k, o) in out[r.clone()].iter_mut().enumerate() {
                    *o = crate::curve::scalar::apply(*scheme, st, |j| row(j)[k]);
                }
            }
        }
    }

    /// 4-point rows: copies and interior inserts as plain loops.
    fn apply_along(
        scheme: &CurveScheme,
        c: CurveScheme,
        input: &[Self],
        cols: Span,
        out: &mut [Self],
    ) {
        let n = input.len();
        if !matches!(c, CurveScheme::FourPoint { .. }) || n < 4 {
            for k in cols.iter() {
                out[k] = crate::curve::scalar::apply(*scheme, c.stencil(n, k), |j| input[j]);
            }
            return;
        }
        // the run of copies and inserts as one plain loop; the rest entry by entry
        let (lo, hi) = four_point_run(cols, n);
        for k in outside(cols, 2 * lo, 2 * hi + 1) {
            out[k] = crate::curve::scalar::apply(*scheme, c.stencil(n, k), |j| input[j]);
        }
        if lo <= hi {
            let w = crate::curve::scalar::insert_weight(c);
            let pairs = out[2 * lo..2 * hi + 2].chunks_exact_mut(2);
            for (o, q) in pairs.zip(input[lo - 1..hi + 3].windows(4)) {
                o[0] = q[1];
                o[1] = crate::curve::scalar::insert(w, q[0], q[1], q[2], q[3]);
            }
        }
    }
}

/// The run of a 4-point row step on `n ≥ 4` inputs inside `cols`: the `i` in
/// `[lo, hi] ⊂ [1, n − 3]` whose copy `2i` and interior insert `2i + 1` both
/// lie in `cols` (empty when `lo > hi`); the entries outside
/// `[2 lo, 2 hi + 1]` take their stencils one by one.
fn four_point_run(cols: Span, n: usize) -> (usize, usize) {
    let lo = cols.lo.div_ceil(2).max(1);
    let hi = ((cols.hi.saturating_sub(1)) / 2).min(n - 3);
    (lo, hi)
}

/// The indices of `cols` before `a` and after `b` (`a ≤ b + 1`).
fn outside(cols: Span, a: usize, b: usize) -> impl Iterator<Item = usize> {
    (cols.lo..a.min(cols.hi + 1)).chain((b + 1).max(cols.lo)..=cols.hi)
}

/// Refines every row of `g`.
pub fn refine_rows<T: Refine>(scheme: CurveScheme, g: &Grid<T>) -> Grid<T> {
    let cols = scheme.refined_len(g.cols());
    let mut data = Vec::with_capacity(g.rows() * cols);
    let mut buf = Vec::with_capacity(cols);
    for r in 0..g.rows() {
        T::refine(scheme, g.row(r), &mut buf);
        data.extend_from_slice(&buf);
    }
    Grid::new(g.rows(), cols, data).expect("sizes agree by construction")
}

/// Refines every column of `g`.
pub fn refine_cols<T: Refine>(scheme: CurveScheme, g: &Grid<T>) -> Grid<T> {
    let rows = scheme.refined_len(g.rows());
    let mut out = Grid::filled(rows, g.cols(), T::default());
    let mut col = Vec::with_capacity(g.rows());
    let mut buf = Vec::with_capacity(rows);
    for c in 0..g.cols() {
        col.clear();
        col.extend((0..g.rows()).map(|r| g.get(r, c)));
        T::refine(scheme, &col, &mut buf);
        for (r, &v) in buf.iter().enumerate() {
            out.set(r, c, v);
        }
    }
    out
}
