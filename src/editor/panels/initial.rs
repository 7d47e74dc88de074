//! Initial curve: the QI initial curve's order, arc length and start point,
//! the anchor column (000 Fig. 1(b): streamlines may start at any column),
//! and its control tangents, which are also handles (cyan arrows along the
//! curve, cyan points on the sphere view). Every edit here re-places the
//! streamlines rigidly (Eq. 1) and re-blends no tangent: Stats shows it
//! ("placed again", "re-blended 0").

use super::PanelCtx;
use crate::ecs::Edit;
use crate::ecs::authoring::AuthorEdit;
use crate::editor::interaction::HandleId;
use bevy_egui::egui;
use streamline_kernel::DVec3;

/// The QI curve's highest order (the kernel refuses more).
const MAX_ORDER: usize = 8;

pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let design = &p.patch.design();
    let curve = design.initial();
    let n = curve.qi().tangents().len();
    let (cur_order, cur_length, cur_origin) = (curve.qi().order(), curve.length(), curve.origin());
    let (cur_anchor, cols) = (design.anchor(), design.net().cols());
    let tangents = curve.qi().tangents().to_vec();

    let mut order = cur_order;
    let r = ui
        .add(egui::Slider::new(&mut order, 2..=n.min(MAX_ORDER)).text("order"))
        .on_hover_text("The QI curve's order k (2: great arcs between the tangents; 4: cubic)");
    if order != cur_order {
        let g = p.slider_group("initial order", &r);
        p.send_grouped(Edit::Author(AuthorEdit::SetInitialOrder(order)), g);
    }
    let mut length = cur_length;
    let r = ui
        .add(
            egui::DragValue::new(&mut length)
                .speed(cur_length * 0.005)
                .range(1e-6..=f64::MAX)
                .prefix("length "),
        )
        .on_hover_text(
            "The initial curve's arc length: the streamlines keep their t and move apart",
        );
    if length != cur_length {
        let g = p.slider_group("initial length", &r);
        p.send_grouped(Edit::Author(AuthorEdit::SetInitialLength(length)), g);
    }
    let mut origin = cur_origin.to_array();
    let speed = cur_length * 0.005;
    let mut moved = None;
    ui.horizontal(|ui| {
        ui.label("origin");
        for (v, name) in origin.iter_mut().zip(["x ", "y ", "z "]) {
            let r = ui
                .add(egui::DragValue::new(v).speed(speed).prefix(name))
                .on_hover_text(
                    "Where the initial curve starts: every streamline moves by the same vector",
                );
            if r.changed() {
                moved = Some(r);
            }
        }
    });
    if let Some(r) = moved {
        let origin = DVec3::from_array(origin);
        if origin != cur_origin && origin.is_finite() {
            let g = p.slider_group("initial origin", &r);
            p.send_grouped(Edit::Author(AuthorEdit::SetInitialOrigin(origin)), g);
        }
    }
    let mut anchor = cur_anchor;
    let r = ui
        .add(egui::Slider::new(&mut anchor, 0..=cols.saturating_sub(1)).text("anchor column"))
        .on_hover_text(
            "The column whose tangents meet the initial curve: each streamline starts there (000 Fig. 1(b))",
        );
    if anchor != cur_anchor {
        let g = p.slider_group("anchor", &r);
        p.send_grouped(Edit::Author(AuthorEdit::SetAnchor(anchor)), g);
    }
    ui.label(
        egui::RichText::new(format!(
            "{n} control tangents (cyan): drag them in the 3D or sphere view"
        ))
        .weak(),
    );
    egui::Grid::new("initial_tangents")
        .striped(true)
        .show(ui, |ui| {
            for (i, t) in tangents.iter().enumerate() {
                let id = HandleId::initial(i);
                let selected = p.selection.contains(id);
                if ui
                    .selectable_label(selected, format!("i{i}"))
                    .on_hover_text("Select this tangent of the initial curve")
                    .clicked()
                {
                    p.selection.select(id);
                }
                ui.label(format!("{:+.3} {:+.3} {:+.3}", t.x, t.y, t.z));
                ui.end_row();
            }
        });
}
