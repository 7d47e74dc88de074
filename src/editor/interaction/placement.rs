//! Placing the first patch's handles: the one system that writes [`Placed`]
//! on its handle entities (with `set_if_neq`, so that only the handles that
//! moved are marked changed; a joined patch's are placed by
//! [`super::placement_joined`]), spawns the edit depth's [`RefinedHandle`] entities and
//! the mirrored copies, and despawns them when they are no longer shown.
//! A turn of control tangents at edit depth 0 re-places only their rows (a
//! streamline is a running sum along its row, Eq. 65 of `docs/math.md`); a
//! new shape, `s`, initial curve, tuning, mirror, edit depth or active patch
//! re-places every handle. While a joined patch is the active one
//! ([`HandleLayout::active`]), the first patch's handles are placed as at
//! edit depth 0 (they are drawn dimmed, and refined cells are not shown).

use super::handles::{Handle, HandleId};
use super::placed::{HandleLayout, MirroredHandle, Placed, RefinedHandle};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::joined::ActivePatch;
use crate::ecs::patch::PatchRef;
use crate::ecs::patch::{
    ArcParam, Direction, InitialHandle, Joined, JoinedHandle, Patch, SurfaceHandle,
};
use bevy::prelude::*;
use streamline_kernel::DVec3;
use streamline_kernel::finetune::streamline::point_by_fraction;
use streamline_kernel::levels::incremental::{LevelState, place_row_tuned, place_rows_tuned};
use streamline_kernel::streamline::initial_curve::InitialCurve;

/// The handles of one level, placed on the streamlines of `initial`; with
/// the mirror on (level 0 of the doubled net, `docs/math.md §9`) its first
/// `reflected` rows are the reflected copies, returned apart.
fn level_handles(
    patch: &PatchRef,
    l: &LevelState,
    scale: f64,
    initial: &InitialCurve,
    reflected: usize,
) -> (Vec<Handle>, Vec<Handle>) {
    let (rows, cols) = l.shape();
    let tuning = patch.tuning();
    let s = &l.params.s;
    let span: f64 = (0..rows)
        .map(|r| (s.get(r, cols - 1) - s.get(r, 0)) / (cols.max(2) - 1) as f64)
        .sum::<f64>()
        / rows.max(1) as f64;
    let length = (span * scale).max(1e-6);
    let mut all = Vec::new();
    place_rows_tuned(initial, &l.tangents, &l.params, tuning, &mut all);
    let mut out = Vec::with_capacity(rows * cols);
    let mut copies = Vec::with_capacity(reflected * cols);
    // the designer's control tangents, read from their handle entities
    let net = patch.net();
    for r in 0..rows {
        let pts = &all[r * (cols + 1)..(r + 1) * (cols + 1)];
        for c in 0..cols {
            let base = point_by_fraction(pts, s.row(r), s.get(r, c));
            if r < reflected {
                // row r of the doubled net reflects control row `reflected − r`
                copies.push(Handle {
                    id: HandleId::tangent(0, reflected - r, c),
                    base,
                    dir: l.tangents.get(r, c),
                    length,
                });
                continue;
            }
            let row = r - reflected;
            // control arrows show the designer's tangents (the interpolated
            // net, when that option is on, is what subdivision starts from)
            let dir = if l.level == 0 && row < net.rows() && c < net.cols() {
                net.get(row, c)
            } else {
                l.tangents.get(r, c)
            };
            out.push(Handle {
                id: HandleId::tangent(l.level, row, c),
                base,
                dir,
                length,
            });
        }
    }
    (out, copies)
}

/// The initial curve's control tangents, each at the curve's point at its
/// Greville abscissa `ξ_i = (u_{i+1} + … + u_{i+k−1}) / (k − 1)` of the QI
/// knot vector (where the QI curve's tangent is nearest `t_i`), drawn `length` long.
fn initial_handles(patch: &PatchRef, length: f64) -> Vec<Handle> {
    let curve = patch.design().initial();
    let qi = curve.qi();
    let (k, u) = (qi.order(), qi.knots());
    qi.tangents()
        .iter()
        .enumerate()
        .map(|(i, &dir)| {
            let xi = u[i + 1..i + k].iter().sum::<f64>() / (k - 1) as f64;
            Handle {
                id: HandleId::initial(i),
                base: curve.point(xi * curve.length()),
                dir,
                length,
            }
        })
        .collect()
}

/// The longest an arrow is drawn: a tenth of the surface's size, taken as
/// the diagonal of its longest streamline (`s` at level 0) and its initial
/// curve, which no turn of a tangent changes (so a turn moves only its row's
/// handles, [`move_rows`]).
fn length_cap(level: &LevelState, initial: &InitialCurve) -> f64 {
    let s = &level.params.s;
    let longest = (0..s.rows())
        .map(|r| s.get(r, s.cols() - 1) - s.get(r, 0))
        .fold(0.0, f64::max);
    (longest.hypot(initial.length()) * 0.1).max(1e-6)
}

/// Control tangents of the first patch whose handle entity's direction
/// changed (a joined patch's are placed by [`super::placement_joined`]).
type TurnedNet<'w, 's> =
    Query<'w, 's, &'static SurfaceHandle, (Changed<Direction>, Without<JoinedHandle>)>;

/// Handle entities of the net or the initial curve not placed yet.
type Unplaced<'w, 's> = Query<
    'w,
    's,
    (),
    (
        Or<(With<SurfaceHandle>, With<InitialHandle>)>,
        Without<Placed>,
        Without<JoinedHandle>,
    ),
>;

/// Control tangents of the first patch whose `s` changed.
type TurnedS<'w, 's> = Query<
    'w,
    's,
    (),
    (
        With<SurfaceHandle>,
        Changed<ArcParam>,
        Without<JoinedHandle>,
    ),
>;

/// What else moves every handle: a new `s`, a new initial curve, a handle
/// entity not placed yet, another active patch.
#[derive(bevy::ecs::system::SystemParam)]
pub(super) struct MovesAll<'w, 's> {
    s: TurnedS<'w, 's>,
    curve: Query<'w, 's, (), (With<InitialHandle>, Changed<Direction>)>,
    unplaced: Unplaced<'w, 's>,
    active: Res<'w, ActivePatch>,
    joined: Query<'w, 's, (), (With<Patch>, With<Joined>)>,
}

/// The entities the placement writes: every [`Placed`], the copies' and the
/// refined cells' own components.
#[derive(bevy::ecs::system::SystemParam)]
pub(super) struct PlacedEntities<'w, 's> {
    commands: Commands<'w, 's>,
    placed: Query<'w, 's, &'static mut Placed>,
    mirrored: Query<'w, 's, &'static mut MirroredHandle>,
    refined: Query<'w, 's, (), With<RefinedHandle>>,
}

impl PlacedEntities<'_, '_> {
    /// Writes handle `h`'s place on entity `e` (marked changed only when it
    /// differs), or gives `e` its id and place when it has none yet.
    fn put(&mut self, e: Entity, h: &Handle) {
        let p = Placed::from(h);
        match self.placed.get_mut(e) {
            Ok(mut old) => {
                old.set_if_neq(p);
            }
            Err(_) => {
                self.commands.entity(e).try_insert((h.id, p));
            }
        }
    }

    /// Despawns the entities `v` (the refined cells or the copies).
    fn despawn(&mut self, v: &[Entity]) {
        for &e in v {
            self.commands.entity(e).try_despawn();
        }
    }
}

/// Places the handles again when what they are drawn from changed: see the
/// module's doc. The refined cells' entities are spawned here when the edit
/// depth or its level's shape changed, the copies' when the mirror's did.
#[allow(clippy::too_many_arguments)]
pub(super) fn place(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    levels: Query<(&SubdivisionLevel, Ref<LevelData>)>,
    turned: TurnedNet,
    all: MovesAll,
    mut layout: ResMut<HandleLayout>,
    mut out: PlacedEntities,
) {
    let _meter = meter.start();
    let st = patch.structure();
    // a joined patch active: the first patch's handles are placed at depth
    // 0, dimmed (its refined cells are not shown)
    let (active, active_joined) = resolve_active(all.active.0, patch.entity(), &all.joined);
    let edit = if active_joined { 0 } else { st.edit_depth };
    let whole = layout.active != Some(active)
        || patch.structure_changed()
        || patch.placement_changed()
        || patch.tuning_changed()
        || !all.s.is_empty()
        || !all.curve.is_empty()
        || !all.unplaced.is_empty()
        || layout.edit_depth != edit
        || !layout.placed;
    let changed = levels
        .iter()
        .any(|(l, d)| (l.0 == 0 || l.0 == edit) && d.is_changed());
    if !whole && !changed {
        return;
    }
    let find = |level: u32| levels.iter().find(|(l, _)| l.0 == level).map(|(_, d)| d);
    let Some(base) = find(0) else {
        return;
    };
    let by_rows = !whole
        && edit == 0
        && !st.mirror
        && patch.tuning().is_none()
        && !crate::scene::model::interpolates(patch.design(), st.interpolate_tangents);
    if by_rows && !turned.is_empty() {
        let mut rows: Vec<usize> = turned.iter().map(|h| h.row).collect();
        rows.sort_unstable();
        rows.dedup();
        if let Some(n) = move_rows(&patch, &base.0, &rows, layout.cap, &mut out) {
            layout.moved = n;
            return;
        }
    }
    // mirrored: the levels are the doubled design's, placed on its initial
    // curve (the scene's own, reflected for the other half)
    let shown = if st.mirror {
        match crate::scene::model::shown_design(patch.design(), st.interpolate_tangents, true) {
            Ok(d) => Some(d),
            Err(_) => return,
        }
    } else {
        None
    };
    let initial = shown
        .as_ref()
        .map_or(patch.design().initial(), |d| d.initial());
    let reflected = match &shown {
        Some(_) => st.rows.saturating_sub(1),
        None => 0,
    };
    let (mut controls, mut mirrored) = level_handles(&patch, &base.0, 0.7, initial, reflected);
    // long intervals (a 3×3 net) would give arrows as large as the scene: cap
    // them at a tenth of the surface's size
    let cap = length_cap(&base.0, initial);
    let clamp = |v: &mut Vec<Handle>| {
        for a in v.iter_mut() {
            a.length = a.length.min(cap);
        }
    };
    clamp(&mut controls);
    clamp(&mut mirrored);
    let refined = if edit == 0 {
        None
    } else {
        match find(edit) {
            Some(d) => {
                let (mut h, _) = level_handles(&patch, &d.0, 0.8, initial, 0);
                clamp(&mut h);
                Some((d.0.shape(), h))
            }
            None => return,
        }
    };
    // the initial curve's arrows: a good part of its spacing between
    // tangents, so they stand out of the column of control arrows there
    let curve = patch.design().initial();
    let spacing = curve.length() / (curve.qi().tangents().len().max(2) - 1) as f64;
    let initial = initial_handles(&patch, (0.6 * spacing).min(2.0 * cap).max(1e-6));
    // write them on their entities
    let index = patch.index();
    for h in &controls {
        if h.id.row < index.surface.rows() && h.id.col < index.surface.cols() {
            out.put(index.surface.get(h.id.row, h.id.col), h);
        }
    }
    for (h, &e) in initial.iter().zip(&index.initial) {
        out.put(e, h);
    }
    place_copies(&patch, &mirrored, &mut layout, &mut out);
    let refined_count = refined.as_ref().map_or(0, |(_, h)| h.len());
    place_refined(&patch, edit, refined, &mut layout, &mut out);
    layout.edit_depth = edit;
    layout.cap = cap;
    layout.placed = true;
    layout.active = Some(active);
    layout.active_joined = active_joined;
    layout.moved = controls.len() + mirrored.len() + initial.len() + refined_count;
}

/// The patch whose handles are shown and picked, and whether it is a
/// joined one: `active` when it names a joined patch, else the first patch
/// `first` (`None`, the first patch's own entity, or a patch no longer there).
pub(super) fn resolve_active(
    active: Option<Entity>,
    first: Entity,
    joined: &Query<(), (With<Patch>, With<Joined>)>,
) -> (Entity, bool) {
    match active {
        Some(e) if e != first && joined.contains(e) => (e, true),
        _ => (first, false),
    }
}

/// The mirrored copies on their entities: the same entities when their
/// number is the same, else new ones.
fn place_copies(
    patch: &PatchRef,
    copies: &[Handle],
    layout: &mut HandleLayout,
    out: &mut PlacedEntities,
) {
    let alive = layout.mirrored.len() == copies.len()
        && layout.mirrored.iter().all(|&e| out.mirrored.contains(e));
    if !alive {
        let old = std::mem::take(&mut layout.mirrored);
        out.despawn(&old);
        layout.mirrored = copies
            .iter()
            .map(|h| {
                let c = (MirroredHandle { of: h.id }, Placed::from(h));
                out.commands.spawn((c, ChildOf(patch.entity()))).id()
            })
            .collect();
        return;
    }
    for (h, &e) in copies.iter().zip(&layout.mirrored) {
        if let Ok(mut m) = out.mirrored.get_mut(e) {
            m.set_if_neq(MirroredHandle { of: h.id });
        }
        if let Ok(mut p) = out.placed.get_mut(e) {
            p.set_if_neq(Placed::from(h));
        }
    }
}

/// The edit depth's cells on their entities (above 0): the same entities
/// while the level and its shape stay, else new ones; none at depth 0.
fn place_refined(
    patch: &PatchRef,
    edit: u32,
    refined: Option<((usize, usize), Vec<Handle>)>,
    layout: &mut HandleLayout,
    out: &mut PlacedEntities,
) {
    let Some((shape, handles)) = refined else {
        if let Some((_, old)) = layout.refined.take() {
            out.despawn(&old);
        }
        return;
    };
    let keep = layout.refined.as_ref().is_some_and(|(s, v)| {
        *s == shape
            && layout.edit_depth == edit
            && v.len() == handles.len()
            && v.iter().all(|&e| out.refined.contains(e))
    });
    if keep {
        let entities = layout.refined.as_ref().map(|(_, v)| v.clone());
        for (h, e) in handles.iter().zip(entities.unwrap_or_default()) {
            out.put(e, h);
        }
        return;
    }
    if let Some((_, old)) = layout.refined.take() {
        out.despawn(&old);
    }
    let entities = handles
        .iter()
        .map(|h| {
            let cell = RefinedHandle {
                level: edit,
                row: h.id.row,
                col: h.id.col,
            };
            let e = (cell, h.id, Placed::from(h), ChildOf(patch.entity()));
            out.commands.spawn(e).id()
        })
        .collect();
    layout.refined = Some((shape, entities));
}

/// Places the control handles of `rows` again (edit depth 0, no mirror, no
/// fine tuning), their directions read from the handle entities, their
/// lengths kept; `None` when the arrows' length cap moved (or a handle has
/// no place yet), so that every handle must be placed afresh. Returns how
/// many handles were placed.
fn move_rows(
    patch: &PatchRef,
    level: &LevelState,
    rows: &[usize],
    cap: f64,
    out: &mut PlacedEntities,
) -> Option<usize> {
    let (nr, cols) = level.shape();
    let index = &patch.index().surface;
    if index.rows() != nr || index.cols() != cols {
        return None;
    }
    let initial = patch.design().initial();
    if length_cap(level, initial).to_bits() != cap.to_bits() {
        return None;
    }
    let tuning = patch.tuning();
    let s = &level.params.s;
    let mut pts = Vec::new();
    let mut new: Vec<(Entity, Placed)> = Vec::with_capacity(rows.len() * cols);
    for &r in rows.iter().filter(|&&r| r < nr) {
        place_row_tuned(initial, &level.tangents, &level.params, r, tuning, &mut pts);
        for c in 0..cols {
            let e = index.get(r, c);
            let old = out.placed.get(e).ok()?;
            let dir: DVec3 = patch.direction(e)?;
            let base = point_by_fraction(&pts, s.row(r), s.get(r, c));
            new.push((
                e,
                Placed {
                    base,
                    dir,
                    length: old.length,
                },
            ));
        }
    }
    for &(e, p) in &new {
        if let Ok(mut old) = out.placed.get_mut(e) {
            old.set_if_neq(p);
        }
    }
    Some(new.len())
}
