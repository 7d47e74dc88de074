//! Drawing the handles ([`Handles`], placed by the interaction core) as
//! arrows: the control tangents (level 0) as yellow arrows at their
//! streamline points, and the refined tangents of the edit depth as red arrows
//! (optionally every other one), and the initial curve with its control
//! tangents in cyan (a second kind of handle); with mirror symmetry on, the
//! reflected copies on the other half dimmed (they cannot be picked). The head's shape tells the column index apart
//! (cone, ball, cross, ring, repeating, as the paper's prototype gives each
//! index its own head), and a number label names it.

use super::super::coords::to_view;
use super::super::interaction::{
    Drag, EditorMode, EditorSet, Handle, HandleSettings, Handles, MainCamera, Selection,
};
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use bevy_state::prelude::in_state;
use streamline_kernel::DVec3;

pub struct ArrowsPlugin;

/// The initial curve and its arrows: drawn over the surface (the curve is the
/// surface's edge, which would hide them) and a little wider.
#[derive(Default, Reflect, GizmoConfigGroup)]
pub struct InitialGizmos;

impl Plugin for ArrowsPlugin {
    fn build(&self, app: &mut App) {
        app.init_gizmo_group::<InitialGizmos>()
            .add_systems(Startup, |mut config: ResMut<GizmoConfigStore>| {
                let (cfg, _) = config.config_mut::<InitialGizmos>();
                cfg.depth_bias = -1.0;
                cfg.line.width = 2.5;
            })
            .add_systems(
                Update,
                draw.run_if(in_state(EditorMode::Streamline))
                    .in_set(EditorSet::Present),
            )
            .add_systems(
                EguiPrimaryContextPass,
                labels.run_if(in_state(EditorMode::Streamline)),
            );
    }
}

const YELLOW: Color = Color::srgb(1.0, 0.85, 0.1);
const RED: Color = Color::srgb(0.95, 0.25, 0.2);
const SELECTED: Color = Color::srgb(1.0, 1.0, 1.0);
const HOVER: Color = Color::srgb(1.0, 0.6, 0.1);
/// The mirrored half's copies of the control arrows: the yellow, dimmed.
const MIRRORED: Color = Color::srgb(0.55, 0.47, 0.14);
const CYAN: Color = Color::srgb(0.2, 0.85, 0.95);
/// Also selected (a group; the primary is [`SELECTED`]).
const GROUP: Color = Color::srgb(0.75, 0.8, 1.0);

#[allow(clippy::too_many_arguments)]
fn draw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: crate::ecs::patch::PatchRef,
    arrows: Res<Handles>,
    settings: Res<HandleSettings>,
    selection: Res<Selection>,
    drag: Res<Drag>,
    mut gizmos: Gizmos,
    mut initial: Gizmos<InitialGizmos>,
) {
    let _meter = meter.start();
    let edit = arrows.edit_depth;
    let active = drag.0.as_ref().map(|d| d.handle).or(selection.primary());
    let colour = |a: &Handle, base: Color| {
        if a.level() == edit && Some(a.id) == active {
            SELECTED
        } else if a.level() == edit && Some(a.id) == selection.hover {
            HOVER
        } else if a.level() == edit && selection.contains(a.id) {
            GROUP
        } else {
            base
        }
    };
    if settings.controls || edit == 0 {
        for a in &arrows.controls {
            arrow(&mut gizmos, a, colour(a, YELLOW));
        }
        for a in &arrows.mirrored {
            arrow(&mut gizmos, a, MIRRORED);
        }
    }
    if edit > 0 && settings.refined {
        for a in &arrows.editable {
            if settings.shows(a) {
                arrow(&mut gizmos, a, colour(a, RED));
            }
        }
    }
    if settings.initial {
        let curve = patch.design().initial();
        let line: Vec<Vec3> = curve.polyline(96).into_iter().map(to_view).collect();
        initial.linestrip(line, CYAN.with_alpha(0.6));
        for a in &arrows.initial {
            let c = if Some(a.id) == active {
                SELECTED
            } else if Some(a.id) == selection.hover {
                HOVER
            } else if selection.contains(a.id) {
                GROUP
            } else {
                CYAN
            };
            arrow(&mut initial, a, c);
        }
    }
}

/// A shaft and a head whose shape follows the column index: cone, ball, cross, ring.
fn arrow<G: GizmoConfigGroup>(gizmos: &mut Gizmos<G>, a: &Handle, color: Color) {
    let base = to_view(a.base);
    let tip = to_view(a.tip());
    let dir = to_view(a.dir).normalize_or(Vec3::X);
    let head = (a.length as f32) * 0.22;
    match a.id.col % 4 {
        0 => {
            gizmos.arrow(base, tip, color).with_tip_length(head);
        }
        1 => {
            gizmos.line(base, tip, color);
            gizmos
                .sphere(Isometry3d::from_translation(tip), head * 0.45, color)
                .resolution(10);
        }
        2 => {
            gizmos.line(base, tip, color);
            let side = dir.any_orthonormal_vector();
            let other = dir.cross(side);
            for v in [side, other, dir] {
                gizmos.line(tip - v * head * 0.5, tip + v * head * 0.5, color);
            }
        }
        _ => {
            gizmos.line(base, tip, color);
            let iso = Isometry3d::new(tip, Quat::from_rotation_arc(Vec3::Z, dir));
            gizmos.circle(iso, head * 0.5, color).resolution(12);
        }
    }
}

/// Column numbers at the control arrows' tips, and the selected handle's index.
fn labels(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    arrows: Res<Handles>,
    settings: Res<HandleSettings>,
    selection: Res<Selection>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
) -> Result {
    let _meter = meter.start();
    let Ok((camera, gt)) = camera.single() else {
        return Ok(());
    };
    let ctx = contexts.ctx_mut()?;
    let painter = ctx.layer_painter(egui::LayerId::new(
        egui::Order::Background,
        egui::Id::new("arrow_labels"),
    ));
    let clip = camera.logical_viewport_rect().map(|r| {
        egui::Rect::from_min_max(egui::pos2(r.min.x, r.min.y), egui::pos2(r.max.x, r.max.y))
    });
    let painter = match clip {
        Some(c) => painter.with_clip_rect(c),
        None => painter,
    };
    let put = |p: DVec3, text: String, color: egui::Color32| {
        if let Ok(v) = camera.world_to_viewport(gt, to_view(p)) {
            painter.text(
                egui::pos2(v.x + 4.0, v.y - 4.0),
                egui::Align2::LEFT_BOTTOM,
                text,
                egui::FontId::proportional(11.0),
                color,
            );
        }
    };
    if settings.labels && (settings.controls || arrows.edit_depth == 0) {
        for a in arrows.controls.iter().filter(|a| a.id.row == 0) {
            put(
                a.tip(),
                a.id.col.to_string(),
                egui::Color32::from_rgb(255, 217, 26),
            );
        }
    }
    if settings.initial && settings.labels {
        for a in &arrows.initial {
            put(
                a.tip(),
                format!("i{}", a.id.col),
                egui::Color32::from_rgb(51, 217, 242),
            );
        }
    }
    if let Some(a) = selection.primary().and_then(|h| arrows.find(h)) {
        let text = if a.id.is_surface() {
            format!("({}, {}) L{}", a.id.row, a.id.col, a.level())
        } else {
            format!("initial {}", a.id.col)
        };
        put(a.tip(), text, egui::Color32::WHITE);
    }
    Ok(())
}
