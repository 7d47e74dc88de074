//! Dirty windows for the incremental rebuild (docs/architecture.md, "Incremental rebuild, exactly").
//!
//! An edit marks the control cells it touched as a [`DirtyWindow`]. One subdivision
//! step maps a dirty input range `[a, b]` to the outputs that read any of it:
//! the stencil radius of the scheme on each side, indices doubled
//! ([`Span::refine`]). Every entry in the new window is recomputed with the
//! same per-entry rule as the full step (the [`crate::curve::scheme::Stencil`] of the
//! entry, applied by [`crate::curve::scheme::Prepared::tangent`] or
//! `crate::curve::scalar::apply`), so a windowed update gives bit-for-bit the
//! numbers of a full rebuild.

use crate::curve::scheme::CurveScheme;
use crate::grid::Grid;
use crate::levels::scheme::{BlendOrder, Refine, SurfaceScheme};
// Defined in `span.rs` (below `scheme.rs`, which reads it); the public path stays here.
pub use crate::levels::span::Span;

/// A rectangle of grid cells: rows (streamlines) × columns (along `s`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DirtyWindow {
    /// Rows.
    pub rows: Span,
    /// Columns.
    pub cols: Span,
}

impl DirtyWindow {
    /// One cell.
    pub fn cell(row: usize, col: usize) -> Self {
        DirtyWindow {
            rows: Span::single(row),
            cols: Span::single(col),
        }
    }

    /// The whole `rows × cols` grid.
    pub fn all(rows: usize, cols: usize) -> Self {
        DirtyWindow {
            rows: Span::all(rows),
            cols: Span::all(cols),
        }
    }

    /// Number of cells.
    pub fn area(self) -> usize {
        self.rows.len() * self.cols.len()
    }

    /// The smallest window holding both.
    pub fn union(self, o: DirtyWindow) -> DirtyWindow {
        DirtyWindow {
            rows: self.rows.union(o.rows),
            cols: self.cols.union(o.cols),
        }
    }

    /// Union with an optional window.
    pub fn merge(a: Option<DirtyWindow>, b: DirtyWindow) -> DirtyWindow {
        a.map_or(b, |a| a.union(b))
    }

    /// Widened by `by` cells each way inside a `rows × cols` grid.
    pub fn widen(self, by: usize, rows: usize, cols: usize) -> DirtyWindow {
        DirtyWindow {
            rows: self.rows.widen(by, rows),
            cols: self.cols.widen(by, cols),
        }
    }

    /// The window of the next level after one tensor step on a `rows × cols` grid.
    pub fn refine(self, scheme: SurfaceScheme, rows: usize, cols: usize) -> DirtyWindow {
        let c = scheme.curve();
        DirtyWindow {
            rows: self.rows.refine(c, rows),
            cols: self.cols.refine(c, cols),
        }
    }
}

/// Splits rows `rows` of `dst` (a `width`-wide grid) between the calling
/// thread and, when `parallel`, one more: `run(chunk, first_row)` fills its
/// chunk of whole rows.
fn split_rows<T, F>(dst: &mut [T], width: usize, rows: Span, parallel: bool, run: F)
where
    T: Send,
    F: Fn(&mut [T], usize) + Sync,
{
    let region = &mut dst[rows.lo * width..(rows.hi + 1) * width];
    if !parallel || rows.len() < 2 {
        run(region, rows.lo);
        return;
    }
    let split = rows.len() / 2;
    let (top, bottom) = region.split_at_mut(split * width);
    crate::parallel::join(|| run(top, rows.lo), || run(bottom, rows.lo + split));
}

/// Entries `cols` of rows `rows` of `dst`: the step along each row of `src`.
fn refine_along_rows<T: Refine + Send + Sync>(
    rule: &T::Rule,
    c: CurveScheme,
    src: &Grid<T>,
    dst: &mut Grid<T>,
    rows: Span,
    cols: Span,
    parallel: bool,
) {
    let width = dst.cols();
    split_rows(dst.data_mut(), width, rows, parallel, |chunk, first| {
        for (i, row) in chunk.chunks_mut(width).enumerate() {
            T::apply_along(rule, c, src.row(first + i), cols, row);
        }
    });
}

/// Entries `cols` of rows `rows` of `dst`: the step along each column of
/// `src`, done a row at a time (output row `r` combines whole input rows by
/// the stencil of `r`, so memory is read in order and nothing is gathered).
fn refine_along_cols<T: Refine + Send + Sync>(
    rule: &T::Rule,
    c: CurveScheme,
    src: &Grid<T>,
    dst: &mut Grid<T>,
    rows: Span,
    cols: Span,
    parallel: bool,
) {
    let width = dst.cols();
    let n = src.rows();
    split_rows(dst.data_mut(), width, rows, parallel, |chunk, first| {
        for (i, row) in chunk.chunks_mut(width).enumerate() {
            T::apply_across(rule, c.stencil(n, first + i), |j| src.row(j), cols, row);
        }
    });
}

/// One tensor step restricted to a window. `prev` is the coarse grid, `half`
/// the intermediate grid of the first direction (s-first: `prev.rows × refined
/// cols`; t-first: `refined rows × prev.cols`), `next` the fine grid; `win` is
/// the dirty window of `prev`. Recomputes the affected entries of `half` and
/// `next` in place and returns the dirty window of `next`. Large windows run on
/// two threads ([`Refine::PARALLEL_MIN_ENTRIES`]).
pub(crate) fn refine_grid_window<T: Refine + Send + Sync>(
    scheme: SurfaceScheme,
    order: BlendOrder,
    prev: &Grid<T>,
    half: &mut Grid<T>,
    next: &mut Grid<T>,
    win: DirtyWindow,
) -> DirtyWindow {
    if in_place(scheme, order, prev.rows()) {
        return refine_in_place_s_first(scheme, prev, next, win);
    }
    let c = scheme.curve();
    let rule = T::prepare(c);
    let out = win.refine(scheme, prev.rows(), prev.cols());
    let parallel = out.area() >= T::PARALLEL_MIN_ENTRIES;
    match order {
        BlendOrder::SFirst => {
            refine_along_rows(&rule, c, prev, half, win.rows, out.cols, parallel);
            refine_along_cols(&rule, c, half, next, out.rows, out.cols, parallel);
        }
        BlendOrder::TFirst => {
            refine_along_cols(&rule, c, prev, half, out.rows, win.cols, parallel);
            refine_along_rows(&rule, c, half, next, out.rows, out.cols, parallel);
        }
    }
    out
}

/// Whether a step keeps no `half` grid: s-first with an interpolatory scheme
/// (Kobbelt) on two rows or more, where the first direction's row `r` *is*
/// row `2r` of the next level (the 4-point rule's `Stencil::Copy`), so it is
/// written there and read from there.
pub(crate) fn in_place(scheme: SurfaceScheme, order: BlendOrder, rows: usize) -> bool {
    order == BlendOrder::SFirst && scheme.is_interpolatory() && rows >= 2
}

/// [`refine_grid_window`] of an s-first interpolatory step ([`in_place`]):
/// the rows of `prev` in `win` refined along `s` straight into the even rows
/// of `next`, then the odd rows of the output window from the even rows, with
/// the same per-entry operations as the two-grid path (bitwise equal). Rows
/// of `next` outside the window are read as they are: they hold the refined
/// rows of unchanged input. Large windows run on two threads, split at an
/// even row; the few even rows one half reads from the other are copied first.
fn refine_in_place_s_first<T: Refine + Send + Sync>(
    scheme: SurfaceScheme,
    prev: &Grid<T>,
    next: &mut Grid<T>,
    win: DirtyWindow,
) -> DirtyWindow {
    let c = scheme.curve();
    let rule = T::prepare(c);
    let n = prev.rows();
    let out = win.refine(scheme, n, prev.cols());
    let nc = next.cols();
    let (nr, cols) = (next.rows(), out.cols);
    // rows [0, split) on the calling thread, [split, nr) on the helper
    let split = if out.area() >= T::PARALLEL_MIN_ENTRIES && out.rows.len() >= 8 {
        (out.rows.lo + out.rows.len() / 2) & !1
    } else {
        nr
    };
    let data = next.data_mut();
    // the first direction: even rows 2r, r in win.rows
    {
        let (top, bottom) = data.split_at_mut(split * nc);
        let even = |chunk: &mut [T], first: usize| {
            for r in win.rows.iter() {
                let at = 2 * r;
                if at >= first && (at - first + 1) * nc <= chunk.len() {
                    let row = &mut chunk[(at - first) * nc..(at - first + 1) * nc];
                    T::apply_along(&rule, c, prev.row(r), cols, row);
                }
            }
        };
        if split < nr {
            crate::parallel::join(|| even(top, 0), || even(bottom, split));
        } else {
            even(top, 0);
        }
    }
    // the second: odd rows of out.rows from the even rows (read in place)
    let odd_rows = || out.rows.iter().filter(|r| r % 2 == 1);
    let mut borrowed: Vec<(usize, Vec<T>)> = Vec::new();
    if split < nr {
        for r in odd_rows() {
            let (lo, hi) = c.stencil(n, r).reads();
            for j in lo..=hi {
                let row = 2 * j;
                if (r < split) != (row < split) && !borrowed.iter().any(|(k, _)| *k == row) {
                    borrowed.push((row, data[row * nc..(row + 1) * nc].to_vec()));
                }
            }
        }
    }
    let borrowed = &borrowed;
    let odd = |chunk: &mut [T], first: usize| {
        let end = first + chunk.len() / nc;
        for r in odd_rows().filter(|&r| first <= r && r < end) {
            let (before, rest) = chunk.split_at_mut((r - first) * nc);
            let (row_out, after) = rest.split_at_mut(nc);
            let (before, after) = (&*before, &*after);
            let rows = |j: usize| -> &[T] {
                let at = 2 * j;
                if at >= first && at < r {
                    &before[(at - first) * nc..(at - first + 1) * nc]
                } else if at > r && at < end {
                    let k = at - r - 1;
                    &after[k * nc..(k + 1) * nc]
                } else {
                    let (_, v) = borrowed
                        .iter()
                        .find(|(k, _)| *k == at)
                        .expect("rows across the split are borrowed");
                    v
                }
            };
            T::apply_across(&rule, c.stencil(n, r), rows, cols, row_out);
        }
    };
    let (top, bottom) = data.split_at_mut(split * nc);
    if split < nr {
        crate::parallel::join(|| odd(top, 0), || odd(bottom, split));
    } else {
        odd(top, 0);
    }
    out
}

/// The shape of `half` for one step of a `rows × cols` grid (`0 × 0` where
/// the step needs none, [`in_place`]).
pub(crate) fn half_shape(
    scheme: SurfaceScheme,
    order: BlendOrder,
    rows: usize,
    cols: usize,
) -> (usize, usize) {
    if in_place(scheme, order, rows) {
        return (0, 0);
    }
    let c = scheme.curve();
    match order {
        BlendOrder::SFirst => (rows, c.refined_len(cols)),
        BlendOrder::TFirst => (c.refined_len(rows), cols),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levels::oracle::refine_grid_gathered;
    use crate::levels::scheme::PARALLEL_MIN_ENTRIES;
    use glam::DVec3;

    fn net(rows: usize, cols: usize) -> Grid<DVec3> {
        let data = (0..rows * cols)
            .map(|i| {
                let a = i as f64 * 0.37;
                DVec3::new(a.cos(), a.sin(), 0.3 * (i as f64 * 0.11).sin()).normalize()
            })
            .collect();
        Grid::new(rows, cols, data).unwrap()
    }

    #[test]
    fn window_full_equals_refine_grid_bitwise() {
        for scheme in [
            SurfaceScheme::default(),
            SurfaceScheme::CatmullClark,
            SurfaceScheme::DooSabin,
        ] {
            // 5×7 runs on one thread; 70×90 (over PARALLEL_MIN_ENTRIES) on two
            for (rows, cols) in [(5, 7), (70, 90)] {
                for order in [BlendOrder::SFirst, BlendOrder::TFirst] {
                    let g = net(rows, cols);
                    let full = refine_grid_gathered(scheme, order, &g);
                    let (hr, hc) = half_shape(scheme, order, rows, cols);
                    let mut half = Grid::filled(hr, hc, DVec3::ZERO);
                    let mut next = Grid::filled(full.rows(), full.cols(), DVec3::ZERO);
                    let w = refine_grid_window(
                        scheme,
                        order,
                        &g,
                        &mut half,
                        &mut next,
                        DirtyWindow::all(rows, cols),
                    );
                    assert_eq!(w, DirtyWindow::all(full.rows(), full.cols()));
                    assert!(w.area() < PARALLEL_MIN_ENTRIES || rows > 5);
                    assert_eq!(next, full, "{scheme:?} {order:?} {rows}×{cols}");
                }
            }
        }
    }

    /// Windowed updates after edits of the coarse grid give the full step's
    /// numbers bitwise: small windows (one thread), windows past
    /// `PARALLEL_MIN_ENTRIES` (split in two; for s-first Kobbelt at an even
    /// row, with rows borrowed across the split), windows at the borders.
    #[test]
    fn windowed_updates_equal_the_full_step_bitwise() {
        for scheme in [
            SurfaceScheme::default(),
            SurfaceScheme::Kobbelt { omega: 1.3 },
            SurfaceScheme::CatmullClark,
        ] {
            for order in [BlendOrder::SFirst, BlendOrder::TFirst] {
                let (rows, cols) = (70, 90);
                let mut g = net(rows, cols);
                let (hr, hc) = half_shape(scheme, order, rows, cols);
                assert_eq!(
                    (hr, hc) == (0, 0),
                    in_place(scheme, order, rows),
                    "{scheme:?} {order:?}"
                );
                // the full step (as `surface::refine_grid_into` runs it)
                let c = scheme.curve();
                let mut half = Grid::filled(hr, hc, DVec3::ZERO);
                let mut next = Grid::filled(c.refined_len(rows), c.refined_len(cols), DVec3::ZERO);
                refine_grid_window(
                    scheme,
                    order,
                    &g,
                    &mut half,
                    &mut next,
                    DirtyWindow::all(rows, cols),
                );
                let windows = [
                    DirtyWindow::cell(35, 40),
                    DirtyWindow {
                        rows: Span::new(5, 60),
                        cols: Span::new(3, 85),
                    },
                    DirtyWindow::cell(0, 0),
                    DirtyWindow::cell(69, 89),
                    DirtyWindow {
                        rows: Span::new(1, 2),
                        cols: Span::all(cols),
                    },
                    DirtyWindow {
                        rows: Span::new(30, 69),
                        cols: Span::new(0, 50),
                    },
                ];
                for (i, w) in windows.into_iter().enumerate() {
                    for r in w.rows.iter() {
                        for c in w.cols.iter() {
                            let a = (r * 31 + c * 17 + i) as f64 * 0.21;
                            g.set(r, c, DVec3::new(a.sin(), 0.4, a.cos()).normalize());
                        }
                    }
                    let out = refine_grid_window(scheme, order, &g, &mut half, &mut next, w);
                    let parallel = out.area() >= PARALLEL_MIN_ENTRIES;
                    assert_eq!(
                        next,
                        refine_grid_gathered(scheme, order, &g),
                        "{scheme:?} {order:?} window {i} (parallel: {parallel})"
                    );
                }
            }
        }
    }

    #[test]
    fn span_refine_covers_every_dependent_output() {
        // Perturb one input at a time and check every output that moved is in the span.
        for scheme in [
            CurveScheme::Chaikin,
            CurveScheme::CubicBSpline,
            CurveScheme::FourPoint { omega: 1.0 },
        ] {
            for n in 3..9 {
                let base: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
                let mut a = Vec::new();
                scheme.refine_scalars(&base, &mut a);
                for j in 0..n {
                    let mut p = base.clone();
                    p[j] += 1.0;
                    let mut b = Vec::new();
                    scheme.refine_scalars(&p, &mut b);
                    let span = Span::single(j).refine(scheme, n);
                    for k in 0..a.len() {
                        if a[k] != b[k] {
                            assert!(
                                span.lo <= k && k <= span.hi,
                                "{scheme:?} n={n} input {j} moves output {k} outside {span:?}"
                            );
                        }
                    }
                }
            }
        }
    }
}
