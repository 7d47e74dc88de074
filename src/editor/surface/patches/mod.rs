//! Every patch's shaded surface, by one path (docs/math.md §4, §11): each
//! patch has one mesh entity, [`PatchSurfaceMesh`], which one system keeps
//! up to date ([`sync_surfaces`]), writing only what changed. A patch's
//! vertices come from its [`PatchSurface`] stack's finest points (the
//! display depth) with the normals its build kept, the rows the last write
//! changed ([`PatchSurface::rows`]) written in place; the first patch's come
//! from its incremental pipeline instead ([`incremental`]: the staging pair
//! swapped in, or the changed window written in place), which is the same
//! surface made without a copy, and what a one-patch design has. A patch's
//! mesh is made whole only for a new grid shape; it is despawned with the
//! patch and hidden while the patch has [`PatchHidden`] (and in mesh mode).
//! The first patch's mesh entity is also the [`SurfaceEntity`], which mesh
//! mode hides.
//!
//! Which surface shows the first patch. Its incremental surface, unless it
//! heads a G2 chain: a G2 run is one merged net (docs/math.md §11.1, Eqs.
//! 68–70), so the first patch's cut of it (its `PatchSurface`) differs near
//! the seam from its one-patch surface, and the second patch starts on the
//! cut's last points, not on the one-patch surface's. On
//! `scenes/hood-screen-wing.ron` at depth 4 the two agree bit for bit on
//! the hood's first half and differ by up to 0.011 (0.5 % of the scene's
//! size) near the seam: a crack of a few pixels between the hood and the
//! screen if the one-patch surface were drawn (test
//! `the_g2_head_cut_differs_from_its_own_surface_near_the_seam`). The
//! editor draws what the seam report measures and what every export
//! writes: the cut. So the first patch of a G2 run is drawn from its stack
//! in every view (its own pipeline waits meanwhile,
//! `crate::ecs::joined::shows_run_cut`), and the analysis maps
//! (`super::maps`) colour the cut as they colour every patch, the map to
//! the reference included (`super::reference_map` measures the cut).

use super::super::interaction::{EditorMode, EditorSet};
use super::patch_mesh::{Triangles, normals_for, write_rows};
use super::shaded::{ShadedMaterial, SurfaceEntity, set_visible, to_bevy_mesh};
use crate::ecs::SurfaceData;
use crate::ecs::joined::{Joined, PatchHidden, PatchStart, PatchSurface, shows_run_cut};
use crate::ecs::patch::Patch;
use bevy::prelude::*;
use bevy_state::prelude::State;
use incremental::Incremental;
use std::collections::HashMap;
use streamline_kernel::joins::RowSpan;
use streamline_kernel::{DVec3, Grid};

use super::super::coords::kernel_to_view;

pub(super) mod incremental;

/// The mesh entity that draws patch `.0`.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct PatchSurfaceMesh(pub Entity);

/// The patches drawn from their stack, for picking and the boundary: a
/// drawn patch's kernel mesh is its stack's finest points (the display
/// depth, not copied) and the triangles kept here ([`PatchMeshes::mesh`]).
#[derive(Resource, Debug, Default)]
pub struct PatchMeshes {
    /// Patch entity → the triangles of its drawn mesh (one entry per patch
    /// drawn from its stack).
    pub triangles: HashMap<Entity, Triangles>,
    /// How many meshes were rebuilt since the start (a meter for the tests:
    /// only a changed surface rebuilds its mesh).
    pub rebuilt: u64,
    /// How many of those wrote only a rejoin's moved rows into the meshes
    /// in place ([`PatchSurface::rows`]).
    pub partial: u64,
    /// How many of those were written into the meshes in place, a rejoin's
    /// moved rows or every row of a surface of the same shape (no new Bevy
    /// mesh, no new triangles).
    pub in_place: u64,
}

impl PatchMeshes {
    /// Whether patch `p` is drawn from its stack (else, the first patch,
    /// from its incremental surface, [`crate::ecs::SurfaceData`]).
    pub fn is_drawn(&self, p: Entity) -> bool {
        self.triangles.contains_key(&p)
    }

    /// The mesh patch `p` is drawn with, `surface` being its
    /// [`PatchSurface`]: its vertices (the stack's finest points, kernel
    /// coordinates, as a grid: its edges) and its triangles; `None` when it
    /// is not drawn from its stack or not built.
    pub fn mesh<'a>(
        &'a self,
        p: Entity,
        surface: &'a PatchSurface,
    ) -> Option<(&'a Grid<DVec3>, &'a [u32])> {
        let t = self.triangles.get(&p)?;
        let g = surface.stack()?.finest_points();
        (t.shape == (g.rows(), g.cols())).then_some((g, t.indices.as_slice()))
    }

    /// The mesh patch `p` is shown with, for picking and the boundary: its
    /// stack's ([`Self::mesh`]) when it is drawn from its stack, else, for
    /// the first patch (not `joined`), its incremental surface `data`'s;
    /// `None` for a joined patch not built.
    pub fn shown<'a>(
        &'a self,
        p: Entity,
        joined: bool,
        surface: Option<&'a PatchSurface>,
        data: &'a SurfaceData,
    ) -> Option<(&'a Grid<DVec3>, &'a [u32])> {
        if self.is_drawn(p) {
            surface.and_then(|s| self.mesh(p, s))
        } else {
            (!joined).then_some((&data.points, data.indices.as_slice()))
        }
    }
}

/// What picking and the boundary read of every patch: its slot, whether it
/// is joined (not the first) or hidden, and its surface, whose stack's
/// finest points a drawn patch's mesh is ([`PatchMeshes::mesh`]).
pub type PickedPatches<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        &'static crate::ecs::joined::PatchSlot,
        Has<Joined>,
        Has<PatchHidden>,
        Option<&'static PatchSurface>,
    ),
>;

pub struct PatchSurfacesPlugin;

impl Plugin for PatchSurfacesPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<PatchMeshes>()
            .add_systems(Update, sync_surfaces.in_set(EditorSet::Sync));
    }
}

/// What [`sync_surfaces`] reads of every patch.
type PatchRow = (
    Entity,
    Option<Ref<'static, PatchSurface>>,
    Option<&'static PatchStart>,
    Has<Joined>,
    Has<PatchHidden>,
);

/// The other patches' mesh entities.
type Shown<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        &'static PatchSurfaceMesh,
        &'static Mesh3d,
        &'static mut Visibility,
    ),
    Without<SurfaceEntity>,
>;

/// The first patch's mesh entity (the [`SurfaceEntity`]).
type FirstMesh<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        Option<&'static Mesh3d>,
        Option<&'static mut Visibility>,
        Option<&'static mut PatchSurfaceMesh>,
    ),
    With<SurfaceEntity>,
>;

/// Keeps every patch's mesh up to date, spawns, shows, hides and despawns
/// them (module documentation).
#[allow(clippy::too_many_arguments)]
pub(super) fn sync_surfaces(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut commands: Commands,
    patches: Query<PatchRow, With<Patch>>,
    mut shown: Shown,
    mut first_mesh: FirstMesh,
    mut incremental: Incremental,
    (mode, material): (Option<Res<State<EditorMode>>>, Res<ShadedMaterial>),
    mut meshes: ResMut<Assets<Mesh>>,
    mut kernel: ResMut<PatchMeshes>,
) {
    let _meter = meter.start();
    // without the editor's mode (tests), the first patch's visibility is
    // left as it is
    let managed = mode.map(|m| *m.get() == EditorMode::Streamline);
    let streamline = managed.unwrap_or(true);
    let first = incremental.patch.entity();
    let first_row = patches.get(first).ok();
    let first_surface = first_row.as_ref().and_then(|r| r.1.as_ref());
    // the first patch drawn from its stack: the cut of the G2 run it
    // heads (a run that failed to build keeps its incremental surface)
    let first_stack = shows_run_cut(
        first,
        patches.iter().filter_map(|r| r.2),
        first_surface.map(|s| &**s),
    );
    let first_hidden = first_row.as_ref().is_some_and(|r| r.4);
    if let Ok((e, mesh, visibility, of)) = first_mesh.single_mut() {
        match of {
            Some(mut of) if of.0 != first => of.0 = first,
            Some(_) => {}
            None => {
                commands.entity(e).insert(PatchSurfaceMesh(first));
            }
        }
        let visible = match visibility {
            Some(mut v) => {
                // mesh mode shows and hides it itself
                if managed == Some(true) {
                    set_visible(&mut v, !first_hidden);
                }
                *v != Visibility::Hidden
            }
            None => true,
        };
        // hidden, or drawn from its stack: the pipeline's staging waits
        let hidden = !visible && incremental.shown.built;
        incremental.pause(hidden || first_stack);
        let mesh = mesh.and_then(|m| meshes.get_mut(&m.0));
        match (mesh, first_surface) {
            (Some(mut m), Some(surface)) if first_stack => {
                let whole = !incremental.shown.from_stack;
                stack_into(&mut m, first, surface, whole, &mut kernel);
                incremental.shown.from_stack = true;
                incremental.shown.built = true;
            }
            (Some(mut m), _) if !hidden => {
                kernel.triangles.remove(&first);
                let whole = incremental.shown.from_stack;
                if incremental.draw(&mut m, whole) {
                    incremental.shown.from_stack = false;
                }
            }
            _ => {}
        }
    }
    // the other patches: despawn the meshes of patches gone
    let mut have: HashMap<Entity, (Entity, Handle<Mesh>)> = HashMap::new();
    for (e, of, mesh, _) in &shown {
        match patches.get(of.0) {
            Ok(r) if r.3 && r.1.is_some() && !have.contains_key(&of.0) => {
                have.insert(of.0, (e, mesh.0.clone()));
            }
            _ => {
                commands.entity(e).despawn();
                if of.0 != first {
                    kernel.triangles.remove(&of.0);
                }
            }
        }
    }
    for r in patches.iter().filter(|r| r.3) {
        let (patch, hidden) = (r.0, r.4);
        let Some(surface) = r.1.as_ref() else {
            continue;
        };
        let visible = streamline && !hidden && surface.stack().is_some();
        let fresh = !have.contains_key(&patch);
        if fresh {
            // filled below, before the renderer sees it
            let h = meshes.add(to_bevy_mesh(&[], &[], &[]));
            let e = commands
                .spawn((
                    PatchSurfaceMesh(patch),
                    Mesh3d(h.clone()),
                    MeshMaterial3d(material.0.clone()),
                    Transform::from_rotation(kernel_to_view()),
                    Visibility::Hidden,
                ))
                .id();
            have.insert(patch, (e, h));
        }
        let (e, h) = &have[&patch];
        if let Some(mut m) = meshes.get_mut(h) {
            stack_into(&mut m, patch, surface, fresh, &mut kernel);
        }
        if fresh {
            if visible {
                commands.entity(*e).insert(Visibility::Inherited);
            }
        } else if let Ok((_, _, _, mut v)) = shown.get_mut(*e) {
            set_visible(&mut v, visible);
        }
    }
    // a patch no longer drawn from its stack leaves the picking
    kernel.triangles.retain(|p, _| {
        if *p == first {
            first_stack
        } else {
            patches.get(*p).is_ok_and(|r| r.3 && r.1.is_some())
        }
    });
}

/// Brings `mesh`, which draws patch `patch`, up to date with its `surface`:
/// the rows the last write changed ([`PatchSurface::rows`], or every row of
/// a surface built again whole) written in place when the mesh has the
/// grid's shape, its triangles kept; else made whole, as it is when
/// `whole` (the mesh shows something else, or nothing yet).
fn stack_into(
    mesh: &mut Mesh,
    patch: Entity,
    surface: &Ref<PatchSurface>,
    whole: bool,
    kernel: &mut PatchMeshes,
) {
    let changed = surface.is_changed();
    let in_place = !whole
        && changed
        && kernel.mesh(patch, surface).is_some()
        && surface.stack().is_some_and(|s| {
            let p = s.finest_points();
            let all = RowSpan {
                lo: 0,
                hi: p.rows().saturating_sub(1),
            };
            write_rows(mesh, p, &surface.normals, surface.rows.unwrap_or(all))
        });
    if in_place {
        kernel.rebuilt += 1;
        kernel.partial += u64::from(surface.rows.is_some());
        kernel.in_place += 1;
    } else if whole || changed || !kernel.is_drawn(patch) {
        let old = kernel.triangles.remove(&patch);
        let triangles = match surface.stack() {
            Some(s) => {
                let p = s.finest_points();
                let t = Triangles::of(p.rows(), p.cols(), old);
                let normals = normals_for(p, &surface.normals);
                *mesh = to_bevy_mesh(p.data(), &normals, &t.indices);
                t
            }
            None => {
                *mesh = to_bevy_mesh(&[], &[], &[]);
                Triangles::default()
            }
        };
        kernel.triangles.insert(patch, triangles);
        kernel.rebuilt += 1;
    }
}

#[cfg(test)]
mod incremental_tests;
#[cfg(test)]
mod tests;
