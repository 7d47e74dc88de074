//! Where the net grows (`docs/math.md §12`, "Growing the net"): the
//! insertion of a column or a row that the cells' scores or the mesh's
//! chords suggest, and the insertion itself, graded so that neighbouring
//! intervals stay within a factor of two.

use crate::fit::construct::Nodes;
use crate::fit::measure::{Measure, breaks, interval};
use crate::fit::options::MAX_NET_SIDE;
use crate::levels::design::Level;
use crate::streamline::integrate::point_arclength;
use glam::DVec3;

/// What to insert: a column in a column interval, or a row in a row interval.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Insert {
    Column(usize),
    Row(usize),
}

/// Where the reference is furthest from the mesh, the insertion that
/// refines the mesh's coarser direction there: across the rows if the
/// mesh bends more between rows than along them (its chords are further
/// from the surface that way), else along them.
pub(super) fn chord_insert(
    nodes: &Nodes,
    lt: f64,
    level: &Level,
    points: &[DVec3],
    at: (usize, usize),
) -> Insert {
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
    let width = cols + 1;
    let (r, k) = (
        at.0.clamp(1, rows.saturating_sub(2).max(1)),
        at.1.clamp(1, width - 2),
    );
    let p = |i: usize, j: usize| points[(i.min(rows - 1)) * width + j.min(width - 1)];
    let across = if rows >= 3 {
        (p(r + 1, k) - 2.0 * p(r, k) + p(r - 1, k)).length()
    } else {
        0.0
    };
    let along = (p(r, k + 1) - 2.0 * p(r, k) + p(r, k - 1)).length();
    if across > along {
        let psi = level.params.t[at.0.min(rows - 1)] / lt;
        Insert::Row(interval(&breaks(&nodes.rows), psi))
    } else {
        let s = level.params.s.row(at.0.min(rows - 1));
        let span = (s[cols - 1] - s[0]).max(f64::MIN_POSITIVE);
        let x = (point_arclength(s, at.1.min(cols)) - s[0]) / span;
        Insert::Column(interval(&breaks(&nodes.cols), x))
    }
}

/// The insertion the scores suggest, among intervals not blocked and
/// directions not at their cap.
pub(super) fn choose(
    m: &Measure,
    blocked: &[Insert],
    col_full: bool,
    row_full: bool,
    flip: bool,
) -> Option<Insert> {
    let mut cells: Vec<(f64, usize, usize)> = Vec::new();
    for (a, (on, bt)) in m.on_nodes.iter().zip(&m.between).enumerate() {
        for (b, (x, y)) in on.iter().zip(bt).enumerate() {
            cells.push((x.max(*y), a, b));
        }
    }
    cells.sort_by(|p, q| q.0.total_cmp(&p.0));
    for (_, a, b) in cells {
        let (on, bt) = (m.on_nodes[a][b], m.between[a][b]);
        let prefer_row = (bt > 2.0 * on) != flip;
        let order = if prefer_row {
            [Insert::Row(a), Insert::Column(b)]
        } else {
            [Insert::Column(b), Insert::Row(a)]
        };
        for ins in order {
            let full = match ins {
                Insert::Column(_) => col_full,
                Insert::Row(_) => row_full,
            };
            if !full && !blocked.contains(&ins) {
                return Some(ins);
            }
        }
    }
    None
}

/// Halves interval `i` of `xs`, then any neighbour more than twice as long
/// as the interval next to it, while the count stays within `cap`.
fn insert_graded(xs: &mut Vec<f64>, i: usize, cap: usize) {
    if i + 1 >= xs.len() || xs.len() >= cap {
        return;
    }
    xs.insert(i + 1, 0.5 * (xs[i] + xs[i + 1]));
    for _ in 0..4 * MAX_NET_SIDE {
        if xs.len() >= cap {
            return;
        }
        let split = (0..xs.len().saturating_sub(2)).find_map(|k| {
            let (l, r) = (xs[k + 1] - xs[k], xs[k + 2] - xs[k + 1]);
            if l > 2.0 * r {
                Some(k)
            } else if r > 2.0 * l {
                Some(k + 1)
            } else {
                None
            }
        });
        match split {
            Some(k) => xs.insert(k + 1, 0.5 * (xs[k] + xs[k + 1])),
            None => return,
        }
    }
}

/// Inserts a row or column node in cell `ins` (graded).
pub(super) fn apply(nodes: &mut Nodes, ins: Insert, cap_rows: usize, cap_cols: usize) {
    let (xs, cell, cap) = match ins {
        Insert::Column(b) => (&mut nodes.cols, b, cap_cols),
        Insert::Row(a) => (&mut nodes.rows, a, cap_rows),
    };
    let mut full = breaks(xs);
    let ends = full.len() - xs.len();
    insert_graded(&mut full, cell, cap + ends);
    if xs.first().is_some_and(|&x| x > 0.0) {
        full.remove(0);
    }
    if xs.last().is_some_and(|&x| x < 1.0) {
        full.pop();
    }
    *xs = full;
}
