//! The shaded surface: one mesh entity mirroring [`SurfaceData`]; rows an edit
//! rewrote are patched in place, anything else rebuilds the Bevy mesh. Lights.

use crate::ecs::{ModelSet, SurfaceData};
use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology, VertexAttributeValues};
use bevy::prelude::*;
use streamline_kernel::DVec3;

use super::coords::kernel_to_view;

/// Marks the surface mesh entity.
#[derive(Component)]
pub struct SurfaceEntity;

/// The generation of [`SurfaceData`] the Bevy mesh shows, and what changed last.
#[derive(Resource, Default)]
pub struct ShownSurface {
    /// `SurfaceData::generation` last copied.
    pub generation: u64,
    /// The last copy rewrote every vertex (analysis must redo all).
    pub full: bool,
}

/// The plain shaded material (the analysis plugin swaps in others).
#[derive(Resource)]
pub struct ShadedMaterial(pub Handle<StandardMaterial>);

pub struct SurfacePlugin;

impl Plugin for SurfacePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ShownSurface>()
            .add_systems(Startup, setup)
            .add_systems(Update, sync_mesh.after(ModelSet::Output));
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

pub(super) fn sync_mesh(
    meter: Res<crate::ecs::meter::CpuMeter>,
    data: Res<SurfaceData>,
    mut shown: ResMut<ShownSurface>,
    mut meshes: ResMut<Assets<Mesh>>,
    surface: Single<&Mesh3d, With<SurfaceEntity>>,
) {
    let _meter = meter.start();
    if data.generation == shown.generation {
        return;
    }
    shown.generation = data.generation;
    let Some(mut mesh) = meshes.get_mut(&surface.0) else {
        return;
    };
    let points = data.points.data();
    let cols = data.points.cols();
    if let Some(w) = data.changed
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
                for (p, q) in p[range.clone()].iter_mut().zip(&points[range]) {
                    *p = q.as_vec3().to_array();
                }
            }
        }
        if let Some(VertexAttributeValues::Float32x3(n)) =
            mesh.attribute_mut(Mesh::ATTRIBUTE_NORMAL)
        {
            for range in rows() {
                for (n, m) in n[range.clone()].iter_mut().zip(&data.normals[range]) {
                    *n = m.as_vec3().to_array();
                }
            }
        }
        shown.full = false;
        return;
    }
    *mesh = to_bevy_mesh(points, &data.normals, &data.indices);
    shown.full = true;
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
