//! Selection: the selected handle's index, its direction as x/y/z sliders that
//! keep unit length, rotation about an axis by an angle, the length
//! coefficient (control tangents), and reset.

use super::PanelCtx;
use crate::ecs::Edit;
use bevy_egui::egui;
use streamline_kernel::DVec3;

/// Sets component `i` of unit vector `v` to `x` and rescales the other two so
/// the length stays 1 (their ratio kept; if both are 0 the next axis takes up the rest).
pub fn set_component(v: DVec3, i: usize, x: f64) -> DVec3 {
    let x = x.clamp(-1.0, 1.0);
    let mut a = v.to_array();
    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
    let rest = (1.0 - x * x).max(0.0).sqrt();
    let norm = (a[j] * a[j] + a[k] * a[k]).sqrt();
    if norm > 1e-12 {
        a[j] *= rest / norm;
        a[k] *= rest / norm;
    } else {
        a[j] = rest;
        a[k] = 0.0;
    }
    a[i] = x;
    DVec3::from_array(a)
}

/// Axis and angle typed by the user, kept between frames.
#[derive(Debug, Clone, Copy)]
struct RotateInput {
    axis: [f64; 3],
    degrees: f64,
    coefficient: f64,
}

pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let depth = p.handles.edit_depth();
    let (rows, cols) = p.handles.shape();
    let Some((mut row, mut col)) = p.selection.cell() else {
        ui.label(
            egui::RichText::new("Click an arrow, or a point on the sphere view, to select it.")
                .weak(),
        );
        if rows > 0
            && ui
                .button("Select (0, 0)")
                .on_hover_text("Select the first handle")
                .clicked()
        {
            p.select_cell((0, 0));
        }
        return;
    };
    ui.horizontal(|ui| {
        ui.label(format!("level {depth}"))
            .on_hover_text("The edit depth: 0 = control tangents, deeper = details");
        ui.add(
            egui::DragValue::new(&mut row)
                .range(0..=rows.saturating_sub(1))
                .prefix("row "),
        )
        .on_hover_text("Row (streamline) of the selected handle");
        ui.add(
            egui::DragValue::new(&mut col)
                .range(0..=cols.saturating_sub(1))
                .prefix("col "),
        )
        .on_hover_text("Column (index along the streamline) of the selected handle");
    });
    p.select_cell((row, col));
    let Some(a) = p.handles.at((row, col)) else {
        return;
    };
    let id = ui.id().with("rotate_input");
    let mut input = ui
        .data(|d| d.get_temp::<RotateInput>(id))
        .unwrap_or(RotateInput {
            axis: [0.0, 0.0, 1.0],
            degrees: 10.0,
            coefficient: 1.1,
        });
    ui.label("direction (unit length kept):");
    for (i, name) in ["x", "y", "z"].into_iter().enumerate() {
        let mut v = a.dir.to_array()[i];
        let r = ui
            .add(
                egui::Slider::new(&mut v, -1.0..=1.0)
                    .text(name)
                    .fixed_decimals(4),
            )
            .on_hover_text(format!(
                "Set {name}; the other two components rescale so the tangent stays a unit vector"
            ));
        let key = ["dir_x", "dir_y", "dir_z"][i];
        let g = p.slider_group(key, &r);
        // egui may report a change from rounding alone: only the user's hand counts
        let by_hand =
            r.dragged() || r.drag_stopped() || r.clicked() || r.has_focus() || r.lost_focus();
        if r.changed() && by_hand && (v - a.dir.to_array()[i]).abs() > 1e-9 {
            let dir = set_component(a.dir, i, v);
            p.send_grouped(Edit::SetDirection { row, col, dir }, g);
        }
    }
    // rotation and length in a sub-section, closed unless asked for: while a
    // drag runs, every widget drawn costs time out of the 4 ms frame budget
    let mut more = egui::CollapsingHeader::new("Rotate about an axis, length")
        .id_salt("selection_more")
        .default_open(false);
    if p.ui_state.force {
        more = more.open(Some(true));
    }
    more.show(ui, |ui| {
        ui.horizontal(|ui| {
            ui.label("axis")
                .on_hover_text("The rotation axis (any length; normalised)");
            for (k, n) in ["x", "y", "z"].into_iter().enumerate() {
                ui.add(
                    egui::DragValue::new(&mut input.axis[k])
                        .speed(0.01)
                        .prefix(n),
                )
                .on_hover_text(format!("Axis component {n}"));
            }
        });
        ui.horizontal(|ui| {
            ui.add(
                egui::DragValue::new(&mut input.degrees)
                    .speed(0.5)
                    .suffix("°"),
            )
            .on_hover_text("Angle, degrees (right-handed about the axis)");
            if ui
                .button("Rotate")
                .on_hover_text("Turn the selected tangent about the axis by the angle")
                .clicked()
            {
                p.send(Edit::Rotate {
                    row,
                    col,
                    axis: DVec3::from_array(input.axis),
                    radians: input.degrees.to_radians(),
                });
            }
            if ui
                .button("tilt axis")
                .on_hover_text(
                    "Use the axis perpendicular to the tangent and the vertical (tilts it up or down)",
                )
                .clicked()
            {
                let ax = a.dir.cross(DVec3::Z).try_normalize().unwrap_or(DVec3::X);
                input.axis = ax.to_array();
            }
        });
        ui.horizontal(|ui| {
            ui.add_enabled(
                depth == 0,
                egui::DragValue::new(&mut input.coefficient).range(0.01..=100.0).speed(0.01).prefix("length ×"),
            )
            .on_hover_text("Length coefficient: scales the arc length of the two intervals beside this control tangent")
            .on_disabled_hover_text("Lengths belong to control tangents: set the edit depth to 0");
            if ui
                .add_enabled(depth == 0, egui::Button::new("Apply"))
                .on_hover_text("Scale the intervals on both sides of this control tangent")
                .on_disabled_hover_text("Set the edit depth to 0 to change lengths")
                .clicked()
            {
                p.send(Edit::SetLength { row, col, coefficient: input.coefficient });
            }
        });
    })
    .header_response
    .on_hover_text("Turn the tangent about any axis by an angle; scale the length of its intervals");
    ui.data_mut(|d| d.insert_temp(id, input));
    let has_detail = p.patch.details().contains_key(&(depth, row, col));
    if depth > 0 {
        if ui
            .add_enabled(has_detail, egui::Button::new("Reset (clear detail)"))
            .on_hover_text("Back to the subdivided tangent: remove this handle's detail")
            .on_disabled_hover_text("This handle has no detail")
            .clicked()
        {
            p.send(Edit::ClearDetail { row, col });
        }
    } else if let Some(orig) = p.opened_direction(row, col) {
        let changed = (orig - a.dir).length() > 1e-12;
        if ui
            .add_enabled(changed, egui::Button::new("Reset"))
            .on_hover_text("Back to the direction it had when the scene was opened")
            .on_disabled_hover_text("Unchanged since the scene was opened")
            .clicked()
        {
            p.send(Edit::SetDirection {
                row,
                col,
                dir: orig,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_component_keeps_unit_length() {
        let v = DVec3::new(0.6, 0.0, 0.8);
        for (i, x) in [(0, 0.9), (1, -0.3), (2, 1.0), (0, -1.0), (1, 0.0)] {
            let w = set_component(v, i, x);
            assert!((w.length() - 1.0).abs() < 1e-12, "{w}");
            assert!((w.to_array()[i] - x).abs() < 1e-12);
        }
        // other two zero: the rest goes to the next axis
        let w = set_component(DVec3::X, 0, 0.6);
        assert!((w - DVec3::new(0.6, 0.8, 0.0)).length() < 1e-12);
    }
}
