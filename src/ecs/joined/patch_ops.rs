//! The patch edits (docs/math.md §11) on a document's state ([`DocState`]):
//! `AddPatch`, `SetPatch`, `RemovePatch`, `RenamePatch`, `HidePatch`, and
//! the checks of a handle edit on a later patch. The edit stage applies
//! them ([`crate::ecs::edit`]) for the editor and for scripts alike; the
//! world follows when the state is written back ([`super::world_io`]). A
//! refused edit is an error naming the patch and the fix, and leaves the
//! state as it was.

use crate::ecs::edit_state::{DocState, JoinedState, StartState};
use crate::scene::design::document_build::stacks;
use crate::scene::design::document_check::check_document;
use crate::scene::edits::patch_edit::PatchEdit;
use crate::scene::files::format_v3::{EdgeSpec, patch_name_problem};
use crate::scene::files::patch_text::PatchText;
use streamline_kernel::joins::edge_curve::EdgeCurve;
use streamline_kernel::joins::{Continuity, Edge};
use streamline_kernel::streamline::integrate::polyline_length;
use streamline_kernel::{DVec3, Design, Grid};

/// A frame's document being edited: its state and the index of the patch
/// that handle edits act on.
#[derive(Debug, Clone)]
pub struct DocWork {
    /// The document.
    pub state: DocState,
    /// The active patch's index (0: the first patch).
    pub active: usize,
}

fn find(state: &DocState, name: &str) -> Result<usize, String> {
    state
        .index(name)
        .ok_or_else(|| format!("no patch `{name}`; the patches are {}", state.listed()))
}

fn fresh_name(state: &DocState, name: &str) -> Result<(), String> {
    if let Some(p) = patch_name_problem(name) {
        return Err(p);
    }
    if state.index(name).is_some() {
        return Err(format!(
            "a patch is already named `{name}`; choose another name"
        ));
    }
    Ok(())
}

/// Applies a patch edit to `work`: `Ok(what was done)`, or why not (the
/// state unchanged).
pub fn apply(work: &mut DocWork, edit: &PatchEdit) -> Result<String, String> {
    let state = &mut work.state;
    match edit {
        PatchEdit::AddPatch {
            name,
            from: (a, edge),
            continuity,
            rows,
            cols,
            length,
        } => {
            fresh_name(state, name)?;
            let parent = find(state, a)?;
            let c = continuity.to_kernel();
            let design = new_design(state, parent, *edge, c, *rows, *cols, length.0)
                .map_err(|m| format!("AddPatch `{name}` on `{a}`: {m}"))?;
            state.joined.push(JoinedState {
                name: name.clone(),
                start: StartState::Edge {
                    parent,
                    edge: edge.to_kernel(),
                    continuity: c,
                },
                design,
                details: Default::default(),
                tuning: None,
                interpolate_tangents: false,
                hidden: false,
            });
            if let Err(m) = check(state) {
                state.joined.pop();
                return Err(format!("AddPatch `{name}` on `{a}`: {m}"));
            }
            Ok(format!(
                "added patch `{name}` on `{a}` ({}, {})",
                edge.to_kernel().name(),
                c.name()
            ))
        }
        PatchEdit::SetPatch(name) => {
            work.active = find(state, name)?;
            Ok(format!("edits act on `{name}`"))
        }
        PatchEdit::RemovePatch(name) => {
            let i = find(state, name)?;
            if i == 0 {
                return Err(format!(
                    "`{name}` is the first patch, which every other starts from; remove the others instead"
                ));
            }
            let children: Vec<String> = (state.children(i).iter())
                .map(|&k| format!("`{}`", state.name(k)))
                .collect();
            if !children.is_empty() {
                return Err(format!(
                    "{} starts on `{name}`; remove {} first",
                    children.join(", "),
                    if children.len() == 1 { "it" } else { "them" }
                ));
            }
            state.joined.remove(i - 1);
            for j in &mut state.joined {
                if let StartState::Edge { parent, .. } = &mut j.start
                    && *parent > i
                {
                    *parent -= 1;
                }
            }
            work.active = match work.active {
                k if k == i => 0,
                k if k > i => k - 1,
                k => k,
            };
            Ok(format!("removed patch `{name}`"))
        }
        PatchEdit::RenamePatch(from, to) => {
            let i = find(state, from)?;
            fresh_name(state, to)?;
            match i {
                0 => state.first_name.clone_from(to),
                _ => state.joined[i - 1].name.clone_from(to),
            }
            Ok(format!("renamed `{from}` to `{to}`"))
        }
        PatchEdit::HidePatch(name, hide) => {
            let i = find(state, name)?;
            match i {
                0 => state.first_hidden = *hide,
                _ => state.joined[i - 1].hidden = *hide,
            }
            Ok(edit.label())
        }
    }
}

/// The document's checks across patches (docs/math.md §11, "Bad input"):
/// what a file of it would be refused for when read back, so that no edit
/// makes a design that cannot be saved and opened again.
pub fn check(state: &DocState) -> Result<(), String> {
    if state.joined.is_empty() {
        return Ok(());
    }
    let doc = state.to_document();
    check_document(&doc, std::path::Path::new("design"), &PatchText::new("")).map_err(|e| e.message)
}

/// The net of a new patch on patch `parent`'s `edge`: a chain takes its
/// rows and `t` and continues its last column; a side join's rows leave
/// the streamline across it, their `t` spread over 5–95 % of its length
/// (the shorter of its polyline at the display depth and at depth 0, so
/// the file reads back: docs/math.md §11).
fn new_design(
    state: &DocState,
    parent: usize,
    edge: EdgeSpec,
    continuity: Continuity,
    rows: usize,
    cols: usize,
    length: f64,
) -> Result<Design, String> {
    if cols < 2 || rows < 2 {
        return Err(format!(
            "a net of {rows} × {cols}; give at least 2 rows and 2 columns"
        ));
    }
    if !(length.is_finite() && length > 0.0) {
        return Err(format!("length {length}; give a positive length"));
    }
    let a = state.design(parent);
    let (ar, ac) = (a.net().rows(), a.net().cols());
    let (t, dirs): (Vec<f64>, Vec<DVec3>) = match edge.to_kernel() {
        Edge::End => {
            if rows != ar {
                return Err(format!(
                    "a chain has the rows of the patch it starts on: give rows: {ar}"
                ));
            }
            (
                a.params().t.clone(),
                (0..ar).map(|r| a.net().get(r, ac - 1)).collect(),
            )
        }
        side => {
            if continuity == Continuity::G2 {
                return Err(
                    "G2 on a side edge is refused (future work, docs/math.md §11); use G1".into(),
                );
            }
            let depth = state.first.display_depth;
            let built = stacks(&state.to_document(), depth)
                .map_err(|e| format!("the design is not built ({}); fix it first", e.message))?;
            let stack = &built[parent];
            let pts = stack.finest_points();
            let r = if side == Edge::First {
                0
            } else {
                pts.rows() - 1
            };
            let inner = if side == Edge::First {
                1.min(pts.rows() - 1)
            } else {
                pts.rows().saturating_sub(2)
            };
            let at_depth0 = EdgeCurve::of(stack, 0, side).map_or(f64::INFINITY, |c| c.length());
            let len = polyline_length(pts.row(r)).min(at_depth0);
            let mid = pts.cols() / 2;
            let across = (pts.get(r, mid) - pts.get(inner, mid))
                .try_normalize()
                .unwrap_or(DVec3::Z);
            let t = (0..rows)
                .map(|j| len * (0.05 + 0.9 * j as f64 / (rows - 1) as f64))
                .collect();
            (t, vec![across; rows])
        }
    };
    let mut net = Grid::filled(rows, cols, DVec3::X);
    let mut s = Grid::filled(rows, cols, 0.0);
    for (r, &dir) in dirs.iter().enumerate() {
        for c in 0..cols {
            net.set(r, c, dir);
            s.set(r, c, length * c as f64 / (cols - 1) as f64);
        }
    }
    Design::new(&net, s, t, 0, a.scheme(), a.order(), a.initial().clone())
        .map_err(|e| e.to_string())
}

/// Why a handle edit of later patch `i` at cell `(row, col)` is refused, if
/// it is: outside its net, or its seam column when that is one handle with
/// the patch it starts on (a G1 or G2 chain, docs/math.md §11.1): that
/// handle is turned on the patch it starts on, whose last column it is.
/// Column `col` of later patch `i` at an edit depth above 0: refused when
/// it is the seam column of a G1 or G2 chain (its parent's last column at
/// every depth, docs/math.md §11.1), naming the handle to turn instead.
pub fn check_joined_seam(state: &DocState, i: usize, col: usize) -> Result<(), String> {
    let j = &state.joined[i - 1];
    if let StartState::Edge {
        parent,
        edge: Edge::End,
        continuity,
    } = j.start
        && continuity != Continuity::G0
        && col == 0
    {
        let a = state.name(parent);
        return Err(format!(
            "column 0 of `{}` is its {} seam with `{a}`, whose last column it is at every depth (one handle, docs/math.md §11.1); turn it on `{a}` (SetPatch(\"{a}\"), its last column)",
            j.name,
            continuity.name()
        ));
    }
    Ok(())
}

/// Cell `(row, col)` of later patch `i`'s control net: inside the net, and
/// not the seam column of a G1 or G2 chain (one handle with its parent's).
pub fn check_joined_cell(state: &DocState, i: usize, row: usize, col: usize) -> Result<(), String> {
    let j = &state.joined[i - 1];
    let (rows, cols) = (j.design.net().rows(), j.design.net().cols());
    if row >= rows || col >= cols {
        return Err(format!(
            "`{}` has a {rows} × {cols} net; ({row}, {col}) is outside it",
            j.name
        ));
    }
    if let StartState::Edge {
        parent,
        edge: Edge::End,
        continuity,
    } = j.start
        && continuity != Continuity::G0
        && col == 0
    {
        let a = state.name(parent);
        let last = state.design(parent).net().cols() - 1;
        return Err(format!(
            "column 0 of `{}` is its {} seam with `{a}`, one handle of both patches (docs/math.md §11); turn it on `{a}` (SetPatch(\"{a}\"), handle ({row}, {last}))",
            j.name,
            continuity.name()
        ));
    }
    Ok(())
}
