//! The Selection section around the single-tangent controls: a selected
//! initial-curve tangent (its direction, a rotation about an axis), and a
//! selection of several handles (Shift-click, Shift box) rotated together
//! about an axis by an angle: one `RotateMany` of the surface tangents (and a
//! rotate of each initial-curve tangent), one undo step.

use super::PanelCtx;
use super::selection::set_component;
use crate::ecs::Edit;
use crate::editor::interaction::HandleId;
use bevy_egui::egui;
use streamline_kernel::DVec3;

/// Axis and angle typed for a group or initial-tangent rotation.
#[derive(Debug, Clone, Copy)]
struct Turn {
    axis: [f64; 3],
    degrees: f64,
}

/// The Selection section: a group, an initial-curve tangent, or the surface
/// tangent's own controls.
pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let n = p.selection.len();
    match p.selection.primary() {
        Some(h) if n == 1 && !h.is_surface() => initial_tangent(ui, p, h),
        Some(_) if n > 1 => several(ui, p),
        _ => super::selection::show(ui, p),
    }
}

/// Axis fields and an angle, kept in egui's memory under `key`.
fn turn_input(ui: &mut egui::Ui, key: &str) -> (Turn, bool) {
    let id = ui.id().with(key);
    let mut t = ui.data(|d| d.get_temp::<Turn>(id)).unwrap_or(Turn {
        axis: [0.0, 0.0, 1.0],
        degrees: 10.0,
    });
    let mut go = false;
    ui.horizontal(|ui| {
        ui.label("axis");
        for (v, name) in t.axis.iter_mut().zip(["x ", "y ", "z "]) {
            ui.add(egui::DragValue::new(v).speed(0.01).prefix(name));
        }
    });
    ui.horizontal(|ui| {
        ui.add(
            egui::DragValue::new(&mut t.degrees)
                .speed(0.5)
                .suffix("°")
                .range(-360.0..=360.0),
        );
        go = ui
            .button("Rotate")
            .on_hover_text("Turn about the axis by the angle (right hand rule), one undo step")
            .clicked();
    });
    ui.data_mut(|d| d.insert_temp(id, t));
    (t, go)
}

/// The axis typed, if usable.
fn axis(t: &Turn) -> Option<DVec3> {
    DVec3::from_array(t.axis)
        .try_normalize()
        .filter(|a| a.is_finite())
}

fn initial_tangent(ui: &mut egui::Ui, p: &mut PanelCtx, h: HandleId) {
    let Some(a) = p.handles.find(h) else {
        ui.label(egui::RichText::new("The selected initial tangent is gone.").weak());
        return;
    };
    ui.label(format!("initial curve tangent {}", h.col))
        .on_hover_text("A control tangent of the QI initial curve (cyan); the streamlines move rigidly with it");
    let mut dir = a.dir.to_array();
    let mut changed = None;
    for (i, name) in ["x", "y", "z"].into_iter().enumerate() {
        let r = ui.add(egui::Slider::new(&mut dir[i], -1.0..=1.0).text(name));
        if r.changed() {
            changed = Some((i, dir[i], r));
        }
    }
    if let Some((i, x, r)) = changed {
        let d = set_component(a.dir, i, x);
        let g = p.slider_group("initial tangent", &r);
        p.send_grouped(h.set_direction(d), g);
    }
    let (t, go) = turn_input(ui, "initial turn");
    if go && let Some(axis) = axis(&t) {
        p.send(h.rotate(axis, t.degrees.to_radians()));
    }
}

fn several(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let ids: Vec<HandleId> = p.selection.iter().collect();
    let surface: Vec<(usize, usize)> = ids
        .iter()
        .filter(|h| h.is_surface())
        .map(|h| h.cell())
        .collect();
    ui.label(format!(
        "{} handles selected ({} surface, {} initial curve)",
        ids.len(),
        surface.len(),
        ids.len() - surface.len()
    ))
    .on_hover_text(
        "Shift-click an arrow to add or remove it, Shift-drag on empty space to add a box; dragging one turns them all",
    );
    let list: Vec<String> = ids
        .iter()
        .take(12)
        .map(|h| {
            if h.is_surface() {
                format!("({}, {})", h.row, h.col)
            } else {
                format!("i{}", h.col)
            }
        })
        .collect();
    let more = if ids.len() > 12 { " …" } else { "" };
    ui.label(egui::RichText::new(format!("{}{more}", list.join(" "))).weak());
    let (t, go) = turn_input(ui, "group turn");
    if go && let Some(axis) = axis(&t) {
        let group = p.groups.fresh();
        let radians = t.degrees.to_radians();
        if !surface.is_empty() {
            p.send_grouped(
                Edit::RotateMany {
                    handles: surface,
                    axis,
                    radians,
                },
                group,
            );
        }
        for h in ids.iter().filter(|h| !h.is_surface()) {
            p.send_grouped(h.rotate(axis, radians), group);
        }
    }
    if ui
        .button("Select one")
        .on_hover_text("Keep only the first selected handle")
        .clicked()
        && let Some(h) = ids.first()
    {
        p.selection.select(*h);
    }
}
