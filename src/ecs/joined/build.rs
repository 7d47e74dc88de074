//! The systems that build the joined patches (docs/math.md §11), in
//! [`crate::ecs::ModelSet::Mesh`]:
//! * [`track_joined`] writes a joined patch's changed net handles into its
//!   [`JoinedDesign`] (only the cells that differ; nothing when nothing does);
//! * [`build_joined`] rebuilds, through the kernel's joins as
//!   [`crate::scene::document_build::stacks`] does (`chain`, `side`,
//!   `g2_run`), exactly the patches whose own design changed, whose parent
//!   was rebuilt, or whose G2 run has a changed member, and the seam report
//!   of every join with a rebuilt side. The first patch's stack is made from
//!   its [`PatchKernel`] (which the incremental pipeline keeps up to date),
//!   rebuilt when that or the display depth changes.
//!
//! A G2 run from the first patch: the run is one merged net (docs/math.md
//! §11.1), so the first patch's cut of it ([`PatchSurface`]) differs from
//! its one-patch surface near the seam (an approximating scheme's, and the
//! 4-point rule's last segments, see the merged net's next columns). The
//! incremental pipeline's [`crate::ecs::SurfaceData`] stays the one-patch
//! surface, unchanged; the seam report and the per-patch output read the
//! [`PatchSurface`], which equals [`crate::scene::Document::build`]'s.

use super::components::*;
use crate::ecs::patch::{
    ArcParam, Direction, PatchIndex, PatchKernel, PatchStructure, SurfaceHandle,
};
use bevy::prelude::*;
use std::collections::HashMap;
use streamline_kernel::joins::chain::chain;
use streamline_kernel::joins::merged::g2_run;
use streamline_kernel::joins::side::side;
use streamline_kernel::joins::{Continuity, Edge, JoinError, Stack, seam_at};
use streamline_kernel::{DVec3, Design};

/// A joined patch's net handles whose value changed since the last run.
type ChangedJoinedNet<'w, 's> = Query<
    'w,
    's,
    (&'static SurfaceHandle, &'static Direction, &'static ChildOf),
    (
        With<JoinedHandle>,
        Or<(Changed<Direction>, Changed<ArcParam>)>,
    ),
>;

/// Writes the changed handles of each joined patch into its design: a
/// direction with [`Design::set_tangent`], a row whose `s` changed with
/// [`Design::set_s_row`]; the design is marked changed only when a value differs.
pub(crate) fn track_joined(
    changed: ChangedJoinedNet,
    params: Query<&ArcParam, With<JoinedHandle>>,
    mut patches: Query<(&PatchIndex, &mut JoinedDesign), With<Joined>>,
) {
    let mut by_patch: HashMap<Entity, Vec<(SurfaceHandle, DVec3)>> = HashMap::new();
    for (h, d, parent) in &changed {
        by_patch.entry(parent.parent()).or_default().push((*h, d.0));
    }
    for (patch, cells) in by_patch {
        let Ok((index, mut design)) = patches.get_mut(patch) else {
            continue;
        };
        let mut d = design.0.clone();
        let mut differs = false;
        let mut rows = Vec::new();
        for (h, dir) in cells {
            if d.net().get(h.row, h.col) != dir && d.set_tangent(h.row, h.col, dir).is_ok() {
                differs = true;
            }
            let s = params.get(index.surface.get(h.row, h.col)).map(|a| a.0);
            if s.is_ok_and(|s| d.params().s.get(h.row, h.col).to_bits() != s.to_bits())
                && !rows.contains(&h.row)
            {
                rows.push(h.row);
            }
        }
        for r in rows {
            let s: Option<Vec<f64>> = (0..index.surface.cols())
                .map(|c| params.get(index.surface.get(r, c)).ok().map(|a| a.0))
                .collect();
            if let Some(s) = s
                && d.set_s_row(r, &s).is_ok()
            {
                differs = true;
            }
        }
        if differs {
            design.0 = d;
        }
    }
}

/// What [`build_joined`] reads and writes of every patch of a document.
type PatchRow = (
    Entity,
    &'static PatchSlot,
    Ref<'static, PatchStart>,
    Option<Ref<'static, PatchKernel>>,
    Option<Ref<'static, JoinedDesign>>,
    &'static mut PatchSurface,
    Option<&'static mut SeamState>,
);

/// Rebuilds the patches whose inputs changed and the seams they touch
/// (module documentation).
pub(crate) fn build_joined(
    meter: Res<crate::ecs::meter::CpuMeter>,
    structure: Query<Ref<PatchStructure>, Without<Joined>>,
    mut patches: Query<PatchRow>,
) {
    if patches.is_empty() {
        return;
    }
    let _meter = meter.start();
    let Ok(st) = structure.single() else {
        return;
    };
    let depth = st.display_depth;
    let mut rows: Vec<_> = patches.iter_mut().collect();
    rows.sort_by_key(|r| r.1.index);
    let n = rows.len();
    let at: HashMap<Entity, usize> = rows.iter().enumerate().map(|(i, r)| (r.0, i)).collect();
    let design = |i: usize| -> Option<&Design> {
        (rows[i].3.as_deref().map(|k| &k.design)).or(rows[i].4.as_deref().map(|j| &j.0))
    };
    // where each starts, as indices
    let parent: Vec<Option<(usize, Edge, Continuity)>> = (0..n)
        .map(|i| match *rows[i].2 {
            PatchStart::Curve => None,
            PatchStart::Edge {
                parent,
                edge,
                continuity,
            } => at.get(&parent).map(|&a| (a, edge, continuity)),
        })
        .collect();
    let g2 = |i: usize| matches!(parent[i], Some((a, Edge::End, Continuity::G2)) if a < i);
    // the G2 run each patch is in, by its first patch
    let mut run = vec![0; n];
    for i in 0..n {
        run[i] = match parent[i] {
            Some((a, ..)) if g2(i) => run[a],
            _ => i,
        };
    }
    let own: Vec<bool> = (0..n)
        .map(|i| {
            let r = &rows[i];
            st.is_changed()
                || r.2.is_changed()
                || r.3.as_ref().is_some_and(|k| k.is_changed())
                || r.4.as_ref().is_some_and(|j| j.is_changed())
                || r.5.built.is_none()
        })
        .collect();
    let mut dirty = vec![false; n];
    for i in 0..n {
        let run_changed = (0..n).any(|k| run[k] == run[i] && own[k]);
        let parent_dirty = parent[i].is_some_and(|(a, ..)| a < i && dirty[a]);
        dirty[i] = run_changed || parent_dirty;
    }
    if !dirty.contains(&true) {
        return;
    }
    let name = |i: usize| rows[i].1.name.as_str();
    let located = |i: usize, e: &dyn std::fmt::Display| match parent[i] {
        Some((a, edge, c)) => format!(
            "patch `{}` starts on `{}` (A = `{}`, B = `{}`, edge {}, {}): {e}",
            name(i),
            name(a),
            name(a),
            name(i),
            edge.name(),
            c.name()
        ),
        None => format!("patch `{}`: {e}", name(i)),
    };
    let mut new: Vec<Option<Result<Stack, String>>> = vec![None; n];
    for i in 0..n {
        if !dirty[i] || new[i].is_some() {
            continue;
        }
        let Some(b) = design(i) else {
            new[i] = Some(Err(format!("patch `{}` has no design", name(i))));
            continue;
        };
        let built = match parent[i] {
            None if run.iter().filter(|&&r| r == i).count() > 1 => {
                // a G2 run from patch i: one merged net, cut at its seams
                let members: Vec<usize> = (0..n).filter(|&k| run[k] == i).collect();
                // each member's seam column is the previous one's last (one handle)
                let mut owned: Vec<Design> = Vec::with_capacity(members.len());
                for &k in &members {
                    let Some(dk) = design(k) else { break };
                    owned.push(match owned.last() {
                        Some(prev) => shared_seam(prev, dk, Continuity::G2),
                        None => dk.clone(),
                    });
                }
                let designs: Vec<&Design> = owned.iter().collect();
                match g2_run(&designs, depth) {
                    Ok(stacks) => {
                        for (&k, s) in members.iter().zip(stacks) {
                            new[k] = Some(Ok(s));
                        }
                    }
                    Err(e) => {
                        let last = *members.last().unwrap_or(&i);
                        for &k in &members {
                            new[k] = Some(Err(located(last, &e)));
                        }
                    }
                }
                continue;
            }
            None => Stack::build(b, depth).map_err(|e| located(i, &JoinError::Kernel(e))),
            Some((a, edge, c)) => {
                let sa = match new[a].as_ref().or(rows[a].5.built.as_ref()) {
                    Some(Ok(s)) => s,
                    _ => {
                        new[i] = Some(Err(format!(
                            "patch `{}` starts on `{}`, which is not built; fix `{}` first",
                            name(i),
                            name(a),
                            name(a)
                        )));
                        continue;
                    }
                };
                let Some(da) = design(a) else { continue };
                match (edge, c) {
                    (Edge::End, Continuity::G2) => Err(located(
                        i,
                        &"a G2 chain is one net from a patch with its own curve; join it with G1",
                    )),
                    (Edge::End, c) => {
                        chain(da, sa, &shared_seam(da, b, c), c).map_err(|e| located(i, &e))
                    }
                    (edge, c) => side(sa, b, edge, c).map_err(|e| located(i, &e)),
                }
            }
        };
        new[i] = Some(built);
    }
    // the seams with a rebuilt side
    let mut seams: Vec<Option<Option<streamline_kernel::joins::SeamReport>>> = vec![None; n];
    for i in 0..n {
        let Some((a, edge, _)) = parent[i] else {
            continue;
        };
        if !dirty[i] && !dirty[a] {
            continue;
        }
        let pick = |k: usize| match new[k].as_ref().or(rows[k].5.built.as_ref()) {
            Some(Ok(s)) => Some(s),
            _ => None,
        };
        seams[i] = Some(match (pick(a), pick(i)) {
            (Some(sa), Some(sb)) => seam_at(sa, sb, edge, depth).ok(),
            _ => None,
        });
    }
    for (i, r) in rows.iter_mut().enumerate() {
        if let Some(b) = new[i].take() {
            r.5.built = Some(b);
        }
        if let (Some(report), Some(state)) = (seams[i].take(), r.6.as_mut()) {
            state.report = report;
        }
    }
}

/// For a G1 or G2 chain, `B` with its first control column `A`'s last: the
/// seam column is one handle of both (docs/math.md §11.1), so turning `A`'s
/// turns `B`'s. A G0 chain takes `B` as it is.
fn shared_seam(a: &Design, b: &Design, c: Continuity) -> Design {
    let mut b = b.clone();
    if c != Continuity::G0 {
        let last = a.net().cols() - 1;
        for r in 0..a.net().rows().min(b.net().rows()) {
            let v = a.net().get(r, last);
            if b.net().get(r, 0) != v {
                let _ = b.set_tangent(r, 0, v);
            }
        }
    }
    b
}
