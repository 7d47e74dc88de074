//! Analysis: curvature comb, Gaussian and mean curvature maps (with legend and
//! range), zebra stripes, the deviation map (with its fit's figures), the
//! map to the reference (with its largest and mean distance), and the seams of a design of several patches (`seam_table`).

use crate::editor::surface::analysis_display::{AnalysisSettings, CurvatureField, SurfaceMode};
use crate::editor::surface::colour_maps::diverging;
use crate::editor::surface::deviation::{BANDS, DeviationField, FRAME_BUDGET_S};
use crate::editor::surface::reference_map::{LIVE_POINTS, ReferenceField, TOLERANCE_SHARE};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;

/// What only the Analysis section touches.
#[derive(SystemParam)]
pub struct AnalysisSection<'w> {
    pub settings: ResMut<'w, AnalysisSettings>,
    pub field: Res<'w, CurvatureField>,
    pub deviation: Res<'w, DeviationField>,
    pub reference: Res<'w, ReferenceField>,
    pub seams: Res<'w, crate::editor::seams::Seams>,
}

pub fn show(ui: &mut egui::Ui, p: &mut AnalysisSection) {
    // the widgets edit a copy; the settings are written only when it differs
    let mut a = p.settings.clone();
    widgets(ui, &mut a, &p.field, &p.deviation, &p.reference);
    p.settings.set_if_neq(a);
    super::seam_table::show(ui, &p.seams);
}

fn widgets(
    ui: &mut egui::Ui,
    a: &mut AnalysisSettings,
    field: &CurvatureField,
    deviation: &DeviationField,
    reference: &ReferenceField,
) {
    ui.horizontal_wrapped(|ui| {
        for (m, tip) in [
            (SurfaceMode::Shaded, "Lit surface"),
            (SurfaceMode::Gaussian, "Gaussian curvature K = κ₁κ₂ as colours: blue < 0 (saddle), white 0, red > 0 (dome)"),
            (SurfaceMode::Mean, "Mean curvature H = (κ₁+κ₂)/2 as colours, signed about the surface normal"),
            (SurfaceMode::Zebra, "Reflection lines of horizontal light stripes: smooth stripes mean a fair surface"),
            (SurfaceMode::Deviation, "Distance to the B-spline surface that STEP and IGES export (tolerance from File > CAD export): green within it, yellow up to twice it, red beyond"),
        ] {
            ui.radio_value(&mut a.mode, m, m.name()).on_hover_text(tip);
        }
        reference_radio(ui, a, reference.has_reference);
    });
    match a.mode {
        SurfaceMode::Gaussian | SurfaceMode::Mean => {
            ui.checkbox(&mut a.auto_range, "automatic range")
                .on_hover_text("Colour range from the data: the 98th percentile of |value|, so border spikes do not wash it out");
            if a.auto_range {
                a.limit = field.limit;
            } else {
                ui.add(
                    egui::Slider::new(&mut a.limit, 1e-4..=1e3)
                        .logarithmic(true)
                        .text("limit"),
                )
                .on_hover_text("Values beyond ±limit get the end colours");
            }
            legend(ui, field.limit);
            let (lo, hi) = if a.mode == SurfaceMode::Gaussian {
                field.gaussian_range
            } else {
                field.mean_range
            };
            ui.label(format!("data range: {lo:.4e} … {hi:.4e}"))
                .on_hover_text("The smallest and largest value over the surface");
            ui.label(egui::RichText::new(format!("computed in {:.0} µs", field.us)).weak())
                .on_hover_text("Kernel time for K and H at every vertex");
        }
        SurfaceMode::Zebra => {
            ui.add(egui::Slider::new(&mut a.stripes, 4.0..=64.0).text("stripes"))
                .on_hover_text("Number of light stripes over the half circle of directions");
        }
        SurfaceMode::Deviation => deviation_legend(ui, deviation),
        SurfaceMode::Reference => reference_legend(ui, reference),
        SurfaceMode::Shaded => {}
    }
    ui.separator();
    ui.checkbox(&mut a.comb, "curvature comb").on_hover_text(
        "Teeth along streamlines, normal to them, as long as the curvature κ = |dT/ds|",
    );
    ui.add_enabled(
        a.comb,
        egui::Slider::new(&mut a.comb_scale, 0.1..=10.0)
            .logarithmic(true)
            .text("comb scale"),
    )
    .on_hover_text("Tooth length factor: at 1 the longest tooth is a tenth of the scene");
    ui.add_enabled(
        a.comb,
        egui::Slider::new(&mut a.comb_lines, 1..=64).text("combed streamlines"),
    )
    .on_hover_text("Streamlines that get a comb, spread evenly");
}

/// The colour map from −limit to +limit.
fn legend(ui: &mut egui::Ui, limit: f64) {
    let (rect, _) = ui.allocate_exact_size(
        egui::vec2(ui.available_width().min(240.0), 14.0),
        egui::Sense::hover(),
    );
    let painter = ui.painter_at(rect);
    let n = 64;
    for i in 0..n {
        let u = i as f64 / (n - 1) as f64;
        let [r, g, b] = diverging(u);
        let x0 = rect.left() + rect.width() * i as f32 / n as f32;
        let x1 = rect.left() + rect.width() * (i + 1) as f32 / n as f32;
        painter.rect_filled(
            egui::Rect::from_min_max(
                egui::pos2(x0, rect.top()),
                egui::pos2(x1 + 0.5, rect.bottom()),
            ),
            0.0,
            egui::Color32::from_rgb(r, g, b),
        );
    }
    let (labels, _) = ui.allocate_exact_size(egui::vec2(rect.width(), 14.0), egui::Sense::hover());
    let font = egui::FontId::proportional(11.0);
    let colour = ui.visuals().text_color();
    for (x, align, text) in [
        (
            labels.left(),
            egui::Align2::LEFT_TOP,
            format!("−{}", short(limit)),
        ),
        (labels.center().x, egui::Align2::CENTER_TOP, "0".to_string()),
        (
            labels.right(),
            egui::Align2::RIGHT_TOP,
            format!("+{}", short(limit)),
        ),
    ] {
        ui.painter().text(
            egui::pos2(x, labels.top()),
            align,
            text,
            font.clone(),
            colour,
        );
    }
}

/// A number in three significant digits, plain or in e-notation.
fn short(v: f64) -> String {
    if (1e-2..1e4).contains(&v.abs()) {
        format!("{v:.3}")
    } else {
        format!("{v:.2e}")
    }
}

/// The faces of a design of several patches (one STEP shell, seams held):
/// each patch's tolerance (a share of its own size), largest and mean
/// deviation one depth finer, and poles; and, when the shell had to be
/// sampled deeper than shown, that depth.
fn faces_table(ui: &mut egui::Ui, d: &DeviationField) {
    ui.label("faces of the STEP shell (checked one depth finer):")
        .on_hover_text("Each patch against its own face of the one shell the STEP export writes, its seams shared with its neighbours' faces; a face's tolerance is that share of its own size");
    egui::Grid::new("deviation_faces")
        .striped(true)
        .show(ui, |ui| {
            for h in ["patch", "tolerance", "largest", "mean", "poles"] {
                ui.label(egui::RichText::new(h).strong());
            }
            ui.end_row();
            for f in &d.faces {
                ui.label(&f.name);
                ui.label(short(f.tolerance));
                ui.label(short(f.max));
                ui.label(short(f.mean));
                ui.label(format!("{} × {}", f.poles.0, f.poles.1));
                ui.end_row();
            }
        });
    if let Some(f) = &d.first_alone {
        ui.label(format!(
            "{} is shown over both halves (mirrored): coloured against its one-patch fit, tolerance {}, largest {}, {} × {} poles",
            f.name,
            short(f.tolerance),
            short(f.max),
            f.poles.0,
            f.poles.1
        ))
        .on_hover_text("A mirrored design shows its first patch as one surface over both halves, which is what the one-patch export fits; the shell has a face for each half");
    }
    if let Some(depth) = d.deeper {
        ui.colored_label(
            egui::Color32::from_rgb(200, 150, 40),
            format!(
                "sampled at depth {depth}, which the tolerance needs: the map measures the points shown against it"
            ),
        );
    }
}

/// The deviation map's bands and its fit's figures.
fn deviation_legend(ui: &mut egui::Ui, d: &DeviationField) {
    if let Some(e) = &d.error {
        ui.colored_label(egui::Color32::from_rgb(210, 60, 50), format!("no fit: {e}"));
        return;
    }
    // several faces: each patch against its own face's tolerance
    let bands = if d.faces.is_empty() {
        [
            format!("≤ {} (the tolerance)", short(d.tolerance)),
            format!("≤ {}", short(2.0 * d.tolerance)),
            format!("> {}", short(2.0 * d.tolerance)),
        ]
    } else {
        [
            "≤ its face's tolerance".to_string(),
            "≤ twice it".to_string(),
            "beyond".to_string(),
        ]
    };
    for (c, text) in BANDS.into_iter().zip(bands) {
        ui.horizontal(|ui| {
            let (rect, _) = ui.allocate_exact_size(egui::vec2(14.0, 14.0), egui::Sense::hover());
            ui.painter()
                .rect_filled(rect, 2.0, egui::Color32::from_rgb(c[0], c[1], c[2]));
            ui.label(text);
        });
    }
    if d.faces.is_empty() {
        ui.label(format!(
            "largest {}, mean {} (checked one depth finer)",
            short(d.max),
            short(d.mean)
        ));
        ui.label(format!(
            "poles {} × {}, degree from File > CAD export",
            d.poles.0, d.poles.1
        ));
    } else {
        faces_table(ui, d);
    }
    let when = if d.live() {
        format!(
            "refits on each edit ({:.1} ms, within the {:.1} ms frame)",
            d.seconds * 1e3,
            FRAME_BUDGET_S * 1e3
        )
    } else {
        format!(
            "refits when the drag ends ({:.1} ms, over the {:.1} ms frame)",
            d.seconds * 1e3,
            FRAME_BUDGET_S * 1e3
        )
    };
    ui.label(egui::RichText::new(when).weak())
        .on_hover_text("The fit at the display depth, timed; under a frame it follows the mouse");
}

/// The "to reference" choice: enabled only when the design has a reference.
pub(super) fn reference_radio(ui: &mut egui::Ui, a: &mut AnalysisSettings, has: bool) {
    let r = ui.add_enabled(
        has,
        egui::RadioButton::new(a.mode == SurfaceMode::Reference, "to reference"),
    );
    let r = if has {
        r.on_hover_text("Distance of each shown point of the first patch to the reference the design was fitted to: green at 0, red at the tolerance and beyond")
    } else {
        r.on_disabled_hover_text("no reference: File ▸ Import surface…")
    };
    if r.clicked() {
        a.mode = SurfaceMode::Reference;
    }
}

/// The map to the reference: its ramp, tolerance, largest and mean distance.
fn reference_legend(ui: &mut egui::Ui, r: &ReferenceField) {
    if !r.has_reference {
        ui.label("no reference: File ▸ Import surface…");
        return;
    }
    if let Some(e) = &r.error {
        ui.colored_label(
            egui::Color32::from_rgb(210, 60, 50),
            format!("reference not read: {e}"),
        );
        return;
    }
    let (rect, _) = ui.allocate_exact_size(
        egui::vec2(ui.available_width().min(240.0), 14.0),
        egui::Sense::hover(),
    );
    let painter = ui.painter_at(rect);
    let n = 64;
    for i in 0..n {
        let [cr, cg, cb] =
            crate::editor::surface::colour_maps::reference_ramp(i as f64 / (n - 1) as f64);
        let x0 = rect.left() + rect.width() * i as f32 / n as f32;
        let x1 = rect.left() + rect.width() * (i + 1) as f32 / n as f32;
        painter.rect_filled(
            egui::Rect::from_min_max(
                egui::pos2(x0, rect.top()),
                egui::pos2(x1 + 0.5, rect.bottom()),
            ),
            0.0,
            egui::Color32::from_rgb(cr, cg, cb),
        );
    }
    ui.label(format!("0 … ≥ {} (the tolerance)", short(r.tolerance)))
        .on_hover_text(format!(
            "{TOLERANCE_SHARE:e} of the reference face's bounding-box diagonal"
        ));
    if r.values.is_some() {
        ui.label(format!(
            "largest {}, mean {}",
            short(r.distances.max),
            short(r.distances.mean)
        ));
        ui.label(
            egui::RichText::new(format!(
                "measured in {:.1} ms ({} points; live during a drag that moves up to {LIVE_POINTS} points, else when it ends)",
                r.seconds * 1e3,
                r.measured
            ))
            .weak(),
        );
    }
}
