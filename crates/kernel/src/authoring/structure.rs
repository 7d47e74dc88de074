//! Inserting and deleting a control row (a streamline) or column
//! (`docs/math.md §9`, Inserting a streamline).
//!
//! **Inside** the net, between lines `i − 1` and `i`, the new line is the one
//! a single step of the current scheme puts there, across the lines alone
//! (for a row: down each control column; for a column: along each row), and
//! its parameters come from the same step on the scalars (`s` per entry, and
//! for a row also `t`; `σ` follows, being `s` of the anchor column):
//! * 4-point (Kobbelt): the insert of Eq. 61 (the 3-point end rule on the
//!   first and last legs, the midpoint when there are two lines);
//! * cubic B-spline (Catmull–Clark): the edge point `mid(t_{i−1}, t_i)` (Eq. 57);
//! * Chaikin (Doo–Sabin): a step puts `¼` and `¾` points on the leg; the new
//!   line is their midpoint, the leg's midpoint `mid(t_{i−1}, t_i)`, where
//!   the quadratic B-spline limit touches the leg.
//!
//! **Outside** (before line 0 or after the last), the new line continues the
//! great circles through the two nearest lines by the same angle,
//! `blend(t_{j−1}, t_j, 2)`, and the parameters by the same spacing
//! (`2 v_j − v_{j−1}`). Along a row `s` then keeps increasing for a new
//! column; for a new row each `s` interval is extended the same way,
//! `2Δ_j − Δ_{j−1}`, except where that is not positive (rows of very
//! different lengths): there the interval continues their ratio,
//! `Δ_j² / Δ_{j−1}`, so the new row's `s` increases too.
//!
//! A new line already lies near the surface, so an insert moves it little
//! (measured on the cars in `tests/authoring_structure.rs`). Deleting removes
//! the line's tangents and parameters; the net keeps at least 2 × 2. The
//! anchor stays on the same column where it can (a deleted anchor column
//! passes the anchor to the column that takes its place, or the new last one).

use super::check_net_size;
use crate::curve::scheme::{CurveScheme, Prepared, Stencil};
use crate::error::KernelError;
use crate::grid::Grid;
use crate::levels::design::Design;
use crate::levels::params::ParamGrid;
use crate::sphere::blend::blend;
use glam::DVec3;

/// Rows (streamlines, across `t`) or columns (along `s`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// A control row: one streamline.
    Row,
    /// A control column: one tangent of every streamline.
    Column,
}

impl Axis {
    /// `row` or `column`.
    pub fn name(self) -> &'static str {
        match self {
            Axis::Row => "row",
            Axis::Column => "column",
        }
    }
}

/// Where a new line goes among `n ≥ 2` lines when it gets index `at`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Slot {
    /// Between lines `at − 1` and `at`, by this stencil.
    Inside(Stencil),
    /// Before line 0.
    Before,
    /// After line `n − 1`.
    After,
}

fn slot(scheme: CurveScheme, n: usize, at: usize) -> Slot {
    if at == 0 {
        Slot::Before
    } else if at >= n {
        Slot::After
    } else {
        match scheme {
            CurveScheme::FourPoint { .. } => Slot::Inside(scheme.stencil(n, 2 * at - 1)),
            _ => Slot::Inside(Stencil::Mid(at - 1)),
        }
    }
}

fn new_tangent(p: &Prepared, w: Slot, n: usize, f: impl Fn(usize) -> DVec3) -> DVec3 {
    match w {
        Slot::Inside(st) => p.tangent(st, f),
        Slot::Before => blend(f(1), f(0), 2.0),
        Slot::After => blend(f(n - 2), f(n - 1), 2.0),
    }
}

fn new_scalar(scheme: CurveScheme, w: Slot, n: usize, f: impl Fn(usize) -> f64) -> f64 {
    match w {
        Slot::Inside(st) => crate::curve::scalar::apply(scheme, st, f),
        Slot::Before => 2.0 * f(0) - f(1),
        Slot::After => 2.0 * f(n - 1) - f(n - 2),
    }
}

impl Design {
    /// The number of control rows or columns.
    pub fn count(&self, axis: Axis) -> usize {
        match axis {
            Axis::Row => self.net.rows(),
            Axis::Column => self.net.cols(),
        }
    }

    /// A copy with a new row or column at index `at` (`0 ..= count`; `0` and
    /// `count` insert outside the net), its tangents and parameters as the
    /// module doc says. Refused: `at` past `count`, a net past 64 a side, or
    /// parameters that would stop increasing (4-point on very uneven intervals).
    pub fn inserted(&self, axis: Axis, at: usize) -> Result<Design, KernelError> {
        let (rows, cols) = (self.net.rows(), self.net.cols());
        let n = self.count(axis);
        if at > n {
            return Err(KernelError::IndexOutOfRange {
                what: match axis {
                    Axis::Row => "insert position (row)",
                    Axis::Column => "insert position (column)",
                },
                index: at,
                len: n + 1,
            });
        }
        let scheme = self.scheme.curve();
        let prep = Prepared::new(scheme);
        let w = slot(scheme, n, at);
        let s = &self.params.s;
        let (net, s_new, t, anchor) = match axis {
            Axis::Row => {
                check_net_size(rows + 1, cols)?;
                let row: Vec<DVec3> = (0..cols)
                    .map(|c| new_tangent(&prep, w, n, |r| self.net.get(r, c)))
                    .collect();
                let mut srow: Vec<f64> = (0..cols)
                    .map(|c| new_scalar(scheme, w, n, |r| s.get(r, c)))
                    .collect();
                if !matches!(w, Slot::Inside(_))
                    && srow
                        .windows(2)
                        .any(|p| p[1].partial_cmp(&p[0]) != Some(std::cmp::Ordering::Greater))
                {
                    let (near, far) = if at == 0 { (0, 1) } else { (n - 1, n - 2) };
                    srow = extend_intervals(s.row(near), s.row(far), srow[0]);
                }
                let tv = new_scalar(scheme, w, n, |r| self.params.t[r]);
                let mut t = self.params.t.clone();
                t.insert(at, tv);
                (
                    insert_row(&self.net, at, &row),
                    insert_row(s, at, &srow),
                    t,
                    self.anchor,
                )
            }
            Axis::Column => {
                check_net_size(rows, cols + 1)?;
                let col: Vec<DVec3> = (0..rows)
                    .map(|r| new_tangent(&prep, w, n, |c| self.net.get(r, c)))
                    .collect();
                let scol: Vec<f64> = (0..rows)
                    .map(|r| new_scalar(scheme, w, n, |c| s.get(r, c)))
                    .collect();
                let anchor = self.anchor + usize::from(self.anchor >= at);
                (
                    insert_col(&self.net, at, &col),
                    insert_col(s, at, &scol),
                    self.params.t.clone(),
                    anchor,
                )
            }
        };
        self.with_net(net, s_new, t, anchor)
    }

    /// A copy without row or column `at`. Refused: `at` out of range, or a
    /// net that would keep fewer than 2 rows or columns.
    pub fn deleted(&self, axis: Axis, at: usize) -> Result<Design, KernelError> {
        let n = self.count(axis);
        if at >= n {
            return Err(KernelError::IndexOutOfRange {
                what: axis.name(),
                index: at,
                len: n,
            });
        }
        if n <= 2 {
            return Err(KernelError::NetTooSmall {
                what: axis.name(),
                count: n,
            });
        }
        let s = &self.params.s;
        match axis {
            Axis::Row => {
                let mut t = self.params.t.clone();
                t.remove(at);
                self.with_net(delete_row(&self.net, at), delete_row(s, at), t, self.anchor)
            }
            Axis::Column => {
                let anchor = if self.anchor > at {
                    self.anchor - 1
                } else {
                    self.anchor.min(n - 2)
                };
                self.with_net(
                    delete_col(&self.net, at),
                    delete_col(s, at),
                    self.params.t.clone(),
                    anchor,
                )
            }
        }
    }

    /// The same design on another net (tangents already unit, kept bit for
    /// bit), with its parameters checked.
    pub(crate) fn with_net(
        &self,
        net: Grid<DVec3>,
        s: Grid<f64>,
        t: Vec<f64>,
        anchor: usize,
    ) -> Result<Design, KernelError> {
        if let Some((i, _)) = net.data().iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(KernelError::NonFiniteTangent {
                at: crate::Place::Grid {
                    row: i / net.cols(),
                    col: i % net.cols(),
                },
            });
        }
        self.scheme.check_depth(net.rows(), net.cols(), 0)?;
        let params = ParamGrid::new(s, t, anchor, self.scheme)?;
        Ok(Design {
            net,
            params,
            anchor,
            ..self.clone()
        })
    }
}

/// A row of `s` from `start`, each interval `2Δ_near − Δ_far` where that is
/// positive, else `Δ_near² / Δ_far` (module doc).
fn extend_intervals(near: &[f64], far: &[f64], start: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(near.len());
    out.push(start);
    for k in 1..near.len() {
        let (a, b) = (near[k] - near[k - 1], far[k] - far[k - 1]);
        let lin = 2.0 * a - b;
        let d = if lin > 0.0 { lin } else { a * a / b };
        out.push(out[k - 1] + d);
    }
    out
}

fn insert_row<T: Copy>(g: &Grid<T>, at: usize, row: &[T]) -> Grid<T> {
    let cols = g.cols();
    let mut data = g.data().to_vec();
    data.splice(at * cols..at * cols, row.iter().copied());
    Grid::new(g.rows() + 1, cols, data).expect("one row more")
}

fn insert_col<T: Copy>(g: &Grid<T>, at: usize, col: &[T]) -> Grid<T> {
    let mut data = Vec::with_capacity(g.rows() * (g.cols() + 1));
    for (r, &v) in col.iter().enumerate().take(g.rows()) {
        let row = g.row(r);
        data.extend_from_slice(&row[..at]);
        data.push(v);
        data.extend_from_slice(&row[at..]);
    }
    Grid::new(g.rows(), g.cols() + 1, data).expect("one column more")
}

fn delete_row<T: Copy>(g: &Grid<T>, at: usize) -> Grid<T> {
    let cols = g.cols();
    let mut data = g.data().to_vec();
    data.drain(at * cols..(at + 1) * cols);
    Grid::new(g.rows() - 1, cols, data).expect("one row less")
}

fn delete_col<T: Copy>(g: &Grid<T>, at: usize) -> Grid<T> {
    let mut data = Vec::with_capacity(g.rows() * (g.cols() - 1));
    for r in 0..g.rows() {
        let row = g.row(r);
        data.extend_from_slice(&row[..at]);
        data.extend_from_slice(&row[at + 1..]);
    }
    Grid::new(g.rows(), g.cols() - 1, data).expect("one column less")
}
