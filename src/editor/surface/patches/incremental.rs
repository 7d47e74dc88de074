//! A patch drawn from the incremental pipeline's surface ([`SurfaceData`],
//! docs/math.md §4, §5): the first patch, unless it is drawn from its stack
//! (`super::first_from_stack`). Its positions and normals are swapped with
//! the ones the mesh stage converted while computing them
//! ([`VertexMirror`]); without those, the points the surface's changes
//! rewrote since the last copy ([`SurfaceChanges`]) are written in place,
//! the changed rows' window only; a new shape, or a mesh that showed the
//! patch's stack, is made whole.

use super::super::shaded::{ShownSurface, mirror_shades, to_bevy_mesh};
use crate::ecs::patch::PatchRef;
use crate::ecs::vertex_mirror::{VertexMirror, write_f32};
use crate::ecs::{SurfaceChange, SurfaceChanges, SurfaceData};
use bevy::ecs::system::SystemParam;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;

/// What drawing from the incremental pipeline reads and keeps.
#[derive(SystemParam)]
pub struct Incremental<'w, 's> {
    data: Res<'w, SurfaceData>,
    changes: SurfaceChanges<'w, 's>,
    pub(super) shown: ResMut<'w, ShownSurface>,
    mirror: Option<ResMut<'w, VertexMirror>>,
    pub(super) patch: PatchRef<'w, 's>,
}

impl Incremental<'_, '_> {
    /// Stops (`true`) or resumes the mesh stage's staging pair: paused while
    /// nothing draws this surface (hidden, mesh mode, or its patch drawn
    /// from its stack), so that the mesh stage stages nothing and, deferred,
    /// makes no normals at all; the changes are left unread, so the first
    /// copy once shown sees all of them (or, too late for them, a change of
    /// everything).
    pub(super) fn pause(&mut self, paused: bool) {
        if let Some(m) = self.mirror.as_deref_mut()
            && m.paused() != paused
        {
            m.set_paused(paused);
        }
    }

    /// Brings `mesh` up to date with the surface (module documentation);
    /// `whole`: the mesh shows something else (the patch's stack), so it is
    /// made whole. Returns whether the mesh shows the surface now.
    pub(super) fn draw(&mut self, mesh: &mut Mesh, whole: bool) -> bool {
        // normals left behind (deferred) are not copied: the staging pair
        // has them, or the mesh stage makes them first
        let staged = self.mirror.as_deref().is_some_and(|m| m.staged_whole());
        if self.data.normals_behind().is_some() && (whole || !staged) {
            return !whole;
        }
        let change = self.changes.take();
        if !change.any() && !whole {
            return true;
        }
        self.shown.built = true;
        let data = &*self.data;
        let points = data.points.data();
        let cols = data.points.cols();
        if !whole
            && let Some(m) = self.mirror.as_deref_mut()
            && swap_in(mesh, m, points.len())
        {
            self.shown.full = false;
            return true;
        }
        if !whole
            && let SurfaceChange::Window(w) = change
            && mesh.count_vertices() == points.len()
            && cols > 0
        {
            let rows = || {
                w.rows
                    .iter()
                    .map(move |r| r * cols + w.cols.lo..r * cols + w.cols.hi + 1)
            };
            if let Some(VertexAttributeValues::Float32x3(p)) =
                mesh.attribute_mut(Mesh::ATTRIBUTE_POSITION)
            {
                for range in rows() {
                    write_f32(&mut p[range.clone()], &points[range]);
                }
            }
            if let Some(VertexAttributeValues::Float32x3(n)) =
                mesh.attribute_mut(Mesh::ATTRIBUTE_NORMAL)
            {
                for range in rows() {
                    write_f32(&mut n[range.clone()], &data.normals[range]);
                }
            }
            self.shown.full = false;
            return true;
        }
        *mesh = to_bevy_mesh(points, &data.normals, &data.indices);
        if let Some(m) = self.mirror.as_deref_mut() {
            m.shown_rebuilt();
        }
        if self.patch.structure().mirror {
            mesh.insert_attribute(
                Mesh::ATTRIBUTE_COLOR,
                mirror_shades(data.points.rows(), cols),
            );
        }
        self.shown.full = true;
        true
    }
}

/// Swaps the mesh's positions and normals with the staging pair of `m`
/// when that is up to date and the mesh has the surface's shape.
fn swap_in(mesh: &mut Mesh, m: &mut VertexMirror, points: usize) -> bool {
    if mesh.count_vertices() != points {
        return false;
    }
    let mut normals = match mesh.attribute_mut(Mesh::ATTRIBUTE_NORMAL) {
        Some(VertexAttributeValues::Float32x3(n)) => std::mem::take(n),
        _ => return false,
    };
    let swapped = match mesh.attribute_mut(Mesh::ATTRIBUTE_POSITION) {
        Some(VertexAttributeValues::Float32x3(p)) => m.swap(p, &mut normals, points),
        _ => false,
    };
    if let Some(VertexAttributeValues::Float32x3(n)) = mesh.attribute_mut(Mesh::ATTRIBUTE_NORMAL) {
        *n = normals;
    }
    swapped
}
