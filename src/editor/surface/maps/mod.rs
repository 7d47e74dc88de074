//! The analysis maps on every patch's mesh, by one path (docs/math.md §4,
//! §11): the Gaussian and mean curvature maps, the zebra stripes, the
//! deviation map and the map to the reference, put by one system
//! ([`colour_maps`]) on each mesh that `super::patches` draws, the first
//! patch's as any other's, so that a map reads across the seams (a G1 seam
//! shows as a kink in the stripes, a G2 seam does not).
//!
//! A mesh's map is made from the points it shows ([`shown`]): its patch's
//! stack's finest points and the normals its build kept, or, for the first
//! patch drawn from its incremental pipeline, that surface
//! ([`SurfaceData`]). The curvature comes from those points
//! ([`curvature`]), with one colour limit for every patch, the one the
//! legend shows, chosen from the first patch's values (a patch that curves
//! more saturates); the stripes from their normals; the deviation map
//! from the one map of every patch's distances to its face of the STEP
//! shell ([`DeviationField::uv`]; a patch the fit did not measure stays
//! shaded); the map to the reference from its distances, which are the
//! first patch's only (a later patch is a surface of its own, not on the
//! reference: it stays shaded).
//!
//! A mesh's coordinates are made again only when what it shows changed
//! (its surface rebuilt, or the changes of the incremental surface,
//! [`SurfaceChanges`]), or the mode, the curvature limit, the stripes, (for
//! zebra) the eye, the deviation fit or the reference's measure moved, and
//! only while it is shown (a hidden mesh gets its map when shown again).
//! The first patch's colours are also what a glTF export carries
//! ([`ExportSettings::colors`]). A deviation fit slower than a frame waits
//! for the drag to end (docs/cad.md), and so does a map to the reference
//! that is measured then (`super::reference_map`): the colours stay until
//! then.

mod curvature;
mod export_colours;
#[cfg(test)]
mod tests;

use super::super::interaction::{EditorSet, MainCamera, OrbitCamera};
use super::analysis_display::{AnalysisMaterials, AnalysisSettings, CurvatureField, SurfaceMode};
use super::colour_maps::{colormap_uv, ramp_uv, zebra_uv};
use super::deviation::DeviationField;
use super::patch_mesh::normals_for;
use super::patches::{PatchMeshes, PatchSurfaceMesh};
use super::reference_map::{ReferenceField, ReferenceMeasure};
use super::shaded::ShadedMaterial;
use crate::ecs::exchange::ExportSettings;
use crate::ecs::joined::{JoinedRead, PatchSurface};
use crate::ecs::patch::PatchRef;
use crate::ecs::{SurfaceChanges, SurfaceData};
use bevy::prelude::*;
use curvature::Curvatures;
use export_colours::vertex_color;
use std::collections::HashMap;
use streamline_kernel::{DVec3, Grid};

pub struct MapsPlugin;

impl Plugin for MapsPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(
            Update,
            colour_maps
                .in_set(EditorSet::Present)
                .after(ReferenceMeasure),
        );
    }
}

/// What a mesh's map coordinates were made for.
#[derive(Debug, Clone, Copy, PartialEq)]
struct MapKey {
    mode: SurfaceMode,
    /// The curvature maps' limit.
    limit: f64,
    /// The zebra stripes' count and the eye (they move with it).
    stripes: f64,
    eye: Option<DVec3>,
    /// The deviation fit ([`DeviationField::generation`]) or the measure
    /// of the reference ([`ReferenceField::generation`]) the map shows.
    measure: u64,
    /// Whether the mesh shows its patch's stack.
    from_stack: bool,
}

/// What the maps keep between frames.
#[derive(Default)]
struct Made {
    /// Each mesh's map, by mesh entity: what its coordinates were made for.
    keys: HashMap<Entity, MapKey>,
    /// The shown meshes' curvature.
    curvature: Curvatures,
}

/// What a patch mesh shows: the points and normals `super::patches` drew
/// it with.
struct Shown<'a> {
    points: &'a Grid<DVec3>,
    normals: &'a [DVec3],
    /// They changed since the maps last looked.
    changed: bool,
    /// They are its patch's stack's (else the incremental surface's).
    from_stack: bool,
}

/// What patch `p`'s mesh shows: its stack's finest points when it is drawn
/// from its stack ([`PatchMeshes::is_drawn`]), else, for the first patch,
/// the incremental surface `data` (which changed when `first_changed`);
/// `None` for a patch not built.
fn shown<'a>(
    p: Entity,
    first: Entity,
    kernel: &PatchMeshes,
    surfaces: &'a Query<Ref<PatchSurface>>,
    data: &'a SurfaceData,
    first_changed: bool,
) -> Option<Shown<'a>> {
    if kernel.is_drawn(p) {
        let s = surfaces.get(p).ok()?;
        let changed = s.is_changed();
        let s = s.into_inner();
        Some(Shown {
            points: s.stack()?.finest_points(),
            normals: &s.normals,
            changed,
            from_stack: true,
        })
    } else {
        (p == first).then_some(Shown {
            points: &data.points,
            normals: &data.normals,
            changed: first_changed,
            from_stack: false,
        })
    }
}

/// Every patch mesh, the first patch's too, with its material.
type PatchMeshRow = (
    Entity,
    &'static PatchSurfaceMesh,
    &'static Mesh3d,
    &'static mut MeshMaterial3d<StandardMaterial>,
    Option<&'static Visibility>,
);

/// Gives every patch mesh the mode's material and, for a map, its
/// coordinates (module documentation).
#[allow(clippy::too_many_arguments)]
fn colour_maps(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<AnalysisSettings>,
    (mut field, mut deviation, reference): (
        ResMut<CurvatureField>,
        ResMut<DeviationField>,
        Res<ReferenceField>,
    ),
    (shaded, mats): (Res<ShadedMaterial>, Res<AnalysisMaterials>),
    (data, mut changes, kernel): (Res<SurfaceData>, SurfaceChanges, Res<PatchMeshes>),
    (model, joined, mut export, mouse): (
        PatchRef,
        JoinedRead,
        ResMut<ExportSettings>,
        Res<ButtonInput<MouseButton>>,
    ),
    (surfaces, mut removed): (Query<Ref<PatchSurface>>, RemovedComponents<PatchSurface>),
    mut drawn: Query<PatchMeshRow>,
    camera: Query<&OrbitCamera, With<MainCamera>>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut made: Local<Made>,
) {
    let _meter = meter.start();
    let first = model.entity();
    let first_changed = changes.take().any();
    // a patch rebuilt, added or removed: its face, and the shell's seams,
    // change with it
    if first_changed || surfaces.iter().any(|s| s.is_changed()) || removed.read().count() > 0 {
        deviation.stale = true;
    }
    // what each mesh shows; a map whose points changed is made again
    made.keys.retain(|e, _| drawn.contains(*e));
    made.curvature.retain(|e| drawn.contains(e));
    let mut rows = Vec::new();
    for (e, of, ..) in &drawn {
        let s = shown(of.0, first, &kernel, &surfaces, &data, first_changed);
        if s.as_ref().is_none_or(|s| s.changed) {
            made.keys.remove(&e);
            made.curvature.forget(e);
        }
        rows.push((e, of.0, s));
    }
    let mode = settings.mode;
    // a fit slower than a frame waits for the drag to end, and so does a
    // map to the reference measured then: the colours stay
    let pressed = mouse.get_pressed().next().is_some();
    let deferred = pressed
        && match mode {
            SurfaceMode::Deviation => deviation.stale && !deviation.live(),
            SurfaceMode::Reference => reference.stale && reference.values.is_some(),
            _ => false,
        };
    if deferred {
        return;
    }
    if mode == SurfaceMode::Shaded && export.colors.is_some() {
        export.colors = None; // a shaded surface exports no colours
    }
    let visible = |e: Entity| {
        drawn
            .get(e)
            .is_ok_and(|r| r.4.is_none_or(|v| *v != Visibility::Hidden))
    };
    if mode == SurfaceMode::Deviation && (deviation.stale || deviation.generation == 0) {
        match model.scene() {
            // one patch: its one-face fit; several: the STEP shell's faces
            Ok(scene) => {
                let doc = joined.document(scene.clone());
                let ids = joined.ids();
                // the first patch's points as its mesh shows them
                let n = (rows.iter())
                    .find_map(|(_, p, s)| s.as_ref().filter(|_| *p == first))
                    .map_or(data.points.data().len(), |s| s.points.data().len());
                deviation.refit(&scene, &doc, &ids, n, &export.fit);
            }
            Err(e) => {
                deviation.generation += 1;
                deviation.stale = false;
                deviation.error = Some(e);
            }
        }
    }
    let mut limit = 0.0;
    if matches!(mode, SurfaceMode::Gaussian | SurfaceMode::Mean) {
        let mut us = 0.0;
        let mut shown_meshes = Vec::new();
        for (e, _, s) in &rows {
            if let Some(s) = s
                && visible(*e)
            {
                us += made.curvature.make(*e, s.points);
                shown_meshes.push(*e);
            }
        }
        if us > 0.0 {
            field.us = us;
        }
        // the legend's: the first patch's values (a patch that curves more
        // saturates), or, while it is not shown, every shown patch's
        let first_mesh = (rows.iter()).find(|(e, p, _)| *p == first && shown_meshes.contains(e));
        let legend = match first_mesh {
            Some((e, ..)) => vec![*e],
            None => {
                shown_meshes.sort();
                shown_meshes
            }
        };
        limit = made.curvature.limit(&settings, legend, &mut field);
    }
    let eye = (mode == SurfaceMode::Zebra).then(|| eye_point(&camera));
    let measure = match mode {
        SurfaceMode::Deviation => deviation.generation,
        SurfaceMode::Reference => reference.generation,
        _ => 0,
    };
    let want = match mode {
        SurfaceMode::Gaussian | SurfaceMode::Mean => &mats.colormap,
        SurfaceMode::Zebra => &mats.zebra,
        SurfaceMode::Deviation => &mats.bands,
        SurfaceMode::Reference => &mats.ramp,
        SurfaceMode::Shaded => &shaded.0,
    };
    for (e, p, s) in &rows {
        let Ok((.., mesh, mut material, visibility)) = drawn.get_mut(*e) else {
            continue;
        };
        let is_first = *p == first;
        if visibility.is_some_and(|v| *v == Visibility::Hidden) {
            // a hidden patch (or mesh mode) gets its map when shown again
            made.keys.remove(e);
            if is_first && export.colors.is_some() {
                export.colors = None;
            }
            continue;
        }
        let Some(s) = s else {
            continue; // not built: nothing drawn
        };
        let key = MapKey {
            mode,
            limit,
            stripes: if eye.is_some() { settings.stripes } else { 0.0 },
            eye,
            measure,
            from_stack: s.from_stack,
        };
        if made.keys.get(e) == Some(&key) {
            continue;
        }
        let uv = match mode {
            SurfaceMode::Gaussian | SurfaceMode::Mean => made
                .curvature
                .values(*e, mode)
                .map(|v| colormap_uv(v, limit)),
            SurfaceMode::Zebra => Some(zebra_uv(
                s.points.data(),
                &normals_for(s.points, s.normals),
                settings.stripes,
                eye.unwrap_or(DVec3::ZERO),
            )),
            SurfaceMode::Deviation => deviation.uv(*p),
            // measured on the first patch as drawn
            SurfaceMode::Reference if is_first => {
                (reference.values.as_ref()).map(|v| ramp_uv(v, reference.tolerance))
            }
            SurfaceMode::Reference | SurfaceMode::Shaded => None,
        };
        // (read first: a mesh taken mutably is sent to the renderer again)
        let fits = |uv: &Vec<[f32; 2]>| {
            (meshes.get(&mesh.0)).is_some_and(|m| m.count_vertices() == uv.len())
        };
        let Some((uv, mut m)) = uv
            .filter(fits)
            .and_then(|uv| Some((uv, meshes.get_mut(&mesh.0)?)))
        else {
            // no map here: shaded
            if material.0 != shaded.0 {
                material.0 = shaded.0.clone();
            }
            made.keys.remove(e);
            if is_first && export.colors.is_some() {
                export.colors = None;
            }
            continue;
        };
        if is_first {
            // the colours the map shows, for a glTF export's COLOR_0 (docs/cad.md)
            export.colors = Some(uv.iter().map(|t| vertex_color(mode, t[0])).collect());
        }
        m.insert_attribute(Mesh::ATTRIBUTE_UV_0, uv);
        if material.0 != *want {
            material.0 = want.clone();
        }
        made.keys.insert(*e, key);
    }
}

/// The eye point of the main camera (kernel coordinates): zebra stripes
/// are reflections and move with it.
fn eye_point(camera: &Query<&OrbitCamera, With<MainCamera>>) -> DVec3 {
    camera
        .single()
        .map(|c| c.target + c.eye_dir() * c.distance)
        .unwrap_or(DVec3::new(10.0, -10.0, 10.0))
}
