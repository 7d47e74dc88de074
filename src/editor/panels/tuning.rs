//! Fine tuning (paper 003, docs/math.md §6): turn it on, the control values of
//! `α(s, t)` as vertical sliders (rows across the streamlines, columns along them), the
//! constraint, and a plot of `α` along the selected streamline. Every change
//! is an edit message; the curvature maps show the effect as it happens.

use super::PanelCtx;
use crate::ecs::Edit;
use bevy_egui::egui;
use streamline_kernel::Grid;
use streamline_kernel::finetune::bspline::TensorBSpline;
use streamline_kernel::finetune::{Constraint, SurfaceTuning};

/// Largest control value the editor offers (α scales the derivative; 1 keeps it).
const VALUE_MAX: f64 = 4.0;

fn identity(along: usize, across: usize, constraint: Constraint) -> SurfaceTuning {
    let degree = |n: usize| (n - 1).min(2);
    SurfaceTuning {
        function: TensorBSpline::new(
            degree(along),
            degree(across),
            Grid::filled(across, along, 1.0),
        )
        .expect("counts ≥ 2 and degree < count"),
        constraint,
    }
}

pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let tuning = p.patch.tuning().cloned();
    let mut on = tuning.is_some();
    if ui
        .checkbox(&mut on, "scale the derivative by α(s, t)")
        .on_hover_text("Reshape the surface without turning a tangent: every streamline's derivative is multiplied by a smooth B-spline function (1 everywhere changes nothing)")
        .changed()
    {
        p.send(Edit::SetTuning(on.then(|| identity(4, 3, Constraint::Free))));
    }
    let Some(t) = tuning else {
        ui.label(
            egui::RichText::new("Off: the streamlines are integrated as they are (Eq. 65).").weak(),
        );
        return;
    };
    let values = t.function.values().clone();
    let (across, along) = (values.rows(), values.cols());
    ui.horizontal(|ui| {
        let (mut a, mut c) = (along, across);
        ui.add(
            egui::DragValue::new(&mut a)
                .range(2..=8)
                .prefix("along s: "),
        )
        .on_hover_text("How many control values along each streamline (resets the values to 1)");
        ui.add(
            egui::DragValue::new(&mut c)
                .range(2..=6)
                .prefix("across t: "),
        )
        .on_hover_text("How many control values across the streamlines (resets the values to 1)");
        if (a, c) != (along, across) {
            p.send(Edit::SetTuning(Some(identity(a, c, t.constraint))));
        }
        if ui
            .button("Reset")
            .on_hover_text("All values back to 1: the surface as it is without fine tuning")
            .clicked()
        {
            p.send(Edit::SetTuning(Some(identity(along, across, t.constraint))));
        }
    });
    ui.label(
        egui::RichText::new(format!(
            "degree {} along, {} across",
            t.function.degree_s(),
            t.function.degree_t()
        ))
        .weak(),
    )
    .on_hover_text(
        "Quadratic B-splines where there are at least 3 values (paper 003 uses 3×3 and 3×4)",
    );
    egui::Grid::new("tuning_values")
        .spacing([4.0, 4.0])
        .show(ui, |ui| {
            ui.label("");
            for col in 0..along {
                ui.label(egui::RichText::new(format!("s{col}")).weak())
                    .on_hover_text(format!("Control value {col} along the streamlines (from their start)"));
            }
            ui.end_row();
            for row in 0..across {
                ui.label(egui::RichText::new(format!("t{row}")).weak())
                    .on_hover_text(format!("Control value {row} across the streamlines (first row of streamlines = t0)"));
                for col in 0..along {
                    let mut v = values.get(row, col);
                    ui.spacing_mut().slider_width = 56.0;
                    let r = ui
                        .add(
                            egui::Slider::new(&mut v, 0.0..=VALUE_MAX)
                                .vertical()
                                .max_decimals(2)
                                .step_by(0.01),
                        )
                        .on_hover_text(format!(
                            "α control value ({row}, {col}): above 1 the streamlines run longer there (they turn later), below 1 shorter; drag, or click the number to type"
                        ));
                    if r.changed() && v != values.get(row, col) {
                        let g = p.slider_group("tuning", &r);
                        p.send_grouped(Edit::SetTuningValue { row, col, value: v }, g);
                    }
                }
                ui.end_row();
            }
        });
    let mut c = t.constraint;
    ui.horizontal(|ui| {
        ui.radio_value(&mut c, Constraint::Free, "free")
            .on_hover_text("Streamlines change freely from where they meet the initial curve");
        ui.radio_value(&mut c, Constraint::KeepEnds, "keep ends")
            .on_hover_text("Both ends of every streamline stay put: the values each streamline uses change as little as possible (least squares) to keep them");
        ui.radio_value(&mut c, Constraint::KeepClosed, "keep closed")
            .on_hover_text("The chord from each streamline's start to its end is kept, so a closed streamline stays closed");
    });
    if c != t.constraint {
        p.send(Edit::SetTuningConstraint(c));
    }
    plot(ui, p, &t);
}

/// `α` along one streamline, `v` from the selected handle's row (or the middle).
fn plot(ui: &mut egui::Ui, p: &PanelCtx, t: &SurfaceTuning) {
    let rows = p.patch.design().net().rows();
    let v = match p.selection.cell() {
        Some((row, _)) if p.handles.edit_depth() == 0 => {
            let ts = &p.patch.design().params().t;
            let (lo, hi) = ts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            SurfaceTuning::row_v(ts[row.min(ts.len() - 1)], lo, hi)
        }
        Some((row, _)) => {
            let last = p.handles.shape().0.saturating_sub(1).max(1);
            row as f64 / last as f64
        }
        None => 0.5,
    };
    let f = t.row_function(v);
    let which = match p.selection.cell() {
        Some((row, _)) => format!("streamline of row {row} (v = {v:.2})"),
        None => format!("middle streamline (v = {v:.2}); select an arrow for its row"),
    };
    ui.label(egui::RichText::new(format!("α along the {which}")).weak())
        .on_hover_text(format!(
            "The designer's function on this streamline, before the constraint; {rows} control rows"
        ));
    let size = egui::vec2(ui.available_width().min(300.0), 110.0);
    let (rect, resp) = ui.allocate_exact_size(size, egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 4.0, egui::Color32::from_gray(28));
    let ymax = f.values().iter().fold(1.5f64, |a, &x| a.max(x)).max(1.5) * 1.1;
    let to_screen = |u: f64, a: f64| {
        egui::pos2(
            rect.left() + 8.0 + (rect.width() - 16.0) * u as f32,
            rect.bottom() - 8.0 - (rect.height() - 16.0) * (a / ymax) as f32,
        )
    };
    // α = 1: nothing changes
    painter.line_segment(
        [to_screen(0.0, 1.0), to_screen(1.0, 1.0)],
        egui::Stroke::new(1.0, egui::Color32::from_gray(90)),
    );
    painter.line_segment(
        [to_screen(0.0, 0.0), to_screen(1.0, 0.0)],
        egui::Stroke::new(1.0, egui::Color32::from_gray(60)),
    );
    let curve: Vec<egui::Pos2> = (0..=100)
        .map(|i| {
            let u = i as f64 / 100.0;
            to_screen(u, f.eval(u))
        })
        .collect();
    painter.add(egui::Shape::line(
        curve,
        egui::Stroke::new(2.0, egui::Color32::from_rgb(255, 200, 60)),
    ));
    // control values at their Greville abscissae (the mean of p interior knots)
    let k = f.knots();
    let deg = f.degree();
    for (i, &c) in f.values().iter().enumerate() {
        let g = if deg == 0 {
            0.5 * (k[i] + k[i + 1])
        } else {
            k[i + 1..=i + deg].iter().sum::<f64>() / deg as f64
        };
        painter.circle_filled(to_screen(g, c), 3.5, egui::Color32::from_rgb(230, 70, 60));
    }
    painter.text(
        rect.left_top() + egui::vec2(6.0, 4.0),
        egui::Align2::LEFT_TOP,
        format!("α ≤ {:.2}", ymax / 1.1),
        egui::FontId::proportional(11.0),
        egui::Color32::from_gray(160),
    );
    resp.on_hover_text("α(s) along the streamline (yellow), its control values (red), and α = 1 (grey): where α > 1 the streamline is stretched");
}
