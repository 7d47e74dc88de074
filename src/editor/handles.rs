//! Tangent arrows: the control tangents (level 0) as yellow arrows at their
//! streamline points, and the refined tangents of the edit depth as red arrows
//! (optionally every other one). The head's shape tells the column index apart
//! (cone, ball, cross, ring, repeating, as the paper's prototype gives each
//! index its own head), and a number label names it.

use super::camera::MainCamera;
use super::coords::to_view;
use super::picking::{Drag, Selection};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::{Model, ModelSet};
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use streamline_kernel::DVec3;
use streamline_kernel::finetune::streamline::point_by_fraction;
use streamline_kernel::levels::incremental::{LevelState, place_row_tuned};

/// One arrow: a tangent at its streamline point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arrow {
    /// Level of the tangent.
    pub level: u32,
    /// Row at that level.
    pub row: usize,
    /// Column at that level.
    pub col: usize,
    /// Its streamline point (kernel coordinates).
    pub base: DVec3,
    /// The unit tangent.
    pub dir: DVec3,
    /// Drawn length.
    pub length: f64,
}

impl Arrow {
    /// The arrow's tip.
    pub fn tip(&self) -> DVec3 {
        self.base + self.dir * self.length
    }
}

/// The arrows to draw and pick, rebuilt when a level changes.
#[derive(Resource, Debug, Default)]
pub struct HandleArrows {
    /// Level-0 control tangents.
    pub controls: Vec<Arrow>,
    /// The handles of the edit depth (the same as `controls` at depth 0).
    pub handles: Vec<Arrow>,
    /// The edit depth they belong to.
    pub edit_depth: u32,
}

impl HandleArrows {
    /// The handle at `(row, col)` of the edit depth.
    pub fn find(&self, (row, col): (usize, usize)) -> Option<&Arrow> {
        self.handles.iter().find(|a| a.row == row && a.col == col)
    }
}

/// How arrows are shown.
#[derive(Resource, Debug, Clone)]
pub struct HandleSettings {
    /// Show the level-0 control tangents.
    pub controls: bool,
    /// Show the refined tangents of the edit depth (when it is above 0).
    pub refined: bool,
    /// Show only every other refined tangent (in both directions).
    pub every_other: bool,
    /// Number labels on the control arrows.
    pub labels: bool,
}

impl Default for HandleSettings {
    fn default() -> Self {
        HandleSettings {
            controls: true,
            refined: true,
            every_other: false,
            labels: true,
        }
    }
}

impl HandleSettings {
    /// Whether a refined handle at `(row, col)` is shown (and so pickable).
    pub fn shows(&self, level: u32, row: usize, col: usize) -> bool {
        level == 0 || !self.every_other || (row.is_multiple_of(2) && col.is_multiple_of(2))
    }
}

pub struct HandlesPlugin;

impl Plugin for HandlesPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<HandleArrows>()
            .init_resource::<HandleSettings>()
            .add_systems(
                Update,
                (rebuild, draw.run_if(super::mesh_mode::streamline_mode))
                    .chain()
                    .after(ModelSet::Output),
            )
            .add_systems(
                EguiPrimaryContextPass,
                labels.run_if(super::mesh_mode::streamline_mode),
            );
    }
}

/// The arrows of one level.
fn level_arrows(model: &Model, l: &LevelState, scale: f64) -> Vec<Arrow> {
    let (rows, cols) = l.shape();
    let initial = &model.scene.design.initial;
    let tuning = model.scene.tuning.as_ref();
    let s = &l.params.s;
    let span: f64 = (0..rows)
        .map(|r| (s.get(r, cols - 1) - s.get(r, 0)) / (cols.max(2) - 1) as f64)
        .sum::<f64>()
        / rows.max(1) as f64;
    let length = (span * scale).max(1e-6);
    let mut pts = Vec::new();
    let mut out = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        place_row_tuned(initial, &l.tangents, &l.params, r, tuning, &mut pts);
        for c in 0..cols {
            // control arrows show the designer's tangents (the interpolated
            // net, when that option is on, is what subdivision starts from)
            let dir = if l.level == 0 {
                model.scene.design.net.get(r, c)
            } else {
                l.tangents.get(r, c)
            };
            let base = point_by_fraction(&pts, s.row(r), s.get(r, c));
            out.push(Arrow {
                level: l.level,
                row: r,
                col: c,
                base,
                dir,
                length,
            });
        }
    }
    out
}

fn rebuild(
    meter: Res<crate::ecs::meter::CpuMeter>,
    model: Res<Model>,
    levels: Query<(&SubdivisionLevel, Ref<LevelData>)>,
    mut arrows: ResMut<HandleArrows>,
) {
    let _meter = meter.start();
    let edit = model.scene.edit_depth;
    let changed = levels
        .iter()
        .any(|(l, d)| (l.0 == 0 || l.0 == edit) && d.is_changed());
    if !changed && arrows.edit_depth == edit && !arrows.controls.is_empty() {
        return;
    }
    let find = |level: u32| levels.iter().find(|(l, _)| l.0 == level).map(|(_, d)| d);
    let Some(base) = find(0) else {
        return;
    };
    let mut controls = level_arrows(&model, &base.0, 0.7);
    // long intervals (a 3×3 net) would give arrows as large as the scene: cap
    // them at a tenth of the control points' extent
    let [lo, hi] =
        streamline_kernel::streamline::surface_mesh::bounds(controls.iter().map(|a| a.base));
    let cap = ((hi - lo).length() * 0.1).max(1e-6);
    let clamp = |v: &mut Vec<Arrow>| {
        for a in v.iter_mut() {
            a.length = a.length.min(cap);
        }
    };
    clamp(&mut controls);
    let handles = if edit == 0 {
        controls.clone()
    } else {
        match find(edit) {
            Some(d) => {
                let mut h = level_arrows(&model, &d.0, 0.8);
                clamp(&mut h);
                h
            }
            None => return,
        }
    };
    *arrows = HandleArrows {
        controls,
        handles,
        edit_depth: edit,
    };
}

const YELLOW: Color = Color::srgb(1.0, 0.85, 0.1);
const RED: Color = Color::srgb(0.95, 0.25, 0.2);
const SELECTED: Color = Color::srgb(1.0, 1.0, 1.0);
const HOVER: Color = Color::srgb(1.0, 0.6, 0.1);

fn draw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    arrows: Res<HandleArrows>,
    settings: Res<HandleSettings>,
    selection: Res<Selection>,
    drag: Res<Drag>,
    mut gizmos: Gizmos,
) {
    let _meter = meter.start();
    let edit = arrows.edit_depth;
    let active = drag.0.as_ref().map(|d| (d.row, d.col)).or(selection.handle);
    let colour = |a: &Arrow, base: Color| {
        if a.level == edit && Some((a.row, a.col)) == active {
            SELECTED
        } else if a.level == edit && Some((a.row, a.col)) == selection.hover {
            HOVER
        } else {
            base
        }
    };
    if settings.controls || edit == 0 {
        for a in &arrows.controls {
            arrow(&mut gizmos, a, colour(a, YELLOW));
        }
    }
    if edit > 0 && settings.refined {
        for a in &arrows.handles {
            if settings.shows(a.level, a.row, a.col) {
                arrow(&mut gizmos, a, colour(a, RED));
            }
        }
    }
}

/// A shaft and a head whose shape follows the column index: cone, ball, cross, ring.
fn arrow(gizmos: &mut Gizmos, a: &Arrow, color: Color) {
    let base = to_view(a.base);
    let tip = to_view(a.tip());
    let dir = to_view(a.dir).normalize_or(Vec3::X);
    let head = (a.length as f32) * 0.22;
    match a.col % 4 {
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
    arrows: Res<HandleArrows>,
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
        for a in arrows.controls.iter().filter(|a| a.row == 0) {
            put(
                a.tip(),
                a.col.to_string(),
                egui::Color32::from_rgb(255, 217, 26),
            );
        }
    }
    if let Some(a) = selection.handle.and_then(|h| arrows.find(h)) {
        put(
            a.tip(),
            format!("({}, {}) L{}", a.row, a.col, a.level),
            egui::Color32::WHITE,
        );
    }
    Ok(())
}
