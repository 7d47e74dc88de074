//! The analysis displays' settings and shared state: what the surface
//! shows ([`SurfaceMode`]: shaded, Gaussian and mean curvature maps with a
//! legend, zebra stripes, the deviation map, [`super::deviation`], and the
//! map to the reference, [`super::reference_map`], which measures), the
//! curvature comb, the legend's figures ([`CurvatureField`]) and the maps'
//! materials. The maps are put on every patch's mesh by one path,
//! [`super::maps`] (the ramps and coordinates: [`super::colour_maps`]); the
//! GPU only looks a value up in a texture through the vertex's `u`
//! coordinate, so stripes and colour bands stay crisp inside large
//! triangles. The combs are [`super::combs`].

use super::super::interaction::{Drag, EditorSet};
use super::colour_maps::{STRIPES, diverging, reference_ramp, texture};
use super::deviation::{BANDS, DeviationField};
use super::reference_map::{ReferenceField, ReferenceMeasure};
use crate::ecs::joined::g2::G2RunState;
use crate::ecs::patch::Joined;
use crate::ecs::{DeferNormals, ModelSet};
use bevy::image::{ImageFilterMode, ImageSampler};
use bevy::prelude::*;

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

/// The curvature maps' legend: the ranges of `K` and `H` of the first
/// patch (of every shown patch while it is hidden) and the colour limit
/// every patch's map uses, chosen from the same values (`super::maps`).
#[derive(Resource, Debug, Default)]
pub struct CurvatureField {
    /// `(min, max)` of `K`.
    pub gaussian_range: (f64, f64),
    /// `(min, max)` of `H`.
    pub mean_range: (f64, f64),
    /// The limit the colour map uses now.
    pub limit: f64,
    /// Microseconds the last curvature computation took.
    pub us: f64,
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
                show_reference
                    .before(ReferenceMeasure)
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
/// G2 run (the run makes its surface, and the first patch is drawn from its
/// stack, `super::patches::first_from_stack`, the incremental one's staging
/// paused, so its normals are not made at all then). The drawn surface has
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::editor::interaction::{ActiveDrag, DragKind, HandleId};
    use bevy::math::DQuat;
    use streamline_kernel::DVec3;

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
