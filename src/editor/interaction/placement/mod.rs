//! Placing every patch's handles: the one system that writes [`Placed`] on
//! the handle entities (with `set_if_neq`, so that only the handles that
//! moved are marked changed), spawns the active patch's [`RefinedHandle`]
//! entities of the edit depth and the mirrored copies, and despawns them
//! when they are no longer shown.
//!
//! One rule for every patch, joined or not: its handles stand on the levels
//! that are drawn for it ([`levels`]). Those are the first patch's
//! incremental levels, unless it heads a G2 run: the run is one merged net
//! (docs/math.md §11.1, Eqs. 68–70), and the first patch is drawn as its
//! cut of it, which differs from its one-patch levels near the seam, so its
//! handles are placed on that cut (its [`PatchSurface`] stack), as a joined
//! patch's are on its own stack; a detail's frame is taken from the same
//! level by the edit stage (docs/math.md §5). The active patch's handles are
//! placed at the edit depth: its control tangents at level 0 and, above 0,
//! its refined cells at that level (the cells its edits can name, less a
//! chain's seam column, which is turned on the parent, §11.1); every other
//! patch's control tangents at level 0, drawn dimmed.
//!
//! A turn of the first patch's control tangents at edit depth 0 re-places
//! only their rows (a streamline is a running sum along its row, Eq. 65); a
//! new shape, `s`, initial curve, tuning, mirror, edit depth or active patch
//! re-places every handle; a patch drawn from a stack is placed again when
//! that stack was rebuilt, its handles turned, the active patch, the edit
//! depth or the arrows' cap changed. A stack is built to the display depth:
//! at an edit depth deeper than that, a joined patch has no refined handles
//! (its control tangents are placed, and none of the edit depth's can be
//! picked) and the first patch's come from its own levels.

mod entities;
mod levels;

pub use levels::{DrawnLevel, shares_first_column, stack_handles};

use super::placed::{HandleLayout, Placed};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::joined::{ActivePatch, JoinedDesign, PatchStart, PatchSurface, heads_g2_run};
use crate::ecs::patch::{
    ArcParam, Direction, InitialHandle, Joined, JoinedHandle, Patch, PatchIndex, PatchRef,
    SurfaceHandle,
};
use bevy::prelude::*;
use entities::{PlacedEntities, Refined, place_copies, place_refined};
use levels::{Cells, initial_handles, length_cap, level_handles};
use streamline_kernel::finetune::streamline::point_by_fraction;
use streamline_kernel::joins::Stack;
use streamline_kernel::levels::incremental::{LevelState, place_row_tuned, place_rows_tuned};
use streamline_kernel::{DVec3, Design};

/// Control tangents of the first patch whose handle entity's direction changed.
type TurnedNet<'w, 's> =
    Query<'w, 's, &'static SurfaceHandle, (Changed<Direction>, Without<JoinedHandle>)>;

/// Handle entities of the first patch's net or initial curve not placed yet.
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

/// The level entities with their patch.
type LevelRows<'w, 's> = Query<
    'w,
    's,
    (
        &'static SubdivisionLevel,
        Ref<'static, LevelData>,
        &'static ChildOf,
    ),
>;

/// What the first patch's handles are placed from, and what moves them.
#[derive(bevy::ecs::system::SystemParam)]
pub(super) struct FirstSide<'w, 's> {
    levels: LevelRows<'w, 's>,
    turned: TurnedNet<'w, 's>,
    s: TurnedS<'w, 's>,
    curve: Query<'w, 's, (), (With<InitialHandle>, Changed<Direction>)>,
    unplaced: Unplaced<'w, 's>,
    active: Res<'w, ActivePatch>,
    joined: Query<'w, 's, (), (With<Patch>, With<Joined>)>,
}

/// A patch built through the joins, with what its handles are placed from.
type StackRow = (
    Entity,
    Ref<'static, PatchSurface>,
    &'static PatchIndex,
    &'static PatchStart,
    Option<&'static JoinedDesign>,
    Has<Joined>,
);

/// The patches with a [`PatchSurface`] and what moves their handles.
#[derive(bevy::ecs::system::SystemParam)]
pub(super) struct StackSide<'w, 's> {
    patches: Query<'w, 's, StackRow, With<Patch>>,
    directions: Query<'w, 's, &'static Direction, With<JoinedHandle>>,
    turned: Query<'w, 's, &'static ChildOf, (With<JoinedHandle>, Changed<Direction>)>,
    unplaced: Query<'w, 's, &'static ChildOf, (With<JoinedHandle>, Without<Placed>)>,
}

impl StackSide<'_, '_> {
    /// The cut of a G2 run that patch `first` heads, when it is built and
    /// has level `level`.
    fn g2_cut(&self, first: Entity, level: u32) -> Option<(&Stack, bool)> {
        if !heads_g2_run(first, self.patches.iter().map(|r| r.3)) {
            return None;
        }
        let (_, surface, ..) = self.patches.get(first).ok()?;
        let changed = surface.is_changed();
        let stack = surface.into_inner().stack()?;
        let fits = DrawnLevel::of_stack(stack, 0).is_some()
            && DrawnLevel::of_stack(stack, level).is_some();
        fits.then_some((stack, changed))
    }
}

/// What the placement placed last, apart from the layout.
#[derive(Debug, Default)]
pub(super) struct LastPlaced {
    /// The active patch.
    active: Option<Entity>,
    /// The arrows' cap, as bits.
    cap: u64,
    /// The edit depth.
    edit: u32,
    /// The level the first patch's handles were placed at.
    first_edit: u32,
    /// Whether the first patch's were placed on its G2 run's cut.
    first_cut: bool,
}

/// Places the handles again when what they are drawn from changed: see the
/// module's doc.
#[allow(clippy::too_many_arguments)]
pub(super) fn place(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    first: FirstSide,
    stacks: StackSide,
    mut layout: ResMut<HandleLayout>,
    mut out: PlacedEntities,
    mut last: Local<LastPlaced>,
) {
    let _meter = meter.start();
    let (active, active_joined) = resolve_active(first.active.0, patch.entity(), &first.joined);
    let edit = patch.structure().edit_depth;
    let at = Placing {
        active,
        active_joined,
        edit,
    };
    let placed_first = place_first(
        &patch,
        &first,
        &stacks,
        at,
        &mut layout,
        &mut last,
        &mut out,
    );
    if !layout.placed {
        return;
    }
    // `Some`: the active patch's refined cells were computed again
    let mut refined = placed_first.filter(|_| !active_joined);
    let every =
        last.active != Some(active) || last.cap != layout.cap.to_bits() || last.edit != edit;
    let joined = place_joined(&stacks, at, every, layout.cap, &mut out);
    if active_joined && joined.is_some() {
        refined = joined;
    }
    if let Some(r) = refined {
        place_refined(active, edit, r, &mut layout, &mut out);
    }
    if layout.edit_depth != edit
        || layout.active != Some(active)
        || layout.active_joined != active_joined
    {
        layout.edit_depth = edit;
        layout.active = Some(active);
        layout.active_joined = active_joined;
    }
    last.active = Some(active);
    last.cap = layout.cap.to_bits();
    last.edit = edit;
}

/// The active patch and the edit depth, for this frame's placement.
#[derive(Debug, Clone, Copy)]
struct Placing {
    /// The patch whose handles are shown and picked.
    active: Entity,
    /// Whether it is a joined one.
    active_joined: bool,
    /// The document's edit depth.
    edit: u32,
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

/// The refined cells of level `level` of a patch drawn from `stack` (above
/// 0): the cells of the patch's `own` shape at that level that the level
/// has, less the seam column when `skip_first`; `None` when the stack has
/// no such level.
fn refined_on(
    stack: &Stack,
    level: u32,
    own: Option<(usize, usize)>,
    skip_first: bool,
    cap: f64,
) -> Option<Refined> {
    let l = DrawnLevel::of_stack(stack, level)?;
    let (rows, cols) = l.shape();
    let own = own.unwrap_or((rows, cols));
    let shape = (rows.min(own.0), cols.min(own.1));
    let cells = Cells {
        first_col: usize::from(skip_first),
        ..Cells::all(shape)
    };
    let (handles, _) = level_handles(&l, levels::REFINED_SCALE, cap, cells, |_, _| None);
    Some(Refined { shape, handles })
}

/// The shape of `design`'s own level `level` (the cells its edits can name).
fn own_shape(design: &Design, level: u32) -> Option<(usize, usize)> {
    let net = design.net();
    design
        .scheme()
        .check_depth(net.rows(), net.cols(), level)
        .ok()
}

/// Places the first patch's handles when what they stand on changed (the
/// module's doc): `None` when it placed none, or only the rows of turned
/// control tangents; else `Some` with its refined cells of the edit depth
/// (`None` at depth 0 and while a joined patch is active).
#[allow(clippy::too_many_arguments)]
fn place_first(
    patch: &PatchRef,
    first: &FirstSide,
    stacks: &StackSide,
    at: Placing,
    layout: &mut ResMut<HandleLayout>,
    last: &mut LastPlaced,
    out: &mut PlacedEntities,
) -> Option<Option<Refined>> {
    let st = patch.structure();
    let me = patch.entity();
    // a joined patch active: the first patch's handles are placed at depth
    // 0, dimmed (its refined cells are not shown)
    let edit = if at.active_joined { 0 } else { at.edit };
    // a G2 run's head is drawn as its cut of the run (module doc)
    let cut = match st.mirror {
        true => None,
        false => stacks.g2_cut(me, edit),
    };
    let whole = layout.active != Some(at.active)
        || patch.structure_changed()
        || patch.placement_changed()
        || patch.tuning_changed()
        || !first.s.is_empty()
        || !first.curve.is_empty()
        || !first.unplaced.is_empty()
        || last.first_edit != edit
        || last.first_cut != cut.is_some()
        || !layout.placed;
    let own_levels = || first.levels.iter().filter(|r| r.2.parent() == me);
    let changed = match cut {
        Some((_, changed)) => changed || !first.turned.is_empty(),
        None => own_levels().any(|(l, d, _)| (l.0 == 0 || l.0 == edit) && d.is_changed()),
    };
    if !whole && !changed {
        return None;
    }
    let find = |level: u32| {
        own_levels()
            .find(|(l, ..)| l.0 == level)
            .map(|(_, d, _)| Ref::into_inner(d))
    };
    let base = find(0)?;
    let by_rows = cut.is_none()
        && !whole
        && edit == 0
        && !st.mirror
        && patch.tuning().is_none()
        && !crate::scene::design::model::interpolates(patch.design(), st.interpolate_tangents);
    if by_rows && !first.turned.is_empty() {
        let mut rows: Vec<usize> = first.turned.iter().map(|h| h.row).collect();
        rows.sort_unstable();
        rows.dedup();
        if let Some(n) = move_rows(patch, &base.0, &rows, layout.cap, out) {
            layout.moved = n;
            return None;
        }
    }
    // mirrored: the levels are the doubled design's, placed on its initial
    // curve (the scene's own, reflected for the other half)
    let shown = match st.mirror {
        true => Some(
            crate::scene::design::model::shown_design(
                patch.design(),
                st.interpolate_tangents,
                true,
            )
            .ok()?,
        ),
        false => None,
    };
    let initial = shown
        .as_ref()
        .map_or(patch.design().initial(), |d| d.initial());
    let reflected = match shown {
        Some(_) => st.rows.saturating_sub(1),
        None => 0,
    };
    // the levels drawn: the cut's, else the incremental ones placed on the
    // (shown) initial curve
    let tuning = patch.tuning();
    let (mut pts0, mut pts) = (Vec::new(), Vec::new());
    let level0 = match cut {
        Some((stack, _)) => DrawnLevel::of_stack(stack, 0)?,
        None => {
            place_rows_tuned(initial, &base.0.tangents, &base.0.params, tuning, &mut pts0);
            drawn(&base.0, &pts0)
        }
    };
    // long intervals (a 3×3 net) would give arrows as large as the scene: cap
    // them at a tenth of the surface's size
    let cap = length_cap(level0.s, initial);
    let refined = match (cut, edit) {
        (_, 0) => None,
        (Some((stack, _)), _) => {
            let own = own_shape(patch.design(), edit);
            Some(refined_on(stack, edit, own, false, cap)?)
        }
        (None, _) => {
            let d = &find(edit)?.0;
            place_rows_tuned(initial, &d.tangents, &d.params, tuning, &mut pts);
            let l = drawn(d, &pts);
            let cells = Cells::all(l.shape());
            let (handles, _) = level_handles(&l, levels::REFINED_SCALE, cap, cells, |_, _| None);
            Some(Refined {
                shape: l.shape(),
                handles,
            })
        }
    };
    let index = patch.index();
    let net = patch.net();
    let cells = Cells {
        rows: index.surface.rows(),
        cols: index.surface.cols(),
        first_col: 0,
        reflected,
    };
    // control arrows show the designer's tangents (the interpolated net,
    // when that option is on, is what subdivision starts from)
    let (controls, mirrored) = level_handles(&level0, levels::CONTROL_SCALE, cap, cells, |r, c| {
        (r < net.rows() && c < net.cols()).then(|| net.get(r, c))
    });
    // the initial curve's arrows: a good part of its spacing between
    // tangents, so they stand out of the column of control arrows there
    let curve = patch.design().initial();
    let spacing = curve.length() / (curve.qi().tangents().len().max(2) - 1) as f64;
    let initial = initial_handles(curve, (0.6 * spacing).min(2.0 * cap).max(1e-6));
    // write them on their entities
    for h in &controls {
        out.put(index.surface.get(h.id.row, h.id.col), h);
    }
    for (h, &e) in initial.iter().zip(&index.initial) {
        out.put(e, h);
    }
    place_copies(me, &mirrored, layout, out);
    let refined_count = refined.as_ref().map_or(0, |r| r.handles.len());
    layout.cap = cap;
    layout.placed = true;
    layout.moved = controls.len() + mirrored.len() + initial.len() + refined_count;
    last.first_edit = edit;
    last.first_cut = cut.is_some();
    Some(refined.filter(|_| !at.active_joined))
}

/// An incremental level as drawn, with its streamlines' points `pts`.
fn drawn<'a>(l: &'a LevelState, pts: &'a [DVec3]) -> DrawnLevel<'a> {
    DrawnLevel {
        level: l.level,
        tangents: &l.tangents,
        s: &l.params.s,
        points: pts,
    }
}

/// Places the joined patches' control tangents on level 0 of their stacks
/// (those that may have moved: every one when `every`) and, for the active
/// one, its refined cells of the edit depth, returned: `Some` when the
/// active patch is a joined one and was placed (`Some(None)`: no refined
/// cells, at depth 0 or when its stack lacks the level).
fn place_joined(
    stacks: &StackSide,
    at: Placing,
    every: bool,
    cap: f64,
    out: &mut PlacedEntities,
) -> Option<Option<Refined>> {
    let mut wanted: Vec<Entity> = (stacks.turned.iter())
        .chain(stacks.unplaced.iter())
        .map(ChildOf::parent)
        .collect();
    wanted.sort_unstable();
    wanted.dedup();
    let mut refined = None;
    for (e, surface, index, start, design, joined) in &stacks.patches {
        if !joined || !(every || surface.is_changed() || wanted.binary_search(&e).is_ok()) {
            continue;
        }
        let active = at.active_joined && e == at.active;
        if active {
            refined = Some(None);
        }
        let Some(stack) = surface.stack() else {
            continue;
        };
        let skip = shares_first_column(start);
        if let Some(l0) = DrawnLevel::of_stack(stack, 0) {
            let cells = Cells {
                first_col: usize::from(skip),
                ..Cells::all((index.surface.rows(), index.surface.cols()))
            };
            let dir = |r: usize, c: usize| {
                let e = index.surface.get(r, c);
                stacks.directions.get(e).ok().map(|d| d.0)
            };
            let (controls, _) = level_handles(&l0, levels::CONTROL_SCALE, cap, cells, dir);
            for h in &controls {
                out.put(index.surface.get(h.id.row, h.id.col), h);
            }
        }
        if active && at.edit > 0 {
            let own = design.and_then(|d| own_shape(&d.0, at.edit));
            refined = Some(refined_on(stack, at.edit, own, skip, cap));
        }
    }
    refined
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
    if length_cap(&level.params.s, initial).to_bits() != cap.to_bits() {
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
