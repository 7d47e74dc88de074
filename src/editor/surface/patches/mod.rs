//! The shaded surfaces of a document's several patches (docs/math.md §11):
//! one Bevy mesh per patch drawn from its [`PatchSurface`] stack's finest
//! points (the display depth), with the normals and triangles the first
//! patch's mesh has ([`SurfaceMesh::from_points`], docs/math.md §4),
//! rebuilt only on `Changed<PatchSurface>`, despawned with the patch,
//! hidden while the patch has [`PatchHidden`] (and in mesh mode).
//!
//! Which surface shows the first patch. The first patch keeps its
//! incremental surface ([`crate::ecs::SurfaceData`], drawn by
//! [`super::shaded`]) unless it heads a G2 chain: a G2 run is one merged net
//! (docs/math.md §11.1, Eqs. 68–70), so the first patch's cut of it (its
//! `PatchSurface`) differs near the seam from its one-patch surface, and
//! the second patch starts on the cut's last points, not on the one-patch
//! surface's. On `scenes/hood-screen-wing.ron` at depth 4 the two agree
//! bit for bit on the hood's first half and differ by up to 0.011 (0.5 %
//! of the scene's size) near the seam: a crack of a few pixels between
//! the hood and the screen if the one-patch surface were drawn (test
//! `the_g2_head_cut_differs_from_its_own_surface_near_the_seam`). The
//! editor draws what the seam report measures and what
//! every export writes: the cut. So in the shaded display the first patch
//! of a G2 run is drawn from its stack here and the incremental mesh is
//! hidden; the analysis maps (which read the incremental surface) show that
//! one instead, and `super::patch_maps` puts the same maps on the joined
//! patches.

use super::super::interaction::{EditorMode, EditorSet};
use super::analysis::{AnalysisSettings, SurfaceMode};
use super::patch_mesh::{Triangles, normals_for, write_rows};
use super::shaded::{ShadedMaterial, SurfaceEntity, set_visible, to_bevy_mesh};
use crate::ecs::SurfaceData;
use crate::ecs::joined::{Joined, PatchHidden, PatchStart, PatchSurface};
use bevy::prelude::*;
use bevy_state::prelude::State;
use std::collections::HashMap;
use streamline_kernel::joins::rejoin::RowSpan;
use streamline_kernel::joins::{Continuity, Edge};
use streamline_kernel::{DVec3, Grid};

use super::super::coords::kernel_to_view;

/// A mesh entity that draws patch `.0`'s [`PatchSurface`].
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
            .add_systems(Update, sync_patch_meshes.in_set(EditorSet::Sync));
    }
}

/// Whether patch `first` heads a G2 run: a patch starts on its `End` with G2.
pub fn heads_g2_run(first: Entity, starts: impl IntoIterator<Item = PatchStart>) -> bool {
    starts.into_iter().any(|s| {
        matches!(s, PatchStart::Edge { parent, edge: Edge::End, continuity: Continuity::G2 }
            if parent == first)
    })
}

/// Whether the first patch is drawn from its stack (module documentation):
/// it heads a G2 run and the surface is shown shaded.
pub fn first_from_stack(g2_head: bool, mode: SurfaceMode) -> bool {
    g2_head && mode == SurfaceMode::Shaded
}

/// What [`sync_patch_meshes`] reads of every patch with a surface.
type PatchRow = (
    Entity,
    Ref<'static, PatchSurface>,
    &'static PatchStart,
    Has<Joined>,
    Has<PatchHidden>,
);

/// The patch mesh entities.
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

/// Spawns, rebuilds, shows, hides and despawns the patch meshes (module
/// documentation), and shows or hides the first patch's incremental mesh.
#[allow(clippy::too_many_arguments)]
fn sync_patch_meshes(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut commands: Commands,
    patches: Query<PatchRow>,
    mut shown: Shown,
    mut first_mesh: Query<&mut Visibility, (With<SurfaceEntity>, Without<PatchSurfaceMesh>)>,
    (mode, analysis, material): (
        Res<State<EditorMode>>,
        Res<AnalysisSettings>,
        Res<ShadedMaterial>,
    ),
    mut meshes: ResMut<Assets<Mesh>>,
    mut kernel: ResMut<PatchMeshes>,
) {
    let _meter = meter.start();
    let streamline = *mode.get() == EditorMode::Streamline;
    let first = patches.iter().find(|r| !r.3).map(|r| r.0);
    // a G2 head whose run failed to build keeps its incremental surface
    let g2_head = first.is_some_and(|f| {
        heads_g2_run(f, patches.iter().map(|r| *r.2))
            && patches.get(f).is_ok_and(|r| r.1.stack().is_some())
    });
    let first_stack = first_from_stack(g2_head, analysis.mode);
    // the first patch's incremental mesh (mesh mode shows and hides it itself)
    if streamline {
        let first_hidden = first.is_some_and(|f| patches.get(f).is_ok_and(|r| r.4));
        for mut v in &mut first_mesh {
            set_visible(&mut v, !first_hidden && !first_stack);
        }
    }
    let drawn = |r: &(Entity, Ref<PatchSurface>, &PatchStart, bool, bool)| r.3 || first_stack;
    // despawn the meshes of patches gone or no longer drawn from a stack
    let mut have: HashMap<Entity, (Entity, Handle<Mesh>)> = HashMap::new();
    for (e, of, mesh, _) in &shown {
        match patches.get(of.0) {
            Ok(r) if drawn(&r) && !have.contains_key(&of.0) => {
                have.insert(of.0, (e, mesh.0.clone()));
            }
            _ => {
                commands.entity(e).despawn();
                kernel.triangles.remove(&of.0);
            }
        }
    }
    for r in patches.iter().filter(|r| drawn(r)) {
        let (patch, surface, hidden) = (r.0, &r.1, r.4);
        let visible = streamline && !hidden && surface.stack().is_some();
        let fresh = !have.contains_key(&patch);
        // a surface of the same shape is written into the mesh in place
        // (its triangles are for the grid's shape): a rejoin's moved rows
        // only, every row of a patch built again (a G2 run's members on
        // every frame of a drag); no new mesh, no new triangles
        let in_place = !fresh
            && surface.is_changed()
            && kernel.mesh(patch, surface).is_some()
            && match (
                surface.stack(),
                have.get(&patch).and_then(|(_, h)| meshes.get_mut(h)),
            ) {
                (Some(s), Some(mut mesh)) => {
                    let p = s.finest_points();
                    let all = RowSpan {
                        lo: 0,
                        hi: p.rows().saturating_sub(1),
                    };
                    write_rows(&mut mesh, p, &surface.normals, surface.rows.unwrap_or(all))
                }
                _ => false,
            };
        if in_place {
            kernel.rebuilt += 1;
            kernel.partial += u64::from(surface.rows.is_some());
            kernel.in_place += 1;
        } else if fresh || surface.is_changed() || !kernel.is_drawn(patch) {
            let old = kernel.triangles.remove(&patch);
            let (bevy_mesh, triangles) = match surface.stack() {
                Some(s) => {
                    let p = s.finest_points();
                    let t = Triangles::of(p.rows(), p.cols(), old);
                    let normals = normals_for(p, &surface.normals);
                    (to_bevy_mesh(p.data(), &normals, &t.indices), t)
                }
                None => (to_bevy_mesh(&[], &[], &[]), Triangles::default()),
            };
            match have.get(&patch) {
                Some((_, h)) => {
                    if let Some(mut mesh) = meshes.get_mut(h) {
                        *mesh = bevy_mesh;
                    }
                }
                None => {
                    let e = commands
                        .spawn((
                            PatchSurfaceMesh(patch),
                            Mesh3d(meshes.add(bevy_mesh)),
                            MeshMaterial3d(material.0.clone()),
                            Transform::from_rotation(kernel_to_view()),
                            if visible {
                                Visibility::Inherited
                            } else {
                                Visibility::Hidden
                            },
                        ))
                        .id();
                    have.insert(patch, (e, Handle::default()));
                }
            }
            kernel.triangles.insert(patch, triangles);
            kernel.rebuilt += 1;
        }
        if let Ok((_, _, _, mut v)) = shown.get_mut(have[&patch].0) {
            set_visible(&mut v, visible);
        }
    }
    // a patch no longer drawn from its stack leaves the picking
    let keep: Vec<Entity> = patches.iter().filter(|r| drawn(r)).map(|r| r.0).collect();
    kernel.triangles.retain(|p, _| keep.contains(p));
}

#[cfg(test)]
mod tests;
