//! Mesh mode's drawing: the Loop surface and the given mesh's wireframe as
//! entities, made anew when the surface changes, and the streamline surface
//! hidden while a mesh is open ([`EditorMode::Mesh`]).

use super::MeshView;
use crate::editor::coords::kernel_to_view;
use crate::editor::interaction::{EditorMode, FrameRequest};
use crate::editor::surface::shaded::{SurfaceEntity, set_visible};
use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use bevy_state::prelude::{NextState, State};
use streamline_kernel::loop_subdiv::trimesh::{Topology, TriMesh};

/// Marks the mesh mode's entities.
#[derive(Component)]
pub(super) struct MeshModeSurface;
#[derive(Component)]
pub(super) struct MeshModeWire;

/// The editor is in mesh mode exactly while a mesh is open.
pub(super) fn follow_mode(
    view: Res<MeshView>,
    mode: Res<State<EditorMode>>,
    mut next: ResMut<NextState<EditorMode>>,
) {
    let want = if view.active() {
        EditorMode::Mesh
    } else {
        EditorMode::Streamline
    };
    if *mode.get() != want {
        next.set(want);
    }
}

pub(super) fn hide_streamline_surface(mut q: StreamlineSurface) {
    for mut v in &mut q {
        set_visible(&mut v, false);
    }
}

pub(super) fn show_streamline_surface(mut q: StreamlineSurface) {
    for mut v in &mut q {
        set_visible(&mut v, true);
    }
}

/// The surface's material (the entities themselves are spawned with the first
/// mesh: empty meshes and gizmo assets upset the renderer's allocator).
#[derive(Resource)]
pub(super) struct MeshModeMaterial(Handle<StandardMaterial>);

pub(super) fn setup(mut commands: Commands, mut materials: ResMut<Assets<StandardMaterial>>) {
    let material = materials.add(StandardMaterial {
        base_color: Color::srgb(0.86, 0.72, 0.55),
        perceptual_roughness: 0.5,
        double_sided: true,
        cull_mode: None,
        ..default()
    });
    commands.insert_resource(MeshModeMaterial(material));
}

/// The mesh mode's entities.
pub(super) type Shown<'w, 's> = Query<
    'w,
    's,
    (Entity, &'static mut Visibility, Has<MeshModeWire>),
    Or<(With<MeshModeSurface>, With<MeshModeWire>)>,
>;
/// The streamline surface's entity (hidden while a mesh is open).
pub(super) type StreamlineSurface<'w, 's> = Query<
    'w,
    's,
    &'static mut Visibility,
    (
        With<SurfaceEntity>,
        Without<MeshModeSurface>,
        Without<MeshModeWire>,
    ),
>;

/// Mirrors the view state into entities (spawned anew when the surface
/// changes).
#[allow(clippy::too_many_arguments)]
pub(super) fn show(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut commands: Commands,
    mut view: ResMut<MeshView>,
    material: Res<MeshModeMaterial>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut gizmo_assets: ResMut<Assets<GizmoAsset>>,
    mut frame: ResMut<FrameRequest>,
    mut shown_entities: Shown,
    mut shown: Local<Option<(usize, u32, u64)>>,
) {
    let _meter = meter.start();
    let active = view.active();
    let key = view.doc.surface.as_ref().map(|s| {
        (
            s.positions.len(),
            view.settings.depth,
            view.doc.report.map_or(0, |r| r.max_error.to_bits()),
        )
    });
    if !active || key != *shown {
        // the surface changed (or the mesh closed): replace the entities
        for (e, ..) in &shown_entities {
            commands.entity(e).despawn();
        }
        *shown = None;
        if let (true, Some(s), Some(g)) = (active, &view.doc.surface, &view.doc.given) {
            let (given, topo) = (&g.0, &g.1);
            commands.spawn((
                MeshModeSurface,
                Mesh3d(meshes.add(surface_mesh(s))),
                MeshMaterial3d(material.0.clone()),
                Transform::from_rotation(kernel_to_view()),
            ));
            commands.spawn((
                MeshModeWire,
                Gizmo {
                    handle: gizmo_assets.add(wireframe(given, topo)),
                    line_config: GizmoLineConfig {
                        width: 1.0,
                        ..default()
                    },
                    depth_bias: -0.002,
                },
                Transform::from_rotation(kernel_to_view()),
                if view.settings.show_given {
                    Visibility::Inherited
                } else {
                    Visibility::Hidden
                },
            ));
            *shown = key;
        }
    } else {
        // only the wireframe toggles; the surface is always shown
        for (_, mut v, wire) in &mut shown_entities {
            if wire {
                set_visible(&mut v, view.settings.show_given);
            }
        }
    }
    if view.work.frame {
        view.work.frame = false;
        if let Some(g) = &view.doc.given {
            let (lo, hi) = g.0.bounds();
            frame.0 = Some(((lo + hi) * 0.5, 0.6 * (hi - lo).max_element()));
        }
    }
}

fn surface_mesh(s: &TriMesh) -> Mesh {
    let pos: Vec<[f32; 3]> = s.positions.iter().map(|p| p.as_vec3().to_array()).collect();
    let nrm: Vec<[f32; 3]> = s
        .vertex_normals()
        .iter()
        .map(|n| n.as_vec3().to_array())
        .collect();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, pos)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, nrm)
    .with_inserted_indices(Indices::U32(s.faces.iter().flatten().copied().collect()))
}

/// The given mesh's edges, and a small cross at each vertex.
fn wireframe(m: &TriMesh, topo: &Topology) -> GizmoAsset {
    let mut g = GizmoAsset::new();
    let edge = Color::srgb(0.15, 0.35, 0.9);
    let dot = Color::srgb(0.95, 0.2, 0.15);
    let r = (0.12 * m.mean_edge_length(topo)) as f32;
    for &([a, b], _) in &topo.edges {
        g.line(
            m.positions[a as usize].as_vec3(),
            m.positions[b as usize].as_vec3(),
            edge,
        );
    }
    for p in &m.positions {
        let c = p.as_vec3();
        for d in [Vec3::X, Vec3::Y, Vec3::Z] {
            g.line(c - d * r, c + d * r, dot);
        }
    }
    g
}
