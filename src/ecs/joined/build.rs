//! The systems that build the joined patches (docs/math.md §11), in
//! [`crate::ecs::ModelSet::Mesh`]:
//! * [`track_joined`] writes a joined patch's changed net handles into its
//!   [`JoinedDesign`] (only the cells that differ; nothing when nothing does);
//! * [`build_joined`] brings up to date, as
//!   [`crate::scene::design::document_build::stacks`] builds them (`chain`, `side`,
//!   `g2_run`), exactly the patches whose own design changed, whose G2 run
//!   has a changed member or whose parent was rebuilt, and the seam report
//!   of every join with a rebuilt side. Every patch but a G2 run's members
//!   and the first patch's pipeline is kept between edits ([`super::kept`]):
//!   its levels are re-blended inside the edit's window, a join's fix (a
//!   chain's `t` and G1 seam column, a side join's `σ` and G1 projection)
//!   is made again and compared, and only the rows whose tangents,
//!   parameters or start moved are placed again, bit for bit the whole
//!   join's; a patch none of whose rows moved is left as it was (not marked
//!   changed), and so are the patches on it. A G2 run is kept as one merged
//!   net ([`super::g2`]). The first patch's stack is kept between edits and
//!   brought up to date in place from its incremental pipeline
//!   ([`super::first`]) when its [`PatchKernel`] or the display depth
//!   changes; with details, fine tuning or interpolated tangents it is kept
//!   as the others are.
//!
//! A G2 run from the first patch: the run is one merged net (docs/math.md
//! §11.1), so the first patch's cut of it ([`PatchSurface`]) differs from
//! its one-patch surface near the seam (an approximating scheme's, and the
//! 4-point rule's last segments, see the merged net's next columns). While
//! the run is built the first patch's own incremental pipeline waits
//! ([`super::shows_run_cut`]: the blend stage builds it afresh once the
//! patch no longer heads a built run), so an edit of the head costs the
//! run's update alone; the drawing, the handles, the seam report and the
//! per-patch output read the [`PatchSurface`], which equals
//! [`crate::scene::Document::build`]'s.

use super::components::*;
use super::first::FirstPipeline;
use super::g2::G2RunState;
use super::kept::{KeptPatch, PatchWork};
use crate::ecs::patch::{
    ArcParam, Direction, PatchIndex, PatchKernel, PatchStructure, PatchTuning, SurfaceHandle,
};
use crate::scene::design::model::{effective_design, interpolates};
use bevy::prelude::*;
use std::collections::HashMap;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::joins::PatchParts;
use streamline_kernel::joins::RowSpan;
use streamline_kernel::joins::g2_state::G2State;
use streamline_kernel::joins::patch_state::{PatchState, Start};
use streamline_kernel::joins::seam::{PatchMesh, chain_seam, side_seam};
use streamline_kernel::joins::{Continuity, Edge, Stack};
use streamline_kernel::levels::multires::Details;
use streamline_kernel::streamline::surface_mesh::normals_window;
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
    Option<&'static mut G2RunState>,
    Option<Ref<'static, JoinedFeatures>>,
    Option<Ref<'static, PatchTuning>>,
    Option<&'static mut KeptPatch>,
);

/// Rebuilds the patches whose inputs changed and the seams they touch
/// (module documentation).
pub(crate) fn build_joined(
    mut commands: Commands,
    meter: Res<crate::ecs::meter::CpuMeter>,
    structure: Query<Ref<PatchStructure>, Without<Joined>>,
    mut pipeline: FirstPipeline,
    mut patches: Query<PatchRow>,
) {
    // what the first patch's pipeline changed, gathered every frame
    pipeline.track();
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
                || r.8.as_ref().is_some_and(|f| f.is_changed())
                || r.9.as_ref().is_some_and(|t| t.is_changed())
                || r.5.built.is_none()
        })
        .collect();
    let run_changed: Vec<bool> = (0..n)
        .map(|i| (0..n).any(|k| run[k] == run[i] && own[k]))
        .collect();
    if !run_changed.contains(&true) {
        return;
    }
    // a G2 run's members, by their run's first patch
    let head = |i: usize| parent[i].is_none() && run.iter().filter(|&&r| r == i).count() > 1;
    let heads: Vec<bool> = (0..n).map(head).collect();
    // the stacks and states of the patches kept between edits (every patch
    // but a G2 run's members and the first patch's pipeline), moved out to
    // be updated in place (super::kept), and put back unless replaced
    let kept_path: Vec<bool> = (0..n)
        .map(|i| !heads[run[i]] && (parent[i].is_some() || rows[i].3.is_none()))
        .collect();
    let mut kept: Vec<Option<Stack>> = vec![None; n];
    let mut kstates: Vec<Option<PatchState>> = vec![None; n];
    for i in 0..n {
        if let Some(k) = rows[i].10.as_mut() {
            kstates[i] = k.bypass_change_detection().0.take();
        }
        if !kept_path[i] {
            continue;
        }
        if let Some(Ok(s)) = rows[i].5.bypass_change_detection().built.take() {
            kept[i] = Some(s);
        }
    }
    // the patches built through their state this frame (the others' states
    // are dropped when another path builds them)
    let mut by_state = vec![false; n];
    // a G2 run's state and its members' stacks, moved out to be updated in
    // place (super::g2)
    let mut g2_old: Vec<Option<Stack>> = vec![None; n];
    let mut states: Vec<Option<G2State>> = vec![None; n];
    for i in 0..n {
        if !heads[run[i]] || !run_changed[i] {
            continue;
        }
        if let Some(c) = rows[i].7.as_mut() {
            states[i] = c.bypass_change_detection().0.take();
        }
        if let Some(Ok(s)) = rows[i].5.bypass_change_detection().built.take() {
            g2_old[i] = Some(s);
        }
    }
    // the first patch's stack and normals, moved out to be brought up to
    // date in place (super::first)
    let mut first_old: Vec<Option<(Stack, Vec<DVec3>)>> = vec![None; n];
    for i in 0..n {
        if parent[i].is_some() || heads[i] || !run_changed[i] || rows[i].3.is_none() {
            continue;
        }
        // with details, fine tuning or interpolated tangents it is kept as
        // the others are (super::kept), its normals redone in its moved rows
        let adds = rows[i].3.as_ref().is_some_and(|k| {
            !k.details.is_empty() || interpolates(&k.design, st.interpolate_tangents)
        }) || rows[i].9.as_ref().is_some_and(|t| t.0.is_some());
        let r = rows[i].5.bypass_change_detection();
        if let Some(Ok(s)) = r.built.take() {
            let normals = match adds {
                true => Vec::new(),
                false => std::mem::take(&mut r.normals),
            };
            first_old[i] = Some((s, normals));
        }
    }
    let mut in_run = vec![false; n];
    // each patch's design as built: with its tangents interpolated when it
    // interpolates them (docs/math.md §7: border tangents, so seam columns, kept)
    let interpolated: Vec<Option<Design>> = (0..n)
        .map(|i| {
            let raw =
                (rows[i].3.as_deref().map(|k| &k.design)).or(rows[i].4.as_deref().map(|j| &j.0))?;
            let on = match (&rows[i].8, rows[i].3.is_some()) {
                (Some(f), _) => f.interpolate_tangents,
                (None, true) => st.interpolate_tangents,
                (None, false) => false,
            };
            interpolates(raw, on).then(|| effective_design(raw, true))
        })
        .collect();
    let design = |i: usize| -> Option<&Design> {
        (interpolated[i].as_ref())
            .or(rows[i].3.as_deref().map(|k| &k.design))
            .or(rows[i].4.as_deref().map(|j| &j.0))
    };
    // what patch i adds to its net: details and fine tuning
    let details = |i: usize| -> Option<&Details> {
        (rows[i].3.as_deref().map(|k| &k.details)).or(rows[i].8.as_deref().map(|f| &f.details))
    };
    let tuning = |i: usize| -> Option<&SurfaceTuning> {
        match (&rows[i].9, &rows[i].8) {
            (Some(t), _) => t.0.as_ref(),
            (None, Some(f)) => f.tuning.as_ref(),
            (None, None) => None,
        }
    };
    let adds = |i: usize| {
        interpolated[i].is_some()
            || details(i).is_some_and(|d| !d.is_empty())
            || tuning(i).is_some()
    };
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
    // what each patch's update through its state did
    let mut work: Vec<Option<PatchWork>> = vec![None; n];
    // the display depth's mesh normals of a rebuilt patch, when it has them already
    let mut normals: Vec<Option<Vec<DVec3>>> = vec![None; n];
    // the display depth's rows an update placed again (`None`: all)
    let mut moved: Vec<Option<RowSpan>> = vec![None; n];
    // the first column of those rows placed again (a G2 run's member; 0: all)
    let mut moved_col: Vec<usize> = vec![0; n];
    // per depth, the rows whose tangents or parameters may have changed (`None`: all)
    let mut level_rows: Vec<Option<Vec<Option<RowSpan>>>> = vec![None; n];
    for i in 0..n {
        // a patch is rebuilt when its G2 run changed, or (below) when its
        // parent was rebuilt and moved what it reads
        let parent_new = parent[i].is_some_and(|(a, ..)| a < i && new[a].is_some());
        if new[i].is_some() || in_run[i] || !(run_changed[i] || parent_new) {
            continue;
        }
        let Some(b) = design(i) else {
            new[i] = Some(Err(format!("patch `{}` has no design", name(i))));
            continue;
        };
        let built = match parent[i] {
            None if heads[i] => {
                // a G2 run from patch i: one merged net, cut at its seams
                // (not the pipeline's surface: its stack is made afresh next)
                if rows[i].3.is_some() {
                    pipeline.forget();
                }
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
                let designs: Vec<PatchParts> = (owned.iter().zip(&members))
                    .map(|(d, &k)| PatchParts::new(d, details(k), tuning(k)))
                    .collect();
                let old: Option<Vec<Stack>> = members.iter().map(|&k| g2_old[k].take()).collect();
                match super::g2::run(&mut states[i], &designs, depth, old) {
                    Ok(b) => {
                        let each = (b.stacks.into_iter().zip(b.changed))
                            .zip(b.rows.into_iter().zip(b.cols));
                        for (&k, ((s, ch), (span, col))) in members.iter().zip(each) {
                            in_run[k] = true;
                            if ch {
                                moved[k] = span;
                                moved_col[k] = col;
                                level_rows[k].clone_from(&b.levels);
                                work[k] =
                                    Some(PatchWork::of_run(b.reblended, b.levels.is_none(), span));
                                new[k] = Some(Ok(s));
                            } else {
                                // not changed: put back as it is
                                kept[k] = Some(s);
                            }
                        }
                    }
                    Err(e) => {
                        let last = *members.last().unwrap_or(&i);
                        for &k in &members {
                            in_run[k] = true;
                            new[k] = Some(Err(located(last, &e)));
                        }
                    }
                }
                continue;
            }
            None => {
                // the first patch's stack, kept and brought up to date from
                // its pipeline (super::first)
                // (whole, with what it adds: the pipeline's stack is its net's)
                let made = match rows[i].3.is_some() && !adds(i) {
                    true => pipeline.stack(rows[i].0, b, depth, first_old[i].take()),
                    false => None,
                };
                match made {
                    Some((s, n)) => {
                        normals[i] = Some(n);
                        Ok(s)
                    }
                    None => {
                        if rows[i].3.is_some() {
                            pipeline.forget();
                        }
                        // a patch on its own curve, kept between edits
                        let old = kept[i].take().or(first_old[i].take().map(|(s, _)| s));
                        let parts = PatchParts::new(b, details(i), tuning(i));
                        let mut state = kstates[i].take();
                        by_state[i] = true;
                        let done = super::kept::update(&mut state, parts, Start::Curve, depth, old);
                        kstates[i] = state;
                        match done {
                            Ok(done) => {
                                match super::kept::settle(
                                    i,
                                    done,
                                    &mut work,
                                    &mut moved,
                                    &mut level_rows,
                                ) {
                                    Ok(s) => Ok(s),
                                    Err(s) => {
                                        kept[i] = Some(s);
                                        continue;
                                    }
                                }
                            }
                            Err(e) => Err(located(i, &e)),
                        }
                    }
                }
            }
            Some((_, Edge::End, Continuity::G2)) => Err(located(
                i,
                &"a G2 chain is one net from a patch with its own curve; join it with G1",
            )),
            Some((a, edge, c)) => {
                let (kept_lo, kept_hi) = kept.split_at_mut(i);
                // A as it is now: rebuilt, or as it was
                let was = (kept_lo[a].as_ref()).or(rows[a].5.stack());
                let sa = match new[a].as_ref() {
                    Some(built) => built.as_ref().ok(),
                    None => was,
                };
                let Some(sa) = sa else {
                    new[i] = Some(Err(format!(
                        "patch `{}` starts on `{}`, which is not built; fix `{}` first",
                        name(i),
                        name(a),
                        name(a)
                    )));
                    continue;
                };
                let Some(da) = design(a) else { continue };
                // a chain's seam column is one handle of both (a side join's is B's own)
                let joined_b;
                let b = if edge == Edge::End {
                    joined_b = shared_seam(da, b, c);
                    &joined_b
                } else {
                    b
                };
                let parts = PatchParts::new(b, details(i), tuning(i));
                let start = Start::Edge {
                    a_design: da,
                    a: sa,
                    edge,
                    continuity: c,
                };
                let mut state = kstates[i].take();
                by_state[i] = true;
                let done = super::kept::update(&mut state, parts, start, depth, kept_hi[0].take());
                kstates[i] = state;
                match done {
                    Ok(done) => {
                        match super::kept::settle(i, done, &mut work, &mut moved, &mut level_rows) {
                            Ok(s) => Ok(s),
                            Err(s) => {
                                kept_hi[0] = Some(s);
                                continue;
                            }
                        }
                    }
                    Err(e) => Err(located(i, &e)),
                }
            }
        };
        new[i] = Some(built);
    }
    // every rebuilt patch's normals (the seams and the drawing read them):
    // a rejoin's in its moved rows ± 1 only, from the old ones, and from
    // one column before the first one placed again (a normal reads its
    // row's and its column's neighbours, docs/math.md §4), bit for bit the whole
    let mut written: Vec<Option<RowSpan>> = vec![None; n];
    for i in 0..n {
        if normals[i].is_none()
            && let Some(Ok(s)) = &new[i]
        {
            let p = s.finest_points();
            let last = p.rows().saturating_sub(1);
            let old = &mut rows[i].5.bypass_change_detection().normals;
            let (mut out, lo, hi, c0) = match moved[i] {
                Some(span) if old.len() == p.data().len() && span.hi <= last => {
                    let (lo, hi) = (span.lo.saturating_sub(1), (span.hi + 1).min(last));
                    written[i] = Some(RowSpan { lo, hi });
                    (std::mem::take(old), lo, hi, moved_col[i].saturating_sub(1))
                }
                _ => (vec![DVec3::Z; p.data().len()], 0, last, 0),
            };
            normals_window(p.data(), p.cols(), lo, hi, c0, &mut out);
            normals[i] = Some(out);
        }
    }
    // the seams with a rebuilt side, from the two meshes at the display depth
    let mut seams: Vec<Option<Option<streamline_kernel::joins::SeamReport>>> = vec![None; n];
    for i in 0..n {
        let Some((a, edge, _)) = parent[i] else {
            continue;
        };
        if new[i].is_none() && new[a].is_none() {
            continue;
        }
        let mesh = |k: usize| {
            let (points, normals) = match &new[k] {
                Some(b) => (b.as_ref().ok()?.finest_points(), normals[k].as_deref()?),
                None => (
                    (kept[k].as_ref())
                        .or_else(|| rows[k].5.built.as_ref()?.as_ref().ok())?
                        .finest_points(),
                    rows[k].5.normals.as_slice(),
                ),
            };
            (normals.len() == points.data().len()).then_some(PatchMesh { points, normals })
        };
        seams[i] = Some(match (mesh(a), mesh(i)) {
            (Some(ma), Some(mb)) => match edge {
                Edge::End => chain_seam(ma, mb).ok(),
                side => Some(side_seam(ma, side, mb)),
            },
            _ => None,
        });
    }
    let new_was: Vec<Option<()>> = new.iter().map(|b| b.as_ref().map(|_| ())).collect();
    for (i, r) in rows.iter_mut().enumerate() {
        if let Some(b) = new[i].take() {
            r.5.built = Some(b);
            r.5.normals = normals[i].take().unwrap_or_default();
            r.5.rows = written[i];
            (r.5.placed, r.5.placed_from) = (moved[i], moved_col[i]);
            r.5.level_rows = level_rows[i].take();
        } else if let Some(s) = kept[i].take() {
            // not rebuilt: put back, not marked changed
            r.5.bypass_change_detection().built = Some(Ok(s));
        }
        // the kept levels back (a new one inserted), or dropped when
        // another path built the patch
        let st = kstates[i]
            .take()
            .filter(|_| by_state[i] || new_was[i].is_none());
        match r.10.as_mut() {
            Some(k) => k.bypass_change_detection().0 = st,
            None if st.is_some() => {
                commands.entity(r.0).try_insert(KeptPatch(st));
            }
            None => {}
        }
        if let Some(w) = work[i].take() {
            commands.entity(r.0).try_insert(w);
        }
        if let (Some(report), Some(state)) = (seams[i].take(), r.6.as_mut()) {
            state.report = report;
        }
        // the G2 run's state back on its head (a new one inserted), and
        // dropped from a patch that no longer heads a run
        match (r.7.as_mut(), states[i].take()) {
            (Some(c), st @ Some(_)) => c.bypass_change_detection().0 = st,
            (None, Some(st)) => {
                commands.entity(r.0).try_insert(G2RunState(Some(st)));
            }
            (Some(_), None) if !heads[i] => {
                commands.entity(r.0).try_remove::<G2RunState>();
            }
            _ => {}
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
