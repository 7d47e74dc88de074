//! Where the net grows next (`docs/math.md §12`, "Growing the net"): the
//! insertion that the mesh's chords suggest once the design is close, or a
//! row at a point much further than its row's tangent error explains, or
//! else the one the cells' scores suggest; then the nodes it gives.

use super::deviation::Measured;
use super::insert::{Insert, apply, choose};
use super::plan::Plan;
use super::state::{Growth, Round};
use super::stops::at_cap;
use crate::fit::measure::{breaks, interval};
use crate::levels::surface::SurfaceScheme;

/// The insertion after the net measured as `net`, among intervals not
/// blocked and directions not at their cap (`full`: the columns', the
/// rows'); `no_gain` when that net came no closer than the last, `flip` to
/// go the other way in the worst cell.
pub(super) fn next_insertion(
    plan: &Plan<'_, '_>,
    g: &mut Growth<'_, '_>,
    net: &Measured,
    no_gain: bool,
    flip: bool,
    (col_full, row_full): (bool, bool),
) -> Option<Insert> {
    // a point much further than its row's tangent error explains is
    // off because its row is (its start, its length: what is blended
    // across the rows): a row there
    let (psi_w, d_w, e_w, _) = net.m.worst;
    // (not again right after such a row brought the design no closer;
    // with Doo–Sabin too, whose limit rows take the reference's lengths,
    // not with Catmull–Clark, whose distance along the rows that the
    // tangents do not explain is its columns' doing: a cylinder, whose
    // rows are all alike, needs columns)
    let rows_mend = !matches!(plan.opts.scheme, SurfaceScheme::CatmullClark);
    let across = (rows_mend && net.chord.is_none() && d_w > plan.tol && e_w < 0.5 * d_w)
        .then(|| Insert::Row(interval(&breaks(&g.nodes.rows), psi_w)))
        .filter(|_| !(no_gain && g.last_across));
    g.last_across = across.is_some();
    match net.chord.or(across) {
        Some(ins @ Insert::Row(_)) if !row_full && !g.blocked.contains(&ins) => Some(ins),
        Some(ins @ Insert::Column(_)) if !col_full && !g.blocked.contains(&ins) => Some(ins),
        _ => choose(&net.m, &g.blocked, col_full, row_full, flip),
    }
}

/// Makes the insertion `next_insertion` chooses (graded), blocking it when
/// it changes no node; the growth ends, at the net's cap, when none is left.
pub(super) fn grow_next(
    plan: &Plan<'_, '_>,
    g: &mut Growth<'_, '_>,
    net: Measured,
    no_gain: bool,
    flip: bool,
    full: (bool, bool),
) -> Round {
    let Some(ins) = next_insertion(plan, g, &net, no_gain, flip, full) else {
        let b = g.best.as_ref().map_or(net.key(), |b| b.key);
        return Round::Stop(Some(at_cap(plan, b)));
    };
    let before = g.nodes.clone();
    apply(&mut g.nodes, ins, plan.cap_rows, plan.cap_cols);
    if g.nodes == before {
        g.blocked.push(ins);
    }
    g.last = Some((before, net.m, ins));
    Round::Grow
}
