//! The 3D view: the shaded surface, streamlines, control tangent arrows, axes and a ground grid.
//! Scene axes: the kernel's `z` is up; Bevy's `y` is up, so positions are shown as `(x, z, −y)`.

use super::state::{DesignState, SurfaceEntity};
use bevy::prelude::*;
use streamline_kernel::DVec3;
use streamline_kernel::streamline::point_at;

pub struct SurfaceViewPlugin;

impl Plugin for SurfaceViewPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(Startup, setup)
            .add_systems(Update, draw_gizmos);
    }
}

/// Kernel coordinates (z up) to Bevy's (y up).
pub fn to_view(p: DVec3) -> Vec3 {
    Vec3::new(p.x as f32, p.z as f32, -p.y as f32)
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
    commands.spawn((
        SurfaceEntity,
        Mesh3d(meshes.add(Mesh::from(Cuboid::new(0.0, 0.0, 0.0)))),
        MeshMaterial3d(material),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9000.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(3.0, 8.0, 5.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 3500.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(-4.0, 2.0, -6.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.insert_resource(GlobalAmbientLight {
        brightness: 400.0,
        ..default()
    });
}

fn draw_gizmos(state: Res<DesignState>, mut gizmos: Gizmos) {
    // axes: red x, green y (the kernel's), and a ground grid
    gizmos.line(
        Vec3::ZERO,
        to_view(DVec3::X * 1.5),
        Color::srgb(0.9, 0.2, 0.2),
    );
    gizmos.line(
        Vec3::ZERO,
        to_view(DVec3::Y * 1.5),
        Color::srgb(0.2, 0.85, 0.3),
    );
    gizmos.grid(
        Isometry3d::new(
            Vec3::new(2.0, -0.3, 0.0),
            Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
        ),
        UVec2::new(16, 12),
        Vec2::splat(0.5),
        Color::srgba(0.5, 0.5, 0.55, 0.35),
    );
    let Some(built) = &state.built else { return };
    let pts = &built.points;
    let step = (pts.rows() / 40).max(1);
    for r in (0..pts.rows()).step_by(step) {
        gizmos.linestrip(
            pts.row(r).iter().map(|&p| to_view(p)),
            Color::srgb(0.15, 0.3, 0.75),
        );
    }
    // control tangents: yellow arrows at their streamline points (level 0)
    let Some(cp) = &state.control_points else {
        return;
    };
    let net = &state.design.net;
    let s = &state.design.params.s;
    for r in 0..net.rows() {
        for c in 0..net.cols() {
            let t = net.get(r, c);
            let at = point_at(cp.row(r), net.row(r), s.row(r), s.get(r, c));
            let base = to_view(at);
            gizmos
                .arrow(base, base + to_view(t) * 0.35, Color::srgb(1.0, 0.85, 0.1))
                .with_tip_length(0.08);
        }
    }
}
