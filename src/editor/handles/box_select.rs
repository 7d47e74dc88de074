//! Box selection: a left drag with Shift held, started on empty space of the
//! 3D view, draws a rectangle; on release every pickable handle (of any
//! kind) whose arrow has its base or tip inside it is added to the
//! selection. Dragging one of the selected arrows then turns them all by the
//! same rotation (the interaction core's drag), one undo step.

use super::super::coords::to_view;
use super::super::interaction::{
    Drag, EditorMode, EditorSet, HandleQuery, HandleSettings, MainCamera, Selection, SphereArea,
};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::input::egui_wants_any_pointer_input;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use bevy_state::prelude::in_state;

/// The box being drawn: where it started and where the pointer is (logical px).
#[derive(Resource, Debug, Default, Clone, Copy, PartialEq)]
pub struct SelectBox(pub Option<(Vec2, Vec2)>);

impl SelectBox {
    /// The box as a rectangle.
    pub fn rect(&self) -> Option<Rect> {
        self.0.map(|(a, b)| Rect::from_corners(a, b))
    }
}

pub struct BoxSelectPlugin;

impl Plugin for BoxSelectPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<SelectBox>()
            .add_systems(
                Update,
                (
                    start.run_if(
                        not(egui_wants_any_pointer_input)
                            .and_then(in_state(EditorMode::Streamline)),
                    ),
                    follow,
                )
                    .chain()
                    .in_set(EditorSet::Input),
            )
            .add_systems(
                EguiPrimaryContextPass,
                draw.run_if(in_state(EditorMode::Streamline)),
            );
    }
}

fn shift(keys: &ButtonInput<KeyCode>) -> bool {
    keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight])
}

/// A Shift + left press on empty space of the 3D view starts a box.
#[allow(clippy::too_many_arguments)]
fn start(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Query<&Camera, With<MainCamera>>,
    sphere: Res<SphereArea>,
    selection: Res<Selection>,
    drag: Res<Drag>,
    mut select_box: ResMut<SelectBox>,
) {
    let _meter = meter.start();
    if !buttons.just_pressed(MouseButton::Left)
        || !shift(&keys)
        || drag.0.is_some()
        || selection.hover.is_some()
    {
        return;
    }
    let Some(p) = window.cursor_position() else {
        return;
    };
    let in_view = camera
        .single()
        .ok()
        .and_then(|c| c.logical_viewport_rect())
        .is_some_and(|r| r.contains(p));
    if in_view && !sphere.contains(p) {
        select_box.0 = Some((p, p));
    }
}

/// Follows the pointer; on release adds the handles inside to the selection.
#[allow(clippy::too_many_arguments)]
fn follow(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    handles: HandleQuery,
    settings: Res<HandleSettings>,
    mut selection: ResMut<Selection>,
    mut select_box: ResMut<SelectBox>,
) {
    let _meter = meter.start();
    let Some((a, b)) = select_box.0 else {
        return;
    };
    let now = window.cursor_position().unwrap_or(b);
    if buttons.pressed(MouseButton::Left) {
        if now != b {
            select_box.0 = Some((a, now));
        }
        return;
    }
    select_box.0 = None;
    let Ok((camera, gt)) = camera.single() else {
        return;
    };
    let rect = Rect::from_corners(a, now);
    let project = |p| camera.world_to_viewport(gt, to_view(p)).ok();
    let inside: Vec<_> = handles
        .pickable(&settings)
        .filter(|h| {
            h.on_screen(project)
                .is_some_and(|(p0, p1)| rect.contains(p0) || rect.contains(p1))
        })
        .map(|h| h.id)
        .collect();
    if !inside.is_empty() {
        selection.extend(inside);
    }
}

/// The box, over the 3D view.
fn draw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    select_box: Res<SelectBox>,
) -> Result {
    let _meter = meter.start();
    let Some(r) = select_box.rect() else {
        return Ok(());
    };
    let ctx = contexts.ctx_mut()?;
    let painter = ctx.layer_painter(egui::LayerId::new(
        egui::Order::Foreground,
        egui::Id::new("select_box"),
    ));
    let rect = egui::Rect::from_min_max(egui::pos2(r.min.x, r.min.y), egui::pos2(r.max.x, r.max.y));
    painter.rect(
        rect,
        0.0,
        egui::Color32::from_rgba_unmultiplied(120, 160, 255, 30),
        egui::Stroke::new(1.0, egui::Color32::from_rgb(150, 180, 255)),
        egui::StrokeKind::Inside,
    );
    Ok(())
}
