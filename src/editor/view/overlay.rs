//! Lines over the 3D view: red x and green y axes, a ground grid (the
//! streamlines: [`super::streamlines`]); and what the overlay draws.

use super::super::coords::to_view;
use super::super::interaction::{EditorMode, EditorSet, SceneBounds};
use bevy::prelude::*;
use bevy_state::prelude::in_state;
use streamline_kernel::DVec3;

/// What the overlay draws.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct OverlaySettings {
    /// Draw the streamlines.
    pub streamlines: bool,
    /// At most this many streamlines are drawn (evenly spread).
    pub max_streamlines: usize,
    /// Axes and ground grid.
    pub axes_and_grid: bool,
}

impl Default for OverlaySettings {
    fn default() -> Self {
        OverlaySettings {
            streamlines: true,
            max_streamlines: 48,
            axes_and_grid: true,
        }
    }
}

pub struct OverlayPlugin;

impl Plugin for OverlayPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<OverlaySettings>().add_systems(
            Update,
            draw.in_set(EditorSet::Present)
                .run_if(in_state(EditorMode::Streamline)),
        );
    }
}

fn draw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<OverlaySettings>,
    bounds: Res<SceneBounds>,
    mut gizmos: Gizmos,
) {
    let _meter = meter.start();
    if settings.axes_and_grid {
        let size = bounds.size().max(1.0) as f32;
        gizmos.line(
            Vec3::ZERO,
            to_view(DVec3::X) * 0.5 * size,
            Color::srgb(0.9, 0.2, 0.2),
        );
        gizmos.line(
            Vec3::ZERO,
            to_view(DVec3::Y) * 0.5 * size,
            Color::srgb(0.2, 0.85, 0.3),
        );
        let c = bounds.center();
        let floor = DVec3::new(c.x, c.y, bounds.min.z - 0.05 * bounds.size());
        let cell = nice_step(bounds.size() / 8.0) as f32;
        let n = ((bounds.size() as f32 * 1.6 / cell).ceil() as u32).clamp(4, 64);
        gizmos.grid(
            Isometry3d::new(
                to_view(floor),
                Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
            ),
            UVec2::splat(n),
            Vec2::splat(cell),
            Color::srgba(0.5, 0.5, 0.55, 0.35),
        );
    }
}

/// 1, 2 or 5 times a power of ten, at least `x`.
fn nice_step(x: f64) -> f64 {
    let x = x.max(1e-6);
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|k| k * p)
        .find(|&v| v >= x)
        .unwrap_or(10.0 * p)
}
