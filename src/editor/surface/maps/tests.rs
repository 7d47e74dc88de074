//! Tests of the one path of the analysis maps (`super`): every patch mesh,
//! the first patch's included, coloured from the points it shows.

use super::super::analysis_display::{
    AnalysisMaterials, AnalysisSettings, CurvatureField, SurfaceMode,
};
use super::super::colour_maps::{colormap_uv, zebra_uv};
use super::super::deviation::{DeviationField, band_u};
use super::super::patches::{PatchMeshes, PatchSurfaceMesh, PatchSurfacesPlugin};
use super::super::reference_map::ReferenceField;
use super::super::shaded::{ShadedMaterial, ShownSurface, SurfaceEntity, to_bevy_mesh};
use super::MapsPlugin;
use super::export_colours::vertex_color;
use crate::ecs::exchange::ExportSettings;
use crate::ecs::joined::PatchSurface;
use crate::ecs::{ModelConfig, ModelSet, SurfaceData};
use crate::editor::interaction::{EditorMode, EditorSet};
use crate::scene::design::document_io::load;
use bevy::ecs::system::RunSystemOnce;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use bevy_state::app::{AppExtStates, StatesPlugin};
use std::path::Path;
use streamline_kernel::analysis::{SurfaceCurvature, surface_curvature};
use streamline_kernel::{DVec3, Grid};

fn document(name: &str) -> crate::scene::Document {
    load(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenes")
            .join(name),
    )
    .unwrap()
}

/// `name`'s model with the patch meshes and their maps (no window, no
/// renderer), two updates in.
fn app(name: &str, settings: AnalysisSettings) -> App {
    let mut app = crate::ecs::headless_document_app(&document(name), None, ModelConfig::default());
    app.add_plugins(StatesPlugin)
        .init_state::<EditorMode>()
        .init_resource::<Assets<Mesh>>()
        .init_resource::<Assets<StandardMaterial>>()
        .insert_resource(settings)
        .init_resource::<CurvatureField>()
        .init_resource::<DeviationField>()
        .init_resource::<ReferenceField>()
        .init_resource::<ExportSettings>()
        .init_resource::<ButtonInput<MouseButton>>()
        .init_resource::<ShownSurface>()
        .configure_sets(
            Update,
            (EditorSet::Sync, EditorSet::Present)
                .chain()
                .after(ModelSet::Output),
        )
        .add_plugins((PatchSurfacesPlugin, MapsPlugin));
    let mut mats = app.world_mut().resource_mut::<Assets<StandardMaterial>>();
    let mut add = || mats.add(StandardMaterial::default());
    let (shaded, colormap, zebra, bands, ramp) = (add(), add(), add(), add(), add());
    app.insert_resource(ShadedMaterial(shaded.clone()))
        .insert_resource(AnalysisMaterials {
            colormap,
            zebra,
            bands,
            ramp,
        });
    let mesh = (app.world_mut().resource_mut::<Assets<Mesh>>()).add(to_bevy_mesh(&[], &[], &[]));
    // the first patch's mesh entity, as `super::super::shaded` spawns it
    app.world_mut().spawn((
        SurfaceEntity,
        Mesh3d(mesh),
        MeshMaterial3d(shaded),
        Visibility::Inherited,
    ));
    app.update();
    app.update();
    app
}

fn mode(mode: SurfaceMode) -> AnalysisSettings {
    AnalysisSettings { mode, ..default() }
}

/// A fixed colour limit.
fn fixed(mode: SurfaceMode, limit: f64) -> AnalysisSettings {
    AnalysisSettings {
        mode,
        auto_range: false,
        limit,
        ..default()
    }
}

/// A drawn patch: its entity, the points and normals its mesh shows (its
/// stack's, or the incremental surface's), its mesh's `u` coordinates (if
/// any) and its material.
struct Drawn {
    patch: Entity,
    points: Grid<DVec3>,
    normals: Vec<DVec3>,
    u: Option<Vec<f32>>,
    material: Handle<StandardMaterial>,
}

/// Every patch mesh, the first patch's included.
fn drawn(app: &mut App) -> Vec<Drawn> {
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
        .map(|(patch, mesh, material)| {
            let (points, normals) = if w.resource::<PatchMeshes>().is_drawn(patch) {
                let s = w.get::<PatchSurface>(patch).unwrap();
                (
                    s.stack().unwrap().finest_points().clone(),
                    s.normals.clone(),
                )
            } else {
                let d = w.resource::<SurfaceData>();
                (d.points.clone(), d.normals.clone())
            };
            let u = match (w.resource::<Assets<Mesh>>().get(&mesh))
                .and_then(|m| m.attribute(Mesh::ATTRIBUTE_UV_0).cloned())
            {
                Some(VertexAttributeValues::Float32x2(v)) => Some(v.iter().map(|t| t[0]).collect()),
                _ => None,
            };
            Drawn {
                patch,
                points,
                normals,
                u,
                material,
            }
        })
        .collect()
}

/// Turns tangent (2, 3) of the first patch, and lets the change reach the
/// meshes and their maps.
fn turn_a_tangent(app: &mut App) {
    let e = crate::ecs::Edit::Rotate {
        row: 2,
        col: 3,
        axis: DVec3::Y,
        radians: 0.2,
    };
    crate::ecs::send(app, e);
    app.update();
    app.update();
}

/// The first patch's entity.
fn first_patch(app: &mut App) -> Entity {
    let w = app.world_mut();
    w.run_system_once(|p: crate::ecs::patch::PatchRef| p.entity())
        .unwrap()
}

fn bits(u: &[[f32; 2]]) -> Vec<u32> {
    u.iter().map(|t| t[0].to_bits()).collect()
}

fn u_bits(d: &Drawn) -> Vec<u32> {
    d.u.as_ref()
        .expect("coordinates")
        .iter()
        .map(|u| u.to_bits())
        .collect()
}

/// The Gaussian map on every patch of hood-screen-wing, the hood (the
/// first patch) as the others: the colour map's material and one `u` per
/// vertex, each `0.5 + 0.5·K/limit` (clamped) of the curvature of the points
/// the mesh shows (the hood heads a G2 run: its stack's cut, as shaded),
/// with one limit, the robust one of the hood's `K`, which the legend
/// shows with the hood's range; a fixed limit the same way; back to shaded,
/// the shaded material and no export colours.
#[test]
fn every_patch_shows_the_gaussian_map_with_one_limit() {
    let mut app = app("hood-screen-wing.ron", mode(SurfaceMode::Gaussian));
    let colormap = app.world().resource::<AnalysisMaterials>().colormap.clone();
    let shaded = app.world().resource::<ShadedMaterial>().0.clone();
    let rows = drawn(&mut app);
    assert_eq!(rows.len(), 3, "one mesh a patch, the first included");
    let kernel = app.world().resource::<PatchMeshes>();
    assert!(
        rows.iter().all(|d| kernel.is_drawn(d.patch)),
        "every patch from its stack"
    );
    let k: Vec<Vec<f64>> = rows
        .iter()
        .map(|d| surface_curvature(&d.points).gaussian)
        .collect();
    let first = first_patch(&mut app);
    let hood = rows.iter().position(|d| d.patch == first).unwrap();
    let limit = SurfaceCurvature::robust_limit(&k[hood], 0.98);
    let field = app.world().resource::<CurvatureField>();
    assert_eq!(field.limit.to_bits(), limit.to_bits(), "the legend's limit");
    assert_eq!(field.gaussian_range, SurfaceCurvature::range(&k[hood]));
    let saturated = |k: &[f64]| k.iter().filter(|k| k.abs() > limit).count();
    assert!(
        saturated(&k.concat()) > saturated(&k[hood]),
        "a patch that curves more saturates"
    );
    for (d, k) in rows.iter().zip(&k) {
        assert_eq!(d.material, colormap);
        assert_eq!(u_bits(d), bits(&colormap_uv(k, limit)));
        assert!(
            d.u.as_ref().unwrap().iter().any(|&u| u != 0.5),
            "a curved patch is coloured"
        );
    }
    app.insert_resource(fixed(SurfaceMode::Gaussian, 0.8));
    app.update();
    for d in drawn(&mut app) {
        let k = surface_curvature(&d.points).gaussian;
        assert_eq!(u_bits(&d), bits(&colormap_uv(&k, 0.8)));
    }
    // the glTF export's colours are the first patch's, when it is the only one
    assert!(app.world().resource::<ExportSettings>().colors.is_some());
    app.world_mut().resource_mut::<AnalysisSettings>().mode = SurfaceMode::Shaded;
    app.update();
    for d in drawn(&mut app) {
        assert_eq!(d.material, shaded);
    }
    assert!(app.world().resource::<ExportSettings>().colors.is_none());
}

/// A design of one patch: its mesh is drawn from the incremental surface
/// and the map is made from that, the export's colours are the map's, one
/// a vertex; a turned tangent moves the surface and the map follows it.
#[test]
fn the_first_patch_is_coloured_from_its_incremental_surface() {
    let mut app = app("car1.ron", mode(SurfaceMode::Mean));
    let check = |app: &mut App| {
        let rows = drawn(app);
        assert_eq!(rows.len(), 1);
        let d = &rows[0];
        assert!(!app.world().resource::<PatchMeshes>().is_drawn(d.patch));
        let own = &app.world().resource::<SurfaceData>().points;
        assert_eq!(d.points.data(), own.data(), "the incremental surface");
        let h = surface_curvature(own).mean;
        let limit = SurfaceCurvature::robust_limit(&h, 0.98);
        let uv = colormap_uv(&h, limit);
        assert_eq!(u_bits(d), bits(&uv));
        let colors = app.world().resource::<ExportSettings>().colors.clone();
        let want: Vec<[f32; 4]> = uv
            .iter()
            .map(|t| vertex_color(SurfaceMode::Mean, t[0]))
            .collect();
        assert_eq!(colors, Some(want));
        u_bits(d)
    };
    let before = check(&mut app);
    turn_a_tangent(&mut app);
    assert_ne!(check(&mut app), before, "the edit moved the map");
}

/// The deviation map on every patch: each gets the bands of its own face of
/// the STEP shell (its distances, within its face's tolerance), the first
/// patch too, from the fit the maps make; a fit without their distances
/// (refused) leaves them shaded.
#[test]
fn each_patch_shows_its_distance_to_its_shell_face() {
    use crate::scene::fit::deviation::document_deviation;
    let mut app = app("hood-screen-wing.ron", mode(SurfaceMode::Deviation));
    let (bands, shaded) = (
        app.world().resource::<AnalysisMaterials>().bands.clone(),
        app.world().resource::<ShadedMaterial>().0.clone(),
    );
    let doc = document("hood-screen-wing.ron");
    // the patch entities in the document's order, as the editor reads them
    let ids = app
        .world_mut()
        .run_system_once(|j: crate::ecs::joined::JoinedRead| j.ids())
        .unwrap();
    assert_eq!(ids.len(), 3);
    let opts = streamline_kernel::nurbs::FitOptions::default();
    // independently: the shell fitted here, each patch's field from it
    let want = document_deviation(&doc, doc.display_depth, &opts).unwrap();
    let rows = drawn(&mut app);
    assert_eq!(rows.len(), 3);
    let mut coloured = 0;
    for d in &rows {
        assert_eq!(d.material, bands);
        let i = ids
            .iter()
            .position(|&x| x == d.patch)
            .expect("a patch of the document");
        let p = &want.patches[i];
        let u =
            d.u.as_ref()
                .unwrap_or_else(|| panic!("no coordinates on {}", p.name));
        assert_eq!(u.len(), p.field.data().len());
        for (u, x) in u.iter().zip(p.field.data()) {
            assert_eq!(u.to_bits(), band_u(*x, p.tolerance).to_bits());
        }
        coloured += u.iter().filter(|&&u| u > 0.0).count();
    }
    assert!(coloured > 0, "every distance is zero: nothing was measured");
    // a fit without their distances (refused): shaded
    let mut d = app.world_mut().resource_mut::<DeviationField>();
    d.maps.clear();
    d.generation += 1;
    app.update();
    for d in drawn(&mut app) {
        assert_eq!(d.material, shaded);
    }
}

/// A hidden patch is left alone and gets the map of the mode of the
/// moment it is shown again.
#[test]
fn a_hidden_patch_gets_its_map_when_shown() {
    use crate::scene::edits::patch_edit::PatchEdit;
    let mut app = app("hood-screen-wing.ron", fixed(SurfaceMode::Gaussian, 0.8));
    let hide = |app: &mut App, on: bool| {
        let e = crate::ecs::Edit::Patch(PatchEdit::HidePatch("wing".into(), on));
        crate::ecs::apply(app, e).unwrap();
        app.update();
    };
    hide(&mut app, true);
    app.world_mut().resource_mut::<AnalysisSettings>().mode = SurfaceMode::Mean;
    app.update();
    let mean = |d: &Drawn| bits(&colormap_uv(&surface_curvature(&d.points).mean, 0.8));
    let rows = drawn(&mut app);
    let stale = rows.iter().filter(|d| u_bits(d) != mean(d));
    assert_eq!(stale.count(), 1, "the hidden wing keeps its Gaussian map");
    hide(&mut app, false);
    for d in drawn(&mut app) {
        assert_eq!(u_bits(&d), mean(&d), "shown again: the mean map");
    }
}

/// Zebra stripes on every patch: the zebra material, and coordinates of
/// the points and normals each mesh shows that follow an edit of the
/// surface (a tangent of the hood turned), while a frame without a change
/// keeps them.
#[test]
fn zebra_stripes_follow_the_surface() {
    let mut app = app("hood-screen-wing.ron", mode(SurfaceMode::Zebra));
    let zebra = app.world().resource::<AnalysisMaterials>().zebra.clone();
    let eye = DVec3::new(10.0, -10.0, 10.0); // no camera: the default eye
    let stripes = |app: &mut App| {
        let rows = drawn(app);
        assert_eq!(rows.len(), 3);
        for d in &rows {
            assert_eq!(d.material, zebra);
            let want = zebra_uv(d.points.data(), &d.normals, 16.0, eye);
            assert_eq!(u_bits(d), bits(&want));
        }
        rows.iter().map(u_bits).collect::<Vec<_>>()
    };
    let before = stripes(&mut app);
    app.update();
    assert_eq!(stripes(&mut app), before, "a frame without a change");
    turn_a_tangent(&mut app);
    assert_ne!(stripes(&mut app), before, "the edit moved the stripes");
}
