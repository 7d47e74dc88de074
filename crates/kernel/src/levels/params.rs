//! Parameter grids (docs/math.md §4): an arc-length parameter `s` per control tangent,
//! strictly increasing along its row; per row a `t` (arc length along the
//! initial curve where the streamline starts) and an anchor arc length `σ`
//! (level 0's `s` of the anchor column, or where the row's limit starts or
//! ends when that column is its first or last: [`anchor_sigma`]). All are
//! subdivided with the same scheme as the tangents, as planar scalars, so
//! every refined tangent has its `s` and every refined row its `(t, σ)`.

use crate::curve::scheme::CurveScheme;
use crate::error::{KernelError, Place};
use crate::grid::Grid;
use crate::levels::surface::{BlendOrder, SurfaceScheme, refine_grid_into};

/// `σ` of a level-0 row anchored at column `anchor` (docs/math.md §4, "The
/// anchor"): the column's `s`, except at the row's first or last column,
/// where it is the arc length at which the row's limit starts or ends
/// ([`CurveScheme::limit_ends`]). An approximating scheme shortens the row
/// at every step, so its first column's `s` ends up before the row: placed
/// there, the row would reach `σ` along its first tangent, which turns at
/// every level, and the whole row would move by a length that only halves
/// per level. At the limit start the row's own point is anchored at every
/// level, and it sits on the initial curve. The 4-point rule keeps its ends:
/// `σ` is the column's `s`, bit for bit.
pub fn anchor_sigma(curve: CurveScheme, row: &[f64], anchor: usize) -> f64 {
    let (a, b) = curve.limit_ends(row);
    if anchor == 0 {
        a
    } else if anchor + 1 == row.len() {
        b
    } else {
        row[anchor]
    }
}

/// The parameters of one subdivision level.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamGrid {
    /// Arc length of each tangent along its streamline.
    pub s: Grid<f64>,
    /// Arc length along the initial curve of each row.
    pub t: Vec<f64>,
    /// Arc length of each row's anchor point.
    pub sigma: Vec<f64>,
}

impl ParamGrid {
    /// Level-0 parameters: `s` per tangent, `t` per row, and the anchor column
    /// that gives `σ` under `scheme` ([`anchor_sigma`]). Checks finiteness,
    /// sizes and strict increase.
    pub fn new(
        s: Grid<f64>,
        t: Vec<f64>,
        anchor: usize,
        scheme: SurfaceScheme,
    ) -> Result<Self, KernelError> {
        if t.len() != s.rows() {
            return Err(KernelError::LengthMismatch {
                what: "row parameters t",
                got: t.len(),
                expected: s.rows(),
            });
        }
        if anchor >= s.cols() {
            return Err(KernelError::IndexOutOfRange {
                what: "anchor column",
                index: anchor,
                len: s.cols(),
            });
        }
        for (r, &tv) in t.iter().enumerate() {
            if !tv.is_finite() {
                return Err(KernelError::NonFiniteParameter {
                    what: "row parameter t",
                    at: Place::Grid { row: r, col: 0 },
                });
            }
            if !crate::limits::in_range(tv) {
                return Err(KernelError::TooLargeValue {
                    what: "row parameter t",
                    value: tv,
                });
            }
        }
        if let Some(&v) = s
            .data()
            .iter()
            .find(|v| v.is_finite() && !crate::limits::in_range(**v))
        {
            return Err(KernelError::TooLargeValue {
                what: "arc-length parameter s",
                value: v,
            });
        }
        let curve = scheme.curve();
        let sigma = (0..s.rows())
            .map(|r| anchor_sigma(curve, s.row(r), anchor))
            .collect();
        let p = ParamGrid { s, t, sigma };
        p.check(0)?;
        Ok(p)
    }

    /// Uniform parameters: each row from 0 to `length` in equal intervals, rows
    /// at `t = 0 ..= width` evenly.
    pub fn uniform(
        rows: usize,
        cols: usize,
        length: f64,
        width: f64,
        anchor: usize,
        scheme: SurfaceScheme,
    ) -> Result<Self, KernelError> {
        let s = (0..rows * cols)
            .map(|i| length * (i % cols) as f64 / (cols - 1).max(1) as f64)
            .collect();
        let t = (0..rows)
            .map(|r| width * r as f64 / (rows - 1).max(1) as f64)
            .collect();
        ParamGrid::new(Grid::new(rows, cols, s)?, t, anchor, scheme)
    }

    /// Every `s` finite and strictly increasing along its row; `t`, `σ` finite.
    pub fn check(&self, level: u32) -> Result<(), KernelError> {
        // the common case in one branch-free pass; the loop below names the place
        // strictly increasing (false on NaN) between finite ends ⇒ all finite
        let ok = (0..self.s.rows()).all(|r| {
            let row = self.s.row(r);
            let ends = row.first().is_none_or(|v| v.is_finite())
                && row.last().is_none_or(|v| v.is_finite());
            let rises = row.windows(2).fold(0u32, |bad, w| {
                bad + u32::from(w[1] <= w[0] || w[1].is_nan())
            });
            ends && rises == 0
        });
        if ok {
            return Ok(());
        }
        for r in 0..self.s.rows() {
            let row = self.s.row(r);
            for (c, &v) in row.iter().enumerate() {
                if !v.is_finite() {
                    return Err(KernelError::NonFiniteParameter {
                        what: "arc-length parameter s",
                        at: Place::Grid { row: r, col: c },
                    });
                }
                if c > 0 && v <= row[c - 1] {
                    return Err(KernelError::ParamsNotIncreasing {
                        level,
                        at: Place::Grid { row: r, col: c },
                    });
                }
            }
        }
        Ok(())
    }

    /// One step with the surface's scheme (scalars commute, so the order only
    /// affects rounding; it is kept equal to the tangents' for consistency).
    /// Refused if `s` stops increasing strictly (very uneven intervals under the 4-point rule).
    pub fn refine(
        &self,
        scheme: SurfaceScheme,
        order: BlendOrder,
        level: u32,
    ) -> Result<Self, KernelError> {
        let mut out = ParamGrid {
            s: Grid::filled(0, 0, 0.0),
            t: Vec::new(),
            sigma: Vec::new(),
        };
        self.refine_into(scheme, order, level, &mut Grid::filled(0, 0, 0.0), &mut out)?;
        Ok(out)
    }

    /// [`Self::refine`] into buffers kept by the caller (`half` is the `s`
    /// grid of the first direction); `out` is overwritten.
    pub(crate) fn refine_into(
        &self,
        scheme: SurfaceScheme,
        order: BlendOrder,
        level: u32,
        half: &mut Grid<f64>,
        out: &mut ParamGrid,
    ) -> Result<(), KernelError> {
        let c = scheme.curve();
        refine_grid_into(scheme, order, &self.s, half, &mut out.s);
        c.refine_scalars(&self.t, &mut out.t);
        c.refine_scalars(&self.sigma, &mut out.sigma);
        out.check(level)
    }
}
