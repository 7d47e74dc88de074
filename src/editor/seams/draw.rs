//! The seams in the 3D view: a polyline along each join's shared edge in
//! its verdict's colour ([`super::verdict`]), and its continuity (`G0`,
//! `G1`, `G2`) written at its middle point, as the arrows' index labels
//! are written (egui's painter over the view).

use super::super::coords::to_view;
use super::super::interaction::{EditorMode, EditorSet, MainCamera};
use super::{SeamSettings, Seams};
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use bevy_state::prelude::in_state;

/// The seams' lines: wider than the streamlines, and drawn a little in
/// front of the surfaces they lie on (so both sides' triangles do not hide
/// them).
#[derive(Default, Reflect, GizmoConfigGroup)]
pub struct SeamGizmos;

pub struct SeamDrawPlugin;

impl Plugin for SeamDrawPlugin {
    fn build(&self, app: &mut App) {
        app.init_gizmo_group::<SeamGizmos>()
            .add_systems(Startup, |mut config: ResMut<GizmoConfigStore>| {
                let (cfg, _) = config.config_mut::<SeamGizmos>();
                cfg.line.width = 4.0;
                cfg.depth_bias = -0.05;
            })
            .add_systems(
                Update,
                lines
                    .in_set(EditorSet::Present)
                    .run_if(in_state(EditorMode::Streamline)),
            )
            .add_systems(
                EguiPrimaryContextPass,
                labels.run_if(in_state(EditorMode::Streamline)),
            );
    }
}

/// The seams' polylines, in their verdicts' colours.
fn lines(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<SeamSettings>,
    seams: Res<Seams>,
    mut gizmos: Gizmos<SeamGizmos>,
) {
    let _meter = meter.start();
    if !settings.show {
        return;
    }
    for s in seams.lines.iter().filter(|s| !s.hidden) {
        let c = s.verdict.bevy();
        gizmos.linestrip(s.points.iter().map(|&p| to_view(p)), c);
    }
}

/// The middle point of a seam's polyline (`None` when it has none).
pub fn middle(points: &[streamline_kernel::DVec3]) -> Option<streamline_kernel::DVec3> {
    match points.len() {
        0 => None,
        n if n % 2 == 1 => Some(points[n / 2]),
        n => Some(0.5 * (points[n / 2 - 1] + points[n / 2])),
    }
}

/// `G0`/`G1`/`G2` at each seam's middle, in its verdict's colour on a dark plate.
fn labels(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    settings: Res<SeamSettings>,
    seams: Res<Seams>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
) -> Result {
    let _meter = meter.start();
    if !settings.show || seams.lines.is_empty() {
        return Ok(());
    }
    let Ok((camera, gt)) = camera.single() else {
        return Ok(());
    };
    let ctx = contexts.ctx_mut()?;
    let painter = ctx.layer_painter(egui::LayerId::new(
        egui::Order::Background,
        egui::Id::new("seam_labels"),
    ));
    let painter = match camera.logical_viewport_rect() {
        Some(r) => painter.with_clip_rect(egui::Rect::from_min_max(
            egui::pos2(r.min.x, r.min.y),
            egui::pos2(r.max.x, r.max.y),
        )),
        None => painter,
    };
    for s in seams.lines.iter().filter(|s| !s.hidden) {
        let Some(m) = middle(&s.points) else {
            continue;
        };
        let Ok(v) = camera.world_to_viewport(gt, to_view(m)) else {
            continue;
        };
        let [r, g, b] = s.verdict.color();
        let galley = painter.layout_no_wrap(
            s.continuity.name().to_string(),
            egui::FontId::proportional(13.0),
            egui::Color32::from_rgb(r, g, b),
        );
        let at = egui::pos2(v.x + 6.0, v.y - 6.0 - galley.size().y);
        let plate = egui::Rect::from_min_size(at, galley.size()).expand(2.0);
        painter.rect_filled(plate, 3.0, egui::Color32::from_black_alpha(170));
        painter.galley(at, galley, egui::Color32::WHITE);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::middle;
    use streamline_kernel::DVec3;

    #[test]
    fn the_middle_of_odd_and_even_polylines() {
        assert_eq!(middle(&[]), None);
        let p = |x: f64| DVec3::new(x, 0.0, 0.0);
        assert_eq!(middle(&[p(0.0), p(1.0), p(2.0)]), Some(p(1.0)));
        assert_eq!(middle(&[p(0.0), p(1.0), p(2.0), p(3.0)]), Some(p(1.5)));
    }
}
