//! Streamline lengths `L_s(t)` (000 §5: "the total length L_s … can be
//! specified as a function of t"; `docs/math.md §9`), shown in the
//! Selection section: a field per control row, and a plot of `L_s` over the
//! row parameter `t` whose points can be dragged up and down. Each change
//! sends `SetStreamlineLength`, which scales that row's `s` intervals by one
//! factor so by Eq. 65 its streamline is exactly that long; a drag of a field
//! or a point is one undo step.

use super::PanelCtx;
use crate::ecs::Edit;
use crate::ecs::authoring::AuthorEdit;
use bevy_egui::egui;
use egui_plot::{HoverPosition, Line, MarkerShape, Plot, PlotPoint, Points};

/// How near (px) the pointer must press to a point to drag it.
const GRAB_PX: f32 = 14.0;

/// The drag of a point in the plot: its row, and the plot's height fixed at
/// the press (bounds that followed the point would run away from the pointer).
#[derive(Debug, Clone, Copy)]
struct PointDrag {
    row: usize,
    y_max: f64,
}

pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let mut head = egui::CollapsingHeader::new("Streamline lengths L(t)")
        .id_salt("streamline_lengths")
        .default_open(false);
    if p.ui_state.force {
        head = head.open(Some(true));
    }
    head.show(ui, |ui| body(ui, p))
        .header_response
        .on_hover_text(
            "The length of each control row's streamline, as a field per row and a plot over t \
         whose points can be dragged",
        );
}

fn body(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let design = &p.patch.design();
    let rows = design.net().rows();
    let lengths: Vec<f64> = (0..rows)
        .map(|r| design.streamline_length(r).unwrap_or(0.0))
        .collect();
    let ts: Vec<f64> = design.params().t.clone();
    let selected_row = p
        .selection
        .primary()
        .filter(|h| h.level() == 0)
        .map(|h| h.row);
    let drag_id = ui.id().with("length_point_drag");
    let dragging: Option<PointDrag> = ui.data(|d| d.get_temp(drag_id));
    let top = lengths.iter().copied().fold(0.0f64, f64::max).max(1e-6);
    let y_max = dragging.map_or(top * 1.35, |d| d.y_max);
    let (t_lo, t_hi) = (
        ts.first().copied().unwrap_or(0.0),
        ts.last().copied().unwrap_or(1.0),
    );
    let pad = ((t_hi - t_lo).abs() * 0.06).max(1e-6);
    let pts: Vec<[f64; 2]> = ts.iter().zip(&lengths).map(|(&t, &l)| [t, l]).collect();
    let sel: Vec<[f64; 2]> = selected_row
        .and_then(|r| pts.get(r).copied())
        .into_iter()
        .collect();
    let plot = Plot::new("streamline_length_plot")
        .height(130.0)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .allow_boxed_zoom(false)
        .allow_double_click_reset(false)
        .x_axis_label("t")
        .y_axis_label("L")
        .label_formatter(|h| {
            let v = match h {
                HoverPosition::NearDataPoint { position, .. } => position,
                HoverPosition::Elsewhere { position } => position,
            };
            Some(format!("t = {:.3}\nL = {:.4}", v.x, v.y))
        });
    let pts_line = pts.clone();
    let out = plot.show(ui, move |pu| {
        pu.set_plot_bounds_x(t_lo - pad..=t_hi + pad);
        pu.set_plot_bounds_y(0.0..=y_max);
        pu.line(Line::new("L(t)", pts_line.clone()).color(egui::Color32::from_rgb(90, 160, 255)));
        pu.points(
            Points::new("control rows", pts_line.clone())
                .shape(MarkerShape::Circle)
                .radius(4.0)
                .filled(true)
                .color(egui::Color32::from_rgb(255, 217, 26)),
        );
        if !sel.is_empty() {
            pu.points(
                Points::new("selected row", sel)
                    .shape(MarkerShape::Circle)
                    .radius(6.0)
                    .filled(false)
                    .color(egui::Color32::WHITE),
            );
        }
        let r = pu.response().clone();
        // the row under a new press, nearest on screen within GRAB_PX
        let grabbed = if r.drag_started() {
            r.interact_pointer_pos().and_then(|at| {
                pts_line
                    .iter()
                    .enumerate()
                    .map(|(i, q)| {
                        let s = pu.screen_from_plot(PlotPoint::new(q[0], q[1]));
                        (i, s.distance(at))
                    })
                    .filter(|&(_, d)| d <= GRAB_PX)
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .map(|(i, _)| i)
            })
        } else {
            None
        };
        (r, grabbed, pu.pointer_coordinate())
    });
    let (r, grabbed, pointer) = out.inner;
    let _ = out.response.on_hover_text(
        "L of each control row over its t; drag a point up or down to set that streamline's length",
    );
    let drag = match (dragging, grabbed) {
        (_, Some(row)) => Some(PointDrag { row, y_max }),
        (Some(d), None) if r.dragged() => Some(d),
        _ => None,
    };
    match drag {
        Some(d) if r.dragged() || r.drag_started() => {
            ui.data_mut(|m| m.insert_temp(drag_id, d));
            // one undo group for the whole drag (fresh at its press)
            let g = p.slider_group("streamline_length_plot", &r);
            if let Some(at) = pointer {
                let length = at.y.clamp(1e-3 * d.y_max, d.y_max);
                if (length - lengths[d.row]).abs() > 1e-9 {
                    p.send_grouped(
                        Edit::Author(AuthorEdit::SetStreamlineLength { row: d.row, length }),
                        g,
                    );
                }
            }
            if selected_row != Some(d.row) {
                let col = p.selection.primary().map_or(0, |h| h.col);
                p.select_cell((d.row, col.min(p.patch.structure().cols - 1)));
            }
        }
        _ => ui.data_mut(|m| m.remove::<PointDrag>(drag_id)),
    }
    egui::Grid::new("streamline_length_fields")
        .num_columns(4)
        .show(ui, |ui| {
            for (row, &now) in lengths.iter().enumerate() {
                let mut l = now;
                let label = ui.selectable_label(selected_row == Some(row), format!("row {row}"));
                if label.clicked() {
                    let col = p.selection.primary().map_or(0, |h| h.col);
                    p.select_cell((row, col.min(p.patch.structure().cols - 1)));
                }
                let f = ui
                    .add(
                        egui::DragValue::new(&mut l)
                            .speed((now * 0.005).max(1e-4))
                            .range(1e-6..=1e6)
                            .max_decimals(4),
                    )
                    .on_hover_text(format!(
                        "The length of streamline {row} (t = {:.3}); its intervals scale by one factor",
                        ts.get(row).copied().unwrap_or(0.0)
                    ));
                // one undo group a drag of the field (fresh at its press)
                if f.drag_started() || f.changed() {
                    let g = p.slider_group("streamline_length_field", &f);
                    if f.changed() && (l - now).abs() > 1e-12 {
                        p.send_grouped(
                        Edit::Author(AuthorEdit::SetStreamlineLength { row, length: l }),
                        g,
                    );
                    }
                }
                if row % 2 == 1 {
                    ui.end_row();
                }
            }
        });
}
