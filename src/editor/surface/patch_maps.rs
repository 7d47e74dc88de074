//! The analysis maps on a document's other patches (docs/math.md §11): the
//! Gaussian and mean curvature maps and the zebra stripes that
//! [`super::analysis`] puts on the first patch, on every patch mesh that
//! [`super::patches`] draws from a [`PatchSurface`] stack, so that a map
//! reads across the seams (a G1 seam shows as a kink in the stripes, a G2
//! seam does not).
//!
//! The curvature comes from each patch's finest points
//! ([`surface_curvature`], docs/math.md §10), the stripes from its normals;
//! every patch uses the first patch's colour limit, the one the legend
//! shows, so a colour means the same value on every patch (a patch that
//! curves more saturates). A patch's coordinates are made again only when
//! its surface was rebuilt, its mesh was made afresh, or the mode, the
//! limit, the stripes or (for zebra) the eye moved, and only while it is
//! shown (a hidden patch gets its map when shown again). The map to the
//! reference is the first patch's only (the others stay shaded: a later
//! patch is a surface of its own, not on the reference). The deviation map
//! colours each patch by its distance to its own face of the STEP shell,
//! within that face's tolerance: its part of the one map that holds every
//! patch's distances, the first's too ([`DeviationField::uv`]); a patch
//! without distances (the fit was refused) stays shaded.

use super::analysis_display::{
    AnalysisMaterials, AnalysisSettings, CurvatureField, SurfaceMode, apply_mode, eye_point,
};
use super::colour_maps::{colormap_uv, zebra_uv};
use super::deviation::DeviationField;
use super::patches::PatchSurfaceMesh;
use super::shaded::{ShadedMaterial, SurfaceEntity};
use crate::ecs::joined::PatchSurface;
use crate::editor::interaction::{EditorSet, MainCamera, OrbitCamera};
use bevy::prelude::*;
use std::collections::HashMap;
use streamline_kernel::DVec3;
use streamline_kernel::analysis::{SurfaceCurvature, surface_curvature};

pub struct PatchMapsPlugin;

impl Plugin for PatchMapsPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(
            Update,
            color_patch_maps
                .in_set(EditorSet::Present)
                .after(apply_mode),
        );
    }
}

/// What a patch mesh's map coordinates were made for.
#[derive(Debug, Clone, Copy, PartialEq)]
struct MapKey {
    mode: SurfaceMode,
    limit: f64,
    stripes: f64,
    /// The eye, for zebra stripes (they move with it).
    eye: Option<DVec3>,
    /// The deviation fit the map was made from ([`DeviationField::generation`]).
    fit: u64,
}

/// A patch mesh's map coordinates, or `None` when the mode shows no map
/// on it (shaded; deviation without this patch's distances).
fn patch_uv(
    key: &MapKey,
    surface: &PatchSurface,
    deviation: Option<Vec<[f32; 2]>>,
) -> Option<Vec<[f32; 2]>> {
    let points = surface.stack()?.finest_points();
    match key.mode {
        SurfaceMode::Gaussian | SurfaceMode::Mean => {
            let c = surface_curvature(points);
            let v = if key.mode == SurfaceMode::Gaussian {
                &c.gaussian
            } else {
                &c.mean
            };
            // the first patch's limit; its own before the first map is made
            let limit = if key.limit > 0.0 && key.limit.is_finite() {
                key.limit
            } else {
                SurfaceCurvature::robust_limit(v, 0.98).max(1e-12)
            };
            Some(colormap_uv(v, limit))
        }
        SurfaceMode::Zebra => Some(zebra_uv(
            points.data(),
            &surface.normals,
            key.stripes,
            key.eye.unwrap_or(DVec3::ZERO),
        )),
        SurfaceMode::Deviation => deviation,
        // only the first patch is measured against the reference
        SurfaceMode::Shaded | SurfaceMode::Reference => None,
    }
}

/// The other patches' mesh entities, with their materials.
type DrawnMaps<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        &'static PatchSurfaceMesh,
        &'static Mesh3d,
        &'static mut MeshMaterial3d<StandardMaterial>,
        &'static Visibility,
    ),
    Without<SurfaceEntity>,
>;

/// Gives every patch mesh the mode's material and, for a map, its
/// coordinates (module documentation).
#[allow(clippy::too_many_arguments)]
fn color_patch_maps(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<AnalysisSettings>,
    (field, deviation): (Res<CurvatureField>, Res<DeviationField>),
    (shaded, mats): (Res<ShadedMaterial>, Res<AnalysisMaterials>),
    patches: Query<Ref<PatchSurface>>,
    mut drawn: DrawnMaps,
    camera: Query<&OrbitCamera, With<MainCamera>>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut made: Local<HashMap<Entity, MapKey>>,
) {
    let _meter = meter.start();
    let mode = settings.mode;
    let want = match mode {
        SurfaceMode::Gaussian | SurfaceMode::Mean => &mats.colormap,
        SurfaceMode::Zebra => &mats.zebra,
        SurfaceMode::Deviation => &mats.bands,
        SurfaceMode::Shaded | SurfaceMode::Reference => &shaded.0,
    };
    let key = MapKey {
        mode,
        limit: field.limit,
        stripes: settings.stripes,
        eye: (mode == SurfaceMode::Zebra).then(|| eye_point(&camera)),
        fit: if mode == SurfaceMode::Deviation {
            deviation.generation
        } else {
            0
        },
    };
    made.retain(|e, _| drawn.contains(*e));
    for (e, of, mesh, mut material, visibility) in &mut drawn {
        let Ok(surface) = patches.get(of.0) else {
            continue;
        };
        if *visibility == Visibility::Hidden {
            // a hidden patch (or mesh mode) gets its map when shown again
            made.remove(&e);
            continue;
        }
        let measured = deviation.maps.contains_key(&of.0);
        if !shows_map(mode) || (mode == SurfaceMode::Deviation && !measured) {
            // no map here: shaded (a patch the fit did not measure too)
            if material.0 != shaded.0 {
                material.0 = shaded.0.clone();
            }
            made.remove(&e);
            continue;
        }
        // made for this key, and the mesh still has them (a rebuild of its
        // surface replaces the mesh, coordinates and all)
        let has_uv = meshes
            .get(&mesh.0)
            .is_some_and(|m| m.attribute(Mesh::ATTRIBUTE_UV_0).is_some());
        if made.get(&e) == Some(&key) && has_uv && !surface.is_changed() {
            continue;
        }
        let distances = (mode == SurfaceMode::Deviation)
            .then(|| deviation.uv(of.0))
            .flatten();
        let Some(uv) = patch_uv(&key, &surface, distances) else {
            continue; // not built: nothing drawn
        };
        let Some(mut m) = meshes.get_mut(&mesh.0) else {
            continue;
        };
        if m.count_vertices() != uv.len() {
            continue;
        }
        m.insert_attribute(Mesh::ATTRIBUTE_UV_0, uv);
        if material.0 != *want {
            material.0 = want.clone();
        }
        made.insert(e, key);
    }
}

/// Whether the mode puts a map on the other patches.
fn shows_map(mode: SurfaceMode) -> bool {
    matches!(
        mode,
        SurfaceMode::Gaussian | SurfaceMode::Mean | SurfaceMode::Zebra | SurfaceMode::Deviation
    )
}

#[cfg(test)]
mod tests {
    use super::super::deviation::band_u;
    use super::super::patches::{PatchMeshes, PatchSurfacesPlugin};
    use super::*;
    use crate::ecs::{ModelConfig, ModelSet};
    use crate::editor::interaction::EditorMode;
    use crate::scene::document_io::load;
    use bevy::ecs::system::RunSystemOnce;
    use bevy::mesh::VertexAttributeValues;
    use bevy_state::app::{AppExtStates, StatesPlugin};
    use std::path::Path;

    /// hood-screen-wing's model with the patch meshes and their maps (no
    /// window, no renderer), two updates in.
    fn app(mode: SurfaceMode, limit: f64) -> App {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
        let doc = load(&path).unwrap();
        let mut app = crate::ecs::headless_document_app(&doc, None, ModelConfig::default());
        app.add_plugins(StatesPlugin)
            .init_state::<EditorMode>()
            .init_resource::<Assets<Mesh>>()
            .init_resource::<Assets<StandardMaterial>>()
            .insert_resource(AnalysisSettings { mode, ..default() })
            .init_resource::<CurvatureField>()
            .init_resource::<DeviationField>()
            .init_resource::<PatchMeshes>()
            .init_resource::<super::super::shaded::ShownSurface>()
            .configure_sets(
                Update,
                (EditorSet::Sync, EditorSet::Present)
                    .chain()
                    .after(ModelSet::Output),
            )
            .add_plugins((PatchSurfacesPlugin, PatchMapsPlugin));
        let mut mats = app.world_mut().resource_mut::<Assets<StandardMaterial>>();
        let (shaded, colormap, zebra, bands, ramp) = (
            mats.add(StandardMaterial::default()),
            mats.add(StandardMaterial::default()),
            mats.add(StandardMaterial::default()),
            mats.add(StandardMaterial::default()),
            mats.add(StandardMaterial::default()),
        );
        app.insert_resource(ShadedMaterial(shaded))
            .insert_resource(AnalysisMaterials {
                colormap,
                zebra,
                bands,
                ramp,
            });
        app.world_mut().resource_mut::<CurvatureField>().limit = limit;
        let mesh = (app.world_mut().resource_mut::<Assets<Mesh>>())
            .add(super::super::shaded::to_bevy_mesh(&[], &[], &[]));
        app.world_mut()
            .spawn((SurfaceEntity, Mesh3d(mesh), Visibility::Inherited));
        app.update();
        app.update();
        app
    }

    /// Each drawn patch: its surface, its mesh's `u` coordinates (if any)
    /// and its material.
    type Drawn = (PatchSurface, Option<Vec<f32>>, Handle<StandardMaterial>);

    fn drawn(app: &mut App) -> Vec<Drawn> {
        drawn_of(app).into_iter().map(|(_, d)| d).collect()
    }

    /// [`drawn`], each with its patch's entity.
    fn drawn_of(app: &mut App) -> Vec<(Entity, Drawn)> {
        let w = app.world_mut();
        let mut q = w.query::<(
            &PatchSurfaceMesh,
            &Mesh3d,
            &MeshMaterial3d<StandardMaterial>,
        )>();
        let rows: Vec<_> = q
            .iter(w)
            .map(|(of, m, mat)| (of.0, m.0.clone(), mat.0.clone()))
            .collect();
        rows.into_iter()
            .map(|(p, mesh, mat)| {
                let surface = w.get::<PatchSurface>(p).unwrap().clone();
                let uv = match w
                    .resource::<Assets<Mesh>>()
                    .get(&mesh)
                    .and_then(|m| m.attribute(Mesh::ATTRIBUTE_UV_0).cloned())
                {
                    Some(VertexAttributeValues::Float32x2(v)) => {
                        Some(v.iter().map(|t| t[0]).collect())
                    }
                    _ => None,
                };
                (p, (surface, uv, mat))
            })
            .collect()
    }

    /// The Gaussian map on every joined patch: the colour map's material, one
    /// `u` per vertex, each `0.5 + 0.5·K/limit` (clamped) of the curvature
    /// of the patch's own finest points; back to shaded, the shaded material.
    #[test]
    fn every_patch_shows_the_gaussian_map_with_the_first_patch_limit() {
        let limit = 0.8;
        let mut app = app(SurfaceMode::Gaussian, limit);
        let colormap = app.world().resource::<AnalysisMaterials>().colormap.clone();
        let shaded = app.world().resource::<ShadedMaterial>().0.clone();
        let rows = drawn(&mut app);
        assert_eq!(
            rows.len(),
            2,
            "the screen and the wing are drawn from stacks"
        );
        let mut saturated = 0;
        for (surface, uv, mat) in &rows {
            assert_eq!(*mat, colormap);
            let uv = uv.as_ref().expect("coordinates");
            let points = surface.stack().unwrap().finest_points();
            let k = surface_curvature(points).gaussian;
            assert_eq!(uv.len(), k.len());
            for (u, k) in uv.iter().zip(&k) {
                let want = (0.5 + 0.5 * (k / limit).clamp(-1.0, 1.0)) as f32;
                assert_eq!(u.to_bits(), want.to_bits());
                saturated += usize::from(*u == 0.0 || *u == 1.0);
            }
            assert!(uv.iter().any(|&u| u != 0.5), "a curved patch is coloured");
        }
        assert!(
            saturated
                < rows
                    .iter()
                    .map(|r| r.1.as_ref().unwrap().len())
                    .sum::<usize>()
        );
        // shaded, and the deviation map before any fit measured them: shaded
        for mode in [SurfaceMode::Shaded, SurfaceMode::Deviation] {
            app.world_mut().resource_mut::<AnalysisSettings>().mode = mode;
            app.update();
            for (_, _, mat) in drawn(&mut app) {
                assert_eq!(mat, shaded, "{mode:?}");
            }
        }
    }

    /// The deviation map on the other patches: each gets the bands of its
    /// own face of the STEP shell (its distances, within its face's
    /// tolerance), made again after each fit; a fit without their distances
    /// (refused) leaves them shaded.
    #[test]
    fn each_patch_shows_its_distance_to_its_shell_face() {
        use crate::scene::document_deviation::document_deviation;
        let mut app = app(SurfaceMode::Deviation, 0.8);
        let (bands, shaded) = (
            app.world().resource::<AnalysisMaterials>().bands.clone(),
            app.world().resource::<ShadedMaterial>().0.clone(),
        );
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
        let doc = load(&path).unwrap();
        let (depth, first) = (doc.display_depth, doc.patch_scene(0));
        let first_points = app
            .world()
            .resource::<crate::ecs::SurfaceData>()
            .points
            .data()
            .len();
        // the patch entities in the document's order, as the editor reads them
        let ids = app
            .world_mut()
            .run_system_once(|j: crate::ecs::joined::JoinedRead| j.ids())
            .unwrap();
        assert_eq!(ids.len(), 3);
        let opts = streamline_kernel::nurbs::FitOptions::default();
        app.world_mut().resource_mut::<DeviationField>().refit(
            &first,
            &doc,
            &ids,
            first_points,
            &opts,
        );
        app.update();
        // independently: the shell fitted here, each patch's field from it
        let want = document_deviation(&doc, depth, &opts).unwrap();
        let rows = drawn_of(&mut app);
        assert_eq!(rows.len(), 2);
        let mut coloured = 0;
        for (e, (_, uv, mat)) in rows {
            assert_eq!(mat, bands);
            let i = ids
                .iter()
                .position(|&x| x == e)
                .expect("a patch of the document");
            let p = &want.patches[i];
            let field = &p.field;
            let uv = uv.unwrap_or_else(|| panic!("no coordinates on {}", p.name));
            assert_eq!(uv.len(), field.data().len());
            for (u, d) in uv.iter().zip(field.data()) {
                assert_eq!(u.to_bits(), band_u(*d, p.tolerance).to_bits());
            }
            coloured += uv.iter().filter(|&&u| u > 0.0).count();
        }
        assert!(coloured > 0, "every distance is zero: nothing was measured");
        // a fit without their distances (refused): shaded again
        let mut d = app.world_mut().resource_mut::<DeviationField>();
        d.maps.clear();
        d.generation += 1;
        app.update();
        for (_, _, mat) in drawn(&mut app) {
            assert_eq!(mat, shaded);
        }
    }

    /// A hidden patch is left alone and gets the map of the mode of the
    /// moment it is shown again.
    #[test]
    fn a_hidden_patch_gets_its_map_when_shown() {
        use crate::scene::patch_edit::PatchEdit;
        let mut app = app(SurfaceMode::Gaussian, 0.8);
        let hide = |app: &mut App, on: bool| {
            let e = crate::ecs::Edit::Patch(PatchEdit::HidePatch("wing".into(), on));
            crate::ecs::apply(app, e).unwrap();
            app.update();
        };
        hide(&mut app, true);
        app.world_mut().resource_mut::<AnalysisSettings>().mode = SurfaceMode::Mean;
        app.update();
        let mean = |surface: &PatchSurface| {
            let points = surface.stack().unwrap().finest_points();
            colormap_uv(&surface_curvature(points).mean, 0.8)
                .iter()
                .map(|t| t[0])
                .collect::<Vec<f32>>()
        };
        let rows = drawn(&mut app);
        let stale = rows
            .iter()
            .filter(|(s, uv, _)| uv.as_ref() != Some(&mean(s)));
        assert_eq!(stale.count(), 1, "the hidden wing keeps its Gaussian map");
        hide(&mut app, false);
        for (surface, uv, _) in drawn(&mut app) {
            assert_eq!(uv, Some(mean(&surface)), "shown again: the mean map");
        }
    }

    /// Each drawn patch's `u` are the zebra coordinates of its points and
    /// normals for `eye`, bit for bit.
    fn stripes_match(rows: &[Drawn], eye: DVec3) {
        for (surface, uv, _) in rows {
            let points = surface.stack().unwrap().finest_points();
            let want = zebra_uv(points.data(), &surface.normals, 16.0, eye);
            let got = uv.as_ref().unwrap();
            assert!(
                got.iter()
                    .zip(&want)
                    .all(|(a, b)| a.to_bits() == b[0].to_bits())
            );
        }
    }

    /// Zebra stripes: the zebra material, and coordinates that follow an
    /// edit of the surface (the wing rebuilt, its stripes made again) while
    /// an untouched frame rewrites nothing.
    #[test]
    fn zebra_stripes_follow_the_surface() {
        let mut app = app(SurfaceMode::Zebra, 0.0);
        let zebra = app.world().resource::<AnalysisMaterials>().zebra.clone();
        let before = drawn(&mut app);
        assert!(before.iter().all(|(_, uv, m)| *m == zebra && uv.is_some()));
        let eye = DVec3::new(10.0, -10.0, 10.0); // no camera: the default eye
        stripes_match(&before, eye);
        // a frame without a change keeps them
        app.update();
        let again = drawn(&mut app);
        assert_eq!(
            before.iter().map(|r| r.1.clone()).collect::<Vec<_>>(),
            again.iter().map(|r| r.1.clone()).collect::<Vec<_>>()
        );
        // turn a tangent of the hood: the joined patches move, their stripes too
        crate::ecs::send(
            &mut app,
            crate::ecs::Edit::Rotate {
                row: 2,
                col: 3,
                axis: DVec3::Y,
                radians: 0.2,
            },
        );
        app.update();
        app.update();
        let after = drawn(&mut app);
        stripes_match(&after, eye);
        assert_ne!(
            before.iter().map(|r| r.1.clone()).collect::<Vec<_>>(),
            after.iter().map(|r| r.1.clone()).collect::<Vec<_>>(),
            "the edit moved the stripes"
        );
    }
}
