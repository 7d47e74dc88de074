//! The design being edited and its build, rebuilt only when something changed.

use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::mesh::SurfaceMesh;
use streamline_kernel::{Built, DVec3, Design, Grid};

/// The design, its settings and its latest build.
#[derive(Resource)]
pub struct DesignState {
    /// The control net, parameters, scheme and initial curve.
    pub design: Design,
    /// The scene's name.
    pub name: String,
    /// Display depth.
    pub depth: u32,
    /// The finest level's build (`None` until the first build or after an error).
    pub built: Option<Built>,
    /// Level-0 streamlines, where the control arrows sit.
    pub control_points: Option<Grid<DVec3>>,
    /// The last build's error, shown in the panel.
    pub error: Option<String>,
    /// Microseconds the last full build took.
    pub build_us: f64,
    /// Set by edits; cleared by the rebuild.
    pub dirty: bool,
}

impl DesignState {
    /// A state that builds on the first frame.
    pub fn new(design: Design, name: String, depth: u32) -> Self {
        DesignState {
            design,
            name,
            depth,
            built: None,
            control_points: None,
            error: None,
            build_us: 0.0,
            dirty: true,
        }
    }
}

/// Marks the entity that shows the surface mesh.
#[derive(Component)]
pub struct SurfaceEntity;

pub struct DesignStatePlugin;

impl Plugin for DesignStatePlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(Update, rebuild.run_if(|s: Res<DesignState>| s.dirty));
    }
}

fn rebuild(
    mut state: ResMut<DesignState>,
    mut meshes: ResMut<Assets<Mesh>>,
    surface: Query<&Mesh3d, With<SurfaceEntity>>,
) {
    state.dirty = false;
    let t0 = Instant::now();
    match state.design.build(state.depth) {
        Ok(built) => {
            state.build_us = t0.elapsed().as_secs_f64() * 1e6;
            for handle in &surface {
                if let Some(mut mesh) = meshes.get_mut(&handle.0) {
                    *mesh = to_bevy_mesh(&built.mesh);
                }
            }
            let base = state.design.base();
            state.control_points = Some(state.design.streamlines(&base));
            state.built = Some(built);
            state.error = None;
        }
        Err(e) => state.error = Some(e.to_string()),
    }
}

/// Converts the kernel's mesh buffers into a Bevy mesh.
pub fn to_bevy_mesh(m: &SurfaceMesh) -> Mesh {
    use bevy::asset::RenderAssetUsages;
    use bevy::mesh::{Indices, PrimitiveTopology};
    let pos: Vec<[f32; 3]> = m.positions.iter().map(|p| p.as_vec3().to_array()).collect();
    let nrm: Vec<[f32; 3]> = m.normals.iter().map(|n| n.as_vec3().to_array()).collect();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, pos)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, nrm)
    .with_inserted_indices(Indices::U32(m.indices.clone()))
}
