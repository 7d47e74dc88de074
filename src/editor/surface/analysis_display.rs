//! Curvature displays: the curvature comb along streamlines, Gaussian and mean
//! curvature colour maps with a legend, zebra stripes, the deviation map
//! ([`super::deviation`]) and the map to the reference
//! ([`super::reference_map`], which measures; the colours are put on here). The numbers come from
//! the kernel ([`streamline_kernel::analysis`]), the ramps and coordinates
//! from [`super::colour_maps`]; the GPU only looks a value up
//! in a texture through the vertex's `u` coordinate, so stripes and colour bands
//! stay crisp inside large triangles.

use super::super::coords::to_view;
use super::super::interaction::{Drag, EditorSet, MainCamera, OrbitCamera, SceneBounds};
use super::colour_maps::{
    STRIPES, colormap_uv, diverging, ramp_uv, reference_ramp, texture, zebra_uv,
};
use super::deviation::{BANDS, DeviationField};
use super::reference_map::{ReferenceField, ReferenceMeasure};
use super::shaded::{ShadedMaterial, SurfaceEntity};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::exchange::ExportSettings;
use crate::ecs::joined::g2::G2RunState;
use crate::ecs::joined::{PatchHidden, PatchSurface};
use crate::ecs::patch::Joined;
use crate::ecs::{DeferNormals, ModelSet, SurfaceChanges, SurfaceData};
use bevy::image::{ImageFilterMode, ImageSampler};
use bevy::prelude::*;
use streamline_kernel::analysis::{SurfaceCurvature, comb, surface_curvature};
use streamline_kernel::{DVec3, Grid};

/// What the surface shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SurfaceMode {
    /// Lit, one colour.
    #[default]
    Shaded,
    /// Gaussian curvature `K`, blue (negative) – white – red (positive).
    Gaussian,
    /// Mean curvature `H`.
    Mean,
    /// Reflection lines of horizontal light stripes.
    Zebra,
    /// Distance to the fitted B-spline surface (docs/cad.md): green within
    /// the export tolerance, yellow up to twice it, red beyond.
    Deviation,
    /// Distance to the design's reference (docs/math.md §12,
    /// [`super::reference_map`]): green at 0 to red at the tolerance.
    Reference,
}

impl SurfaceMode {
    /// All modes, for the panel.
    pub const ALL: [SurfaceMode; 6] = [
        SurfaceMode::Shaded,
        SurfaceMode::Gaussian,
        SurfaceMode::Mean,
        SurfaceMode::Zebra,
        SurfaceMode::Deviation,
        SurfaceMode::Reference,
    ];

    /// Its name in the panel and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceMode::Shaded => "shaded",
            SurfaceMode::Gaussian => "gaussian",
            SurfaceMode::Mean => "mean",
            SurfaceMode::Zebra => "zebra",
            SurfaceMode::Deviation => "deviation",
            SurfaceMode::Reference => "reference",
        }
    }

    /// From its name.
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == s)
    }
}

/// Analysis settings (the Analysis panel edits them).
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct AnalysisSettings {
    /// Surface display.
    pub mode: SurfaceMode,
    /// Draw curvature combs.
    pub comb: bool,
    /// Comb length factor (1: the largest tooth is a tenth of the scene).
    pub comb_scale: f64,
    /// At most this many streamlines get a comb.
    pub comb_lines: usize,
    /// Colour-map range from the data (98th percentile of |value|).
    pub auto_range: bool,
    /// The colour map's limit when not automatic: values in `[−limit, limit]`.
    pub limit: f64,
    /// Zebra stripes over the half circle of reflected directions.
    pub stripes: f64,
}

impl Default for AnalysisSettings {
    fn default() -> Self {
        AnalysisSettings {
            mode: SurfaceMode::Shaded,
            comb: false,
            comb_scale: 1.0,
            comb_lines: 12,
            auto_range: true,
            limit: 1.0,
            stripes: 16.0,
        }
    }
}

/// The curvature of the shown surface and the colour map's range in use.
#[derive(Resource, Debug, Default)]
pub struct CurvatureField {
    /// `K` and `H` per vertex (`None` until a map is shown).
    pub values: Option<SurfaceCurvature>,
    /// `(min, max)` of `K`.
    pub gaussian_range: (f64, f64),
    /// `(min, max)` of `H`.
    pub mean_range: (f64, f64),
    /// The limit the colour map uses now.
    pub limit: f64,
    /// Microseconds the last curvature computation took.
    pub us: f64,
    /// The surface changed since `values` were computed.
    stale: bool,
}

/// The maps' materials: a texture looked up through the vertex's `u`.
#[derive(Resource)]
pub(super) struct AnalysisMaterials {
    /// The diverging colour map of `K` and `H`.
    pub colormap: Handle<StandardMaterial>,
    /// The zebra stripes.
    pub zebra: Handle<StandardMaterial>,
    /// The deviation map's bands.
    pub bands: Handle<StandardMaterial>,
    /// The reference map's ramp, green (0) to red (the tolerance).
    pub ramp: Handle<StandardMaterial>,
}

pub struct AnalysisPlugin;

impl Plugin for AnalysisPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<AnalysisSettings>()
            .init_resource::<CurvatureField>()
            .init_resource::<DeviationField>()
            .init_resource::<ReferenceField>()
            .add_systems(Startup, setup)
            .add_systems(
                Update,
                (
                    apply_mode.after(ReferenceMeasure),
                    draw_combs,
                    show_reference.before(ReferenceMeasure),
                )
                    .in_set(EditorSet::Present),
            )
            .add_systems(
                Update,
                defer_normals.after(EditorSet::Drag).before(ModelSet::Edit),
            );
    }
}

fn setup(
    mut commands: Commands,
    mut images: ResMut<Assets<Image>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let ramp = texture(
        (0..256).map(|i| diverging(i as f64 / 255.0)).collect(),
        false,
    );
    let stripes = texture(
        (0..64)
            .map(|i| if i < 32 { STRIPES[0] } else { STRIPES[1] })
            .collect(),
        true,
    );
    let mut bands = texture(BANDS.to_vec(), false);
    if let ImageSampler::Descriptor(d) = &mut bands.sampler {
        // hard band edges
        d.mag_filter = ImageFilterMode::Nearest;
        d.min_filter = ImageFilterMode::Nearest;
    }
    let material = |tex: Handle<Image>| StandardMaterial {
        base_color_texture: Some(tex),
        unlit: true,
        double_sided: true,
        cull_mode: None,
        ..default()
    };
    commands.insert_resource(AnalysisMaterials {
        colormap: materials.add(material(images.add(ramp))),
        zebra: materials.add(material(images.add(stripes))),
        bands: materials.add(material(images.add(bands))),
        ramp: materials.add(material(images.add(texture(
            (0..256).map(|i| reference_ramp(i as f64 / 255.0)).collect(),
            false,
        )))),
    });
}

/// Tells the map to the reference whether it is shown
/// ([`super::reference_map`]).
fn show_reference(settings: Res<AnalysisSettings>, mut field: ResMut<ReferenceField>) {
    let shown = settings.mode == SurfaceMode::Reference;
    if field.shown != shown {
        field.shown = shown;
    }
}

/// Lets the mesh stage leave the surface's `f64` normals behind
/// ([`DeferNormals`]) while a handle is dragged and nothing shown reads
/// them: the zebra stripes do, and so do the joined patches (their meshes
/// and maps start from the first patch's), unless the first patch heads a
/// G2 run (the run makes its surface; while shaded the first patch is drawn
/// from its stack, the incremental one's staging paused, so its normals are
/// not made at all then). The drawn surface has
/// its own `f32` normals all along; the `f64` ones are made in the frame
/// the drag ends, or the frame the stripes are turned on.
fn defer_normals(
    meter: Res<crate::ecs::meter::CpuMeter>,
    drag: Res<Drag>,
    settings: Res<AnalysisSettings>,
    joined: Query<(), With<Joined>>,
    g2_head: Query<(), (With<G2RunState>, Without<Joined>)>,
    mut defer: ResMut<DeferNormals>,
) {
    let _meter = meter.start();
    defer.set_if_neq(DeferNormals(
        drag.0.is_some()
            && settings.mode != SurfaceMode::Zebra
            && (joined.is_empty() || !g2_head.is_empty()),
    ));
}

/// Sets the first patch's material and map coordinates for the mode
/// (its incremental surface, [`SurfaceData`]); `super::patch_maps` does the
/// other patches after it, with the limit it chose.
#[allow(clippy::too_many_arguments)]
pub(super) fn apply_mode(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<AnalysisSettings>,
    data: Res<SurfaceData>,
    mut changes: SurfaceChanges,
    shaded: Res<ShadedMaterial>,
    mats: Res<AnalysisMaterials>,
    mut field: ResMut<CurvatureField>,
    (mut deviation, model, mut export, mouse): (
        ResMut<DeviationField>,
        crate::ecs::patch::PatchRef,
        ResMut<ExportSettings>,
        Res<ButtonInput<MouseButton>>,
    ),
    reference: Res<ReferenceField>,
    (joined, rebuilt, mut removed): (
        crate::ecs::joined::JoinedRead,
        Query<(), Changed<PatchSurface>>,
        RemovedComponents<PatchSurface>,
    ),
    mut meshes: ResMut<Assets<Mesh>>,
    surface: Single<(&Mesh3d, &mut MeshMaterial3d<StandardMaterial>), With<SurfaceEntity>>,
    camera: Query<&OrbitCamera, With<MainCamera>>,
    mut last: Local<Option<(AnalysisSettings, Option<DVec3>, u64)>>,
) {
    let _meter = meter.start();
    let surface_changed = changes.take().any();
    if surface_changed {
        field.stale = true;
        deviation.stale = true;
    }
    // another patch rebuilt, added or removed: its face, and the shell's
    // seams, change with it
    if !rebuilt.is_empty() || removed.read().count() > 0 {
        deviation.stale = true;
    }
    let (mesh, mut material) = surface.into_inner();
    let want = match settings.mode {
        SurfaceMode::Shaded => &shaded.0,
        SurfaceMode::Gaussian | SurfaceMode::Mean => &mats.colormap,
        SurfaceMode::Zebra => &mats.zebra,
        // a fit that measured nothing here (refused) leaves the surface
        // shaded, not the last fit's colours
        SurfaceMode::Deviation
            if !deviation.maps.contains_key(&model.entity()) && deviation.generation > 0 =>
        {
            &shaded.0
        }
        SurfaceMode::Deviation => &mats.bands,
        SurfaceMode::Reference if reference.values.is_none() => &shaded.0,
        SurfaceMode::Reference => &mats.ramp,
    };
    if material.0 != *want {
        material.0 = want.clone();
    }
    let eye = eye_point(&camera);
    let zebra = settings.mode == SurfaceMode::Zebra;
    // zebra stripes are reflections: they move with the eye
    let measured = (settings.mode == SurfaceMode::Reference).then_some(reference.generation);
    let key = (
        settings.clone(),
        zebra.then_some(eye),
        measured.unwrap_or(0),
    );
    // a fit slower than a frame waits for the drag to end (docs/cad.md),
    // and so does a map to the reference that is measured then
    // (`reference_map`): its colours stay until it is measured again
    let pressed = mouse.get_pressed().next().is_some();
    let deferred = pressed
        && match settings.mode {
            SurfaceMode::Deviation => deviation.stale && !deviation.live(),
            SurfaceMode::Reference => reference.stale && reference.values.is_some(),
            _ => false,
        };
    let unchanged = !surface_changed && !deviation.stale && last.as_ref() == Some(&key);
    if deferred {
        return;
    }
    *last = Some(key);
    if settings.mode == SurfaceMode::Shaded && export.colors.is_some() {
        export.colors = None; // a shaded surface exports no colours
    }
    if settings.mode == SurfaceMode::Shaded || unchanged {
        return;
    }
    let uv: Vec<[f32; 2]> = match settings.mode {
        SurfaceMode::Gaussian | SurfaceMode::Mean => {
            if field.stale || field.values.is_none() {
                let t0 = std::time::Instant::now();
                let c = surface_curvature(&data.points);
                field.gaussian_range = SurfaceCurvature::range(&c.gaussian);
                field.mean_range = SurfaceCurvature::range(&c.mean);
                field.values = Some(c);
                field.stale = false;
                field.us = t0.elapsed().as_secs_f64() * 1e6;
            }
            let Some(c) = field.values.as_ref() else {
                return;
            };
            let v = if settings.mode == SurfaceMode::Gaussian {
                &c.gaussian
            } else {
                &c.mean
            };
            let limit = if settings.auto_range {
                SurfaceCurvature::robust_limit(v, 0.98)
            } else {
                settings.limit.abs().max(1e-12)
            };
            let uv = colormap_uv(v, limit);
            field.limit = limit;
            uv
        }
        SurfaceMode::Zebra => zebra_uv(data.points.data(), &data.normals, settings.stripes, eye),
        SurfaceMode::Deviation => {
            if deviation.stale || deviation.generation == 0 {
                match model.scene() {
                    // one patch: its one-face fit; several: the STEP shell's faces
                    Ok(scene) => {
                        let doc = joined.document(scene.clone());
                        let ids = joined.ids();
                        let n = data.points.data().len();
                        deviation.refit(&scene, &doc, &ids, n, &export.fit);
                    }
                    Err(e) => {
                        deviation.generation += 1;
                        deviation.stale = false;
                        deviation.error = Some(e);
                    }
                }
            }
            // the first patch's part of the one map (`patch_maps` colours
            // the others from it)
            let Some(uv) = deviation.uv(model.entity()) else {
                if material.0 != shaded.0 {
                    material.0 = shaded.0.clone();
                }
                return;
            };
            if material.0 != mats.bands {
                material.0 = mats.bands.clone();
            }
            uv
        }
        SurfaceMode::Reference => {
            let Some(v) = reference.values.as_ref() else {
                return;
            };
            ramp_uv(v, reference.tolerance)
        }
        SurfaceMode::Shaded => return,
    };
    // the colours the map shows, for a glTF export's COLOR_0 (docs/cad.md)
    export.colors = Some(
        uv.iter()
            .map(|t| vertex_color(settings.mode, t[0]))
            .collect(),
    );
    if let Some(mut m) = meshes.get_mut(&mesh.0)
        && m.count_vertices() == uv.len()
    {
        m.insert_attribute(Mesh::ATTRIBUTE_UV_0, uv);
    }
}

/// The colour a map's texture shows at `u` (the texel the sampler picks,
/// nearest), as linear RGBA: what glTF's `COLOR_0` holds.
fn vertex_color(mode: SurfaceMode, u: f32) -> [f32; 4] {
    let srgb = match mode {
        SurfaceMode::Gaussian | SurfaceMode::Mean => diverging(u as f64),
        SurfaceMode::Zebra => {
            if u.rem_euclid(1.0) < 0.5 {
                STRIPES[0]
            } else {
                STRIPES[1]
            }
        }
        SurfaceMode::Deviation => BANDS[((u * 3.0) as usize).min(2)],
        SurfaceMode::Reference => reference_ramp(u as f64),
        SurfaceMode::Shaded => [255, 255, 255],
    };
    let linear = |c: u8| {
        let c = c as f32 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    [linear(srgb[0]), linear(srgb[1]), linear(srgb[2]), 1.0]
}

/// The eye point of the main camera (kernel coordinates): zebra stripes
/// are reflections and move with it.
pub(super) fn eye_point(camera: &Query<&OrbitCamera, With<MainCamera>>) -> DVec3 {
    camera
        .single()
        .map(|c| c.target + c.eye_dir() * c.distance)
        .unwrap_or(DVec3::new(10.0, -10.0, 10.0))
}

/// One patch's streamlines for its combs: row `r` is the streamline of
/// points `points.row(r)`, tangents `tangents.row(r)` at arc lengths
/// `s.row(r)`.
struct CombRows<'a> {
    points: &'a Grid<DVec3>,
    tangents: &'a Grid<DVec3>,
    s: &'a Grid<f64>,
}

impl CombRows<'_> {
    /// Up to `lines` rows, spread evenly, the last one always.
    fn chosen(&self, lines: usize) -> impl Iterator<Item = usize> {
        let rows = self.points.rows();
        let step = rows.div_ceil(lines.max(1)).max(1);
        (0..rows).filter(move |&r| r.is_multiple_of(step) || r + 1 == rows)
    }
}

/// Combs on up to `comb_lines` streamlines of every shown patch, spread
/// evenly over each, all at one scale (the largest tooth of all is a tenth of
/// the scene, times the factor): the first patch's from its levels and
/// surface, a joined patch's from its stack's finest level (docs/math.md
/// §11).
#[allow(clippy::too_many_arguments)]
fn draw_combs(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<AnalysisSettings>,
    bounds: Res<SceneBounds>,
    patch: crate::ecs::patch::PatchRef,
    levels: Query<(&SubdivisionLevel, &LevelData)>,
    data: Res<SurfaceData>,
    joined: Query<&PatchSurface, (With<Joined>, Without<PatchHidden>)>,
    mut gizmos: Gizmos,
) {
    let _meter = meter.start();
    if !settings.comb {
        return;
    }
    let depth = patch.structure().display_depth;
    let mut patches = Vec::new();
    // the first patch's streamlines are its surface's rows
    if let Some((_, level)) = levels.iter().find(|(l, _)| l.0 == depth)
        && data.points.rows() > 0
        && data.points.rows() == level.0.tangents.rows()
    {
        patches.push(CombRows {
            points: &data.points,
            tangents: &level.0.tangents,
            s: &level.0.params.s,
        });
    }
    for stack in joined.iter().filter_map(PatchSurface::stack) {
        let finest = stack.finest();
        patches.push(CombRows {
            points: stack.finest_points(),
            tangents: &finest.tangents,
            s: &finest.params.s,
        });
    }
    let lines = settings.comb_lines;
    let kmax = (patches.iter())
        .flat_map(|p| p.chosen(lines).map(move |r| (p, r)))
        .flat_map(|(p, r)| {
            streamline_kernel::analysis::streamline_curvature(p.tangents.row(r), p.s.row(r))
        })
        .fold(0.0f64, f64::max);
    if kmax <= 0.0 {
        return;
    }
    let scale = settings.comb_scale * 0.1 * bounds.size() / kmax;
    let tooth = Color::srgba(0.95, 0.35, 0.85, 0.8);
    let hull = Color::srgb(0.95, 0.35, 0.85);
    for p in &patches {
        for r in p.chosen(lines) {
            let teeth = comb(p.points.row(r), p.tangents.row(r), p.s.row(r), scale);
            for c in &teeth {
                gizmos.line(to_view(c.base), to_view(c.tip), tooth);
            }
            gizmos.linestrip(teeth.iter().map(|c| to_view(c.tip)), hull);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::editor::interaction::{ActiveDrag, DragKind, HandleId};
    use bevy::math::DQuat;

    /// The mesh stage may leave the `f64` normals behind only while a handle
    /// is dragged, the surface is not striped and no patch is joined.
    #[test]
    fn normals_wait_only_for_a_drag_that_nothing_reads_them_in() {
        let mut app = App::new();
        app.init_resource::<crate::ecs::meter::CpuMeter>()
            .init_resource::<Drag>()
            .init_resource::<AnalysisSettings>()
            .init_resource::<DeferNormals>()
            .add_systems(Update, defer_normals);
        let deferred = |app: &mut App| {
            app.update();
            app.world().resource::<DeferNormals>().0
        };
        assert!(!deferred(&mut app), "no drag");
        app.world_mut().resource_mut::<Drag>().0 = Some(ActiveDrag {
            handle: HandleId::tangent(0, 2, 4),
            group: 1,
            start_dir: DVec3::X,
            last: DVec3::X,
            sent: true,
            kind: DragKind::Sphere,
            turned: DQuat::IDENTITY,
        });
        assert!(deferred(&mut app), "a drag, shaded");
        for mode in [
            SurfaceMode::Gaussian,
            SurfaceMode::Mean,
            SurfaceMode::Deviation,
        ] {
            app.world_mut().resource_mut::<AnalysisSettings>().mode = mode;
            assert!(deferred(&mut app), "{mode:?} reads no normals");
        }
        app.world_mut().resource_mut::<AnalysisSettings>().mode = SurfaceMode::Zebra;
        assert!(!deferred(&mut app), "the stripes read them");
        app.world_mut().resource_mut::<AnalysisSettings>().mode = SurfaceMode::Shaded;
        assert!(deferred(&mut app));
        let joined = app.world_mut().spawn(Joined).id();
        assert!(!deferred(&mut app), "a joined patch reads them");
        app.world_mut().despawn(joined);
        assert!(deferred(&mut app));
        app.world_mut().resource_mut::<Drag>().0 = None;
        assert!(!deferred(&mut app), "the drag is over");
    }
}
