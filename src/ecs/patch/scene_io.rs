//! A patch and its scene: the scene (`src/scene`) is the file format and what
//! undo stores; at run time the design lives in the patch's components and
//! its handles ([`super::components`]). [`spawn_patch`] makes the entities of
//! a scene, [`assemble`] gives the scene back from them (to save, snapshot
//! or export), and [`PatchParts::write`] writes a scene into them, comparing
//! value by value so that only what differs is written (`set_if_neq`) and so
//! marked changed for [`super::track`].

use super::components::*;
use super::dirty::Dirty;
use crate::scene::Scene;
use crate::scene::files::format::{Dir, Finite, InitialSpec, Point};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use std::collections::BTreeMap;
use streamline_kernel::levels::multires::Details;
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::{DVec3, Design, Grid};

/// The patch-wide components of a scene.
fn structure_of(s: &Scene) -> PatchStructure {
    let d = &s.design;
    PatchStructure {
        rows: d.net().rows(),
        cols: d.net().cols(),
        t: d.params().t.clone(),
        scheme: d.scheme(),
        order: d.order(),
        display_depth: s.display_depth,
        edit_depth: s.edit_depth,
        interpolate_tangents: s.interpolate_tangents,
        mirror: s.mirror,
    }
}

fn placement_of(s: &Scene) -> PatchPlacement {
    PatchPlacement {
        anchor: s.design.anchor(),
        initial_order: s.initial.order,
        initial_length: s.initial.length.0,
        initial_origin: s.initial.origin.vec(),
    }
}

/// Spawns the entities of `scene`: the patch and its handles, as children
/// (levels and streamlines follow with the first build, which the new
/// [`PatchStructure`] asks for). Returns the patch entity.
pub fn spawn_patch(world: &mut World, scene: &Scene) -> Entity {
    let patch = world
        .spawn((
            Patch,
            PatchName(scene.name.clone()),
            structure_of(scene),
            placement_of(scene),
            PatchTuning(scene.tuning.clone()),
            PatchView(scene.view),
            PatchReference(scene.reference.clone()),
            PatchKernel {
                design: scene.design.clone(),
                details: scene.details.clone(),
            },
            Dirty::default(),
        ))
        .id();
    let index = PatchIndex {
        surface: spawn_net(&mut world.commands(), patch, scene),
        initial: spawn_initial(&mut world.commands(), patch, &scene.initial),
        details: scene
            .details
            .iter()
            .map(|(&k, &v)| (k, spawn_detail(&mut world.commands(), patch, k, v)))
            .collect(),
    };
    world.flush();
    world.entity_mut(patch).insert(index);
    patch
}

/// One entity per control tangent of `design`'s net, children of `patch`
/// (its cell, direction and `s`), each with `marker` too; their grid.
pub(crate) fn spawn_net_handles(
    commands: &mut Commands,
    patch: Entity,
    design: &Design,
    marker: impl Bundle + Clone,
) -> Grid<Entity> {
    let (net, s) = (design.net(), &design.params().s);
    let mut ids = Grid::filled(net.rows(), net.cols(), Entity::PLACEHOLDER);
    for row in 0..net.rows() {
        for col in 0..net.cols() {
            let id = commands
                .spawn((
                    SurfaceHandle { row, col },
                    Direction(net.get(row, col)),
                    ArcParam(s.get(row, col)),
                    marker.clone(),
                    ChildOf(patch),
                ))
                .id();
            ids.set(row, col, id);
        }
    }
    ids
}

fn spawn_net(commands: &mut Commands, patch: Entity, scene: &Scene) -> Grid<Entity> {
    spawn_net_handles(commands, patch, &scene.design, ())
}

fn spawn_initial(commands: &mut Commands, patch: Entity, spec: &InitialSpec) -> Vec<Entity> {
    (spec.tangents.iter().enumerate())
        .map(|(index, d)| {
            let h = (InitialHandle { index }, Direction(d.vec()), ChildOf(patch));
            commands.spawn(h).id()
        })
        .collect()
}

fn spawn_detail(
    commands: &mut Commands,
    patch: Entity,
    (level, row, col): (u32, usize, usize),
    v: DVec3,
) -> Entity {
    let h = DetailHandle { level, row, col };
    commands.spawn((h, DetailRotation(v), ChildOf(patch))).id()
}

/// The scene of a patch, from its components and its handles' values
/// (`dir`, `s` and `detail` read a handle entity's). `kernel` lends its
/// initial curve when the handles describe the same one ([`initial_curve`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn assemble_with(
    name: &PatchName,
    st: &PatchStructure,
    pl: &PatchPlacement,
    tuning: &PatchTuning,
    view: &PatchView,
    reference: &PatchReference,
    index: &PatchIndex,
    kernel: Option<&PatchKernel>,
    dir: impl Fn(Entity) -> Option<DVec3>,
    s: impl Fn(Entity) -> Option<f64>,
    detail: impl Fn(Entity) -> Option<DVec3>,
) -> Result<Scene, String> {
    let missing = || "a handle of the patch is missing; reload the scene".to_string();
    let (rows, cols) = (index.surface.rows(), index.surface.cols());
    let mut net = Grid::filled(rows, cols, DVec3::X);
    let mut sg = Grid::filled(rows, cols, 0.0);
    for r in 0..rows {
        for c in 0..cols {
            let e = index.surface.get(r, c);
            net.set(r, c, dir(e).ok_or_else(missing)?);
            sg.set(r, c, s(e).ok_or_else(missing)?);
        }
    }
    let initial = InitialSpec {
        tangents: (index.initial.iter())
            .map(|&e| dir(e).map(Dir::from_vec).ok_or_else(missing))
            .collect::<Result<_, _>>()?,
        order: pl.initial_order,
        length: Finite(pl.initial_length),
        origin: Point::from_vec(pl.initial_origin),
    };
    let tangents: Vec<DVec3> = initial.tangents.iter().map(|d| d.vec()).collect();
    let curve = initial_curve(pl, &tangents, kernel.map(|k| k.design.initial()))?;
    let design = Design::new(
        &net,
        sg,
        st.t.clone(),
        pl.anchor,
        st.scheme,
        st.order,
        curve,
    )
    .map_err(|e| e.to_string())?;
    let details: Details = (index.details.iter())
        .map(|(&k, &e)| detail(e).map(|v| (k, v)).ok_or_else(missing))
        .collect::<Result<_, _>>()?;
    Ok(Scene {
        name: name.0.clone(),
        design,
        initial,
        details,
        display_depth: st.display_depth,
        edit_depth: st.edit_depth,
        view: view.0,
        tuning: tuning.0.clone(),
        interpolate_tangents: st.interpolate_tangents,
        mirror: st.mirror,
        reference: reference.0.clone(),
    })
}

/// The initial curve of `pl` and the curve handles' `tangents`: `old` when
/// it is that curve (same order, length, origin and normalised tangents, bit
/// for bit), else made afresh (making one evaluates its arc length, Eq. 1,
/// by quadrature).
pub(crate) fn initial_curve(
    pl: &PatchPlacement,
    tangents: &[DVec3],
    old: Option<&InitialCurve>,
) -> Result<InitialCurve, String> {
    let same = |c: &InitialCurve| {
        c.qi().order() == pl.initial_order
            && c.length().to_bits() == pl.initial_length.to_bits()
            && c.origin() == pl.initial_origin
            && c.qi().tangents().len() == tangents.len()
            && (c.qi().tangents().iter().zip(tangents))
                .all(|(a, b)| streamline_kernel::Tangent::new(*b).is_ok_and(|t| t.get() == *a))
    };
    match old {
        Some(c) if same(c) => Ok(c.clone()),
        _ => InitialCurve::new(
            tangents,
            pl.initial_order,
            pl.initial_length,
            pl.initial_origin,
        )
        .map_err(|e| e.to_string()),
    }
}

/// The scene of the world's patch, assembled from its entities (for
/// callers outside the schedule: the command line, tests).
pub fn scene(world: &World) -> Scene {
    try_scene(world).unwrap_or_else(|e| panic!("the world's patch: {e}"))
}

/// [`scene`], or why there is none.
pub fn try_scene(world: &World) -> Result<Scene, String> {
    let patch = patch_entity(world).ok_or("the world has no patch")?;
    let e = world.entity(patch);
    let get = || -> Option<_> {
        Some((
            e.get::<PatchName>()?,
            e.get::<PatchStructure>()?,
            e.get::<PatchPlacement>()?,
            e.get::<PatchTuning>()?,
            e.get::<PatchView>()?,
            e.get::<PatchReference>()?,
            e.get::<PatchIndex>()?,
        ))
    };
    let (name, st, pl, tu, vw, rf, index) = get().ok_or("the patch is not complete")?;
    assemble_with(
        name,
        st,
        pl,
        tu,
        vw,
        rf,
        index,
        e.get::<PatchKernel>(),
        |h| world.get::<Direction>(h).map(|d| d.0),
        |h| world.get::<ArcParam>(h).map(|a| a.0),
        |h| world.get::<DetailRotation>(h).map(|d| d.0),
    )
}

/// The world's first patch entity (the one the incremental pipeline
/// builds; not a [`Joined`] one).
///
/// Works before any system has run: a query naming [`Joined`] would find
/// nothing while that component is not registered (no system has asked for
/// it yet), which is how the editor once opened a version-3 scene without
/// its later patches (its Stats said `patches 1`).
pub fn patch_entity(world: &World) -> Option<Entity> {
    let mut q = world.try_query_filtered::<Entity, With<Patch>>()?;
    q.iter(world).find(|&e| world.get::<Joined>(e).is_none())
}

/// The patch's own components, writable.
type PatchDataMut = (
    Entity,
    &'static mut PatchName,
    &'static mut PatchStructure,
    &'static mut PatchPlacement,
    &'static mut PatchTuning,
    &'static mut PatchView,
    &'static mut PatchReference,
    &'static mut PatchIndex,
    &'static PatchKernel,
);

/// A net handle's values, writable.
type NetValuesMut = (&'static mut Direction, &'static mut ArcParam);

/// A net handle of the first patch (not an initial-curve one, not a joined patch's).
type FirstNet = (
    With<SurfaceHandle>,
    Without<InitialHandle>,
    Without<JoinedHandle>,
);

/// The patch and its handles, writable: what the edit stage reads a scene
/// from and writes one back into.
#[derive(SystemParam)]
pub(crate) struct PatchParts<'w, 's> {
    patches: Query<'w, 's, PatchDataMut, (With<Patch>, Without<Joined>)>,
    surface: Query<'w, 's, NetValuesMut, FirstNet>,
    initial: Query<'w, 's, &'static mut Direction, (With<InitialHandle>, Without<SurfaceHandle>)>,
    details: Query<'w, 's, &'static mut DetailRotation, With<DetailHandle>>,
    commands: Commands<'w, 's>,
}

impl PatchParts<'_, '_> {
    /// The patch's scene, assembled from the entities.
    pub(crate) fn assemble(&self) -> Result<Scene, String> {
        let (_, name, st, pl, tu, vw, rf, index, kernel) = self
            .patches
            .single()
            .map_err(|_| "the world has no patch".to_string())?;
        assemble_with(
            name,
            st,
            pl,
            tu,
            vw,
            rf,
            index,
            Some(kernel),
            |h| {
                self.surface
                    .get(h)
                    .map(|(d, _)| d.0)
                    .ok()
                    .or_else(|| self.initial.get(h).ok().map(|d| d.0))
            },
            |h| self.surface.get(h).map(|(_, a)| a.0).ok(),
            |h| self.details.get(h).map(|d| d.0).ok(),
        )
    }

    /// Writes `target` into the entities: each component only where its
    /// value differs; the net's handles are made afresh only when the net
    /// changes shape, the initial curve's when their number changes, and a
    /// detail's entity is spawned or despawned with the detail.
    pub(crate) fn write(&mut self, target: &Scene) {
        let Ok((patch, mut name, mut st, mut pl, mut tu, mut vw, mut rf, mut index, _)) =
            self.patches.single_mut()
        else {
            return;
        };
        if name.0 != target.name {
            name.0.clone_from(&target.name);
        }
        st.set_if_neq(structure_of(target));
        pl.set_if_neq(placement_of(target));
        if tu.0 != target.tuning {
            tu.0.clone_from(&target.tuning);
        }
        vw.set_if_neq(PatchView(target.view));
        if rf.0 != target.reference {
            rf.0.clone_from(&target.reference);
        }
        let (net, s) = (target.design.net(), &target.design.params().s);
        if (index.surface.rows(), index.surface.cols()) != (net.rows(), net.cols()) {
            for &e in index.surface.data() {
                self.commands.entity(e).despawn();
            }
            index.surface = spawn_net(&mut self.commands, patch, target);
        } else {
            for r in 0..net.rows() {
                for c in 0..net.cols() {
                    if let Ok((mut d, mut a)) = self.surface.get_mut(index.surface.get(r, c)) {
                        d.set_if_neq(Direction(net.get(r, c)));
                        a.set_if_neq(ArcParam(s.get(r, c)));
                    }
                }
            }
        }
        let tangents = &target.initial.tangents;
        if index.initial.len() != tangents.len() {
            for &e in &index.initial {
                self.commands.entity(e).despawn();
            }
            index.initial = spawn_initial(&mut self.commands, patch, &target.initial);
        } else {
            for (&e, d) in index.initial.iter().zip(tangents) {
                if let Ok(mut h) = self.initial.get_mut(e) {
                    h.set_if_neq(Direction(d.vec()));
                }
            }
        }
        let old = std::mem::take(&mut index.details);
        let mut kept = BTreeMap::new();
        for (k, e) in old {
            match target.details.get(&k) {
                Some(&v) => {
                    if let Ok(mut d) = self.details.get_mut(e) {
                        d.set_if_neq(DetailRotation(v));
                    }
                    kept.insert(k, e);
                }
                None => self.commands.entity(e).despawn(),
            }
        }
        for (&k, &v) in &target.details {
            kept.entry(k)
                .or_insert_with(|| spawn_detail(&mut self.commands, patch, k, v));
        }
        if index.details != kept {
            index.details = kept;
        }
    }
}
