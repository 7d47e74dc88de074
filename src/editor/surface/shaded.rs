//! The shaded surface's material, the first patch's mesh entity
//! ([`SurfaceEntity`]), the lights, and the Bevy mesh made from the
//! kernel's buffers. What every patch's mesh shows is kept up to date by
//! one system, `super::patches::sync_surfaces`.

use crate::ecs::vertex_mirror::VertexMirror;
use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use streamline_kernel::DVec3;

use super::super::coords::kernel_to_view;

/// Marks the first patch's mesh entity (it also has its
/// `super::patches::PatchSurfaceMesh`).
#[derive(Component)]
pub struct SurfaceEntity;

/// What the first patch's Bevy mesh shows of its incremental surface
/// ([`crate::ecs::SurfaceData`]).
#[derive(Resource, Default)]
pub struct ShownSurface {
    /// A surface has been copied into it (the patch's stack counts).
    pub built: bool,
    /// The last copy rewrote every vertex.
    pub full: bool,
    /// It shows the patch's stack instead (a G2 run's first patch, shaded:
    /// `super::patches::first_from_stack`).
    pub from_stack: bool,
}

/// The plain shaded material (the analysis plugin swaps in others).
#[derive(Resource)]
pub struct ShadedMaterial(pub Handle<StandardMaterial>);

pub struct SurfacePlugin;

impl Plugin for SurfacePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ShownSurface>()
            .init_resource::<VertexMirror>()
            .add_systems(Startup, setup);
    }
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let material = materials.add(StandardMaterial {
        base_color: Color::srgb(0.62, 0.70, 0.82),
        perceptual_roughness: 0.45,
        metallic: 0.05,
        double_sided: true,
        cull_mode: None,
        ..default()
    });
    commands.insert_resource(ShadedMaterial(material.clone()));
    commands.spawn((
        SurfaceEntity,
        Mesh3d(meshes.add(to_bevy_mesh(&[], &[], &[]))),
        MeshMaterial3d(material),
        Transform::from_rotation(kernel_to_view()),
    ));
    for (illuminance, from) in [
        (9000.0, Vec3::new(3.0, 8.0, 5.0)),
        (3500.0, Vec3::new(-4.0, 2.0, -6.0)),
    ] {
        commands.spawn((
            DirectionalLight {
                illuminance,
                shadow_maps_enabled: false,
                ..default()
            },
            Transform::from_translation(from).looking_at(Vec3::ZERO, Vec3::Y),
        ));
    }
    commands.insert_resource(GlobalAmbientLight {
        brightness: 400.0,
        ..default()
    });
}

/// How much of the colour the mirrored half keeps (`docs/math.md §9`: it is
/// shown, analysed and exported, but not edited).
pub const MIRROR_SHADE: f32 = 0.4;

/// Vertex colours that dim the mirrored half of a mirrored surface: its
/// streamlines are the first half of the rows (the doubled net is symmetric,
/// so every scheme's levels are: the seam is the middle row, or lies between
/// the two middle rows), the design's own rows (the seam included) keep
/// their colour. The materials multiply their colour by it, the analysis
/// maps' too.
pub fn mirror_shades(rows: usize, cols: usize) -> Vec<[f32; 4]> {
    let mut out = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        let k = if r < rows / 2 { MIRROR_SHADE } else { 1.0 };
        out.extend(std::iter::repeat_n([k, k, k, 1.0], cols));
    }
    out
}

/// Converts the kernel's mesh buffers into a Bevy mesh (kernel axes; the
/// entity's transform turns them into the view's).
pub fn to_bevy_mesh(positions: &[DVec3], normals: &[DVec3], indices: &[u32]) -> Mesh {
    let pos: Vec<[f32; 3]> = positions.iter().map(|p| p.as_vec3().to_array()).collect();
    let nrm: Vec<[f32; 3]> = normals.iter().map(|n| n.as_vec3().to_array()).collect();
    let uv = vec![[0.5f32, 0.5]; pos.len()];
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, pos)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, nrm)
    .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, uv)
    .with_inserted_indices(Indices::U32(indices.to_vec()))
}

/// Shows (`Inherited`) or hides a surface, writing the visibility only when
/// it differs (so that change detection sees real changes only).
pub(in crate::editor) fn set_visible(v: &mut Visibility, on: bool) {
    let want = if on {
        Visibility::Inherited
    } else {
        Visibility::Hidden
    };
    if *v != want {
        *v = want;
    }
}
