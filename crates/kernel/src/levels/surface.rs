//! Tensor-product subdivision surfaces on the Gaussian sphere (paper 000, §4).
//!
//! An open regular control net of `nt` rows × `ns` columns of tangents; each row
//! is one streamline (parameter `s` along it, `t` across rows).
//! Kobbelt = 4-point ⊗ 4-point, Catmull–Clark = cubic B-spline ⊗ cubic B-spline,
//! Doo–Sabin = Chaikin ⊗ Chaikin. On the sphere the two directions do not
//! commute, so the [`BlendOrder`] is chosen by the scene (000 §4, last paragraph
//! before §5): [`BlendOrder::SFirst`] refines every row, then every column of the result.

use crate::curve::scheme::{CurveScheme, OMEGA_DEFAULT, Prepared, Stencil};
use crate::error::{KernelError, Place};
use crate::grid::Grid;
use crate::levels::dirty_window::Span;
use crate::sphere::tangent::normalize_at;
use glam::DVec3;

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
    const PARALLEL_MIN_ENTRIES: usize = crate::levels::dirty_window::PARALLEL_MIN_ENTRIES;
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

/// One tensor-product step in the given blend order: the whole grid as one
/// window (`crate::levels::dirty_window::refine_grid_window`: rows and columns both
/// passed row by row, large grids on two threads).
pub fn refine_grid<T: Refine + Send + Sync>(
    scheme: SurfaceScheme,
    order: BlendOrder,
    g: &Grid<T>,
) -> Grid<T> {
    let (mut half, mut next) = (
        Grid::filled(0, 0, T::default()),
        Grid::filled(0, 0, T::default()),
    );
    refine_grid_into(scheme, order, g, &mut half, &mut next);
    next
}

/// [`refine_grid`] into buffers kept by the caller: `half` (the grid of the
/// first direction; left empty where the step needs none,
/// [`crate::levels::dirty_window::in_place`]) and `next` are reshaped and overwritten.
pub(crate) fn refine_grid_into<T: Refine + Send + Sync>(
    scheme: SurfaceScheme,
    order: BlendOrder,
    g: &Grid<T>,
    half: &mut Grid<T>,
    next: &mut Grid<T>,
) {
    let c = scheme.curve();
    let (hr, hc) = crate::levels::dirty_window::half_shape(scheme, order, g.rows(), g.cols());
    half.reshape(hr, hc, T::default());
    next.reshape(
        c.refined_len(g.rows()),
        c.refined_len(g.cols()),
        T::default(),
    );
    crate::levels::dirty_window::refine_grid_window(
        scheme,
        order,
        g,
        half,
        next,
        crate::levels::dirty_window::DirtyWindow::all(g.rows(), g.cols()),
    );
}

/// Normalises every tangent of a net, reporting the first bad one by row and column.
pub fn normalize_grid(g: &Grid<DVec3>) -> Result<Grid<DVec3>, KernelError> {
    let mut out = g.clone();
    for r in 0..g.rows() {
        for c in 0..g.cols() {
            out.set(
                r,
                c,
                normalize_at(g.get(r, c), Place::Grid { row: r, col: c })?,
            );
        }
    }
    Ok(out)
}

/// Refines a net of tangents `depth` times: the kernel's boundary for surfaces.
pub fn subdivide(
    scheme: SurfaceScheme,
    order: BlendOrder,
    net: &Grid<DVec3>,
    depth: u32,
) -> Result<Grid<DVec3>, KernelError> {
    let scheme = scheme.validate()?;
    scheme.check_depth(net.rows(), net.cols(), depth)?;
    let mut g = normalize_grid(net)?;
    for _ in 0..depth {
        g = refine_grid(scheme, order, &g);
    }
    Ok(g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_counts_car_net() {
        let net = Grid::filled(6, 9, DVec3::X);
        let g = subdivide(SurfaceScheme::default(), BlendOrder::SFirst, &net, 5).unwrap();
        assert_eq!(
            (g.rows(), g.cols()),
            (161, 257),
            "9x6 Kobbelt depth 5 is 257x161"
        );
        let cc = SurfaceScheme::CatmullClark.check_depth(6, 9, 2).unwrap();
        assert_eq!(cc, (15, 27));
        assert!(matches!(
            SurfaceScheme::default().check_depth(6, 9, 12),
            Err(KernelError::DepthTooLarge { depth: 12, .. })
        ));
        assert!(matches!(
            SurfaceScheme::default().check_depth(6, 9, 17),
            Err(KernelError::DepthPastMax { depth: 17, max: 16 })
        ));
        assert!(matches!(
            SurfaceScheme::default().check_depth(4000, 1001, 0),
            Err(KernelError::TooManyTangents {
                tangents: 4_004_000,
                ..
            })
        ));
    }
}
