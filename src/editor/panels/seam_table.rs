//! The Analysis section's seam table (docs/math.md §11.3), as Alias's
//! continuity check reports: for each join, the two patches, the edge, the
//! continuity built (in its verdict's colour, the seam's colour in the
//! view), the largest gap, the largest normal angle and the curvature
//! deviation largest in size, measured at the display depth.

use crate::editor::seams::verdict::{ANGLE_MEETS_DEG, CURVATURE_MEETS, GAP_MEETS};
use crate::editor::seams::{SeamLine, Seams};
use bevy_egui::egui;

/// A figure in three significant digits (e-notation when small or large).
pub fn figure(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if (1e-2..1e4).contains(&v.abs()) {
        format!("{v:.3}")
    } else {
        format!("{v:.2e}")
    }
}

/// The table's cells of one seam, as shown (`—` where not measured).
pub fn cells(s: &SeamLine) -> [String; 7] {
    let (gap, angle, dev) = match &s.report {
        Some(r) => (
            figure(r.gap),
            format!("{}°", figure(r.angle_deg)),
            figure(r.curvature_dev),
        ),
        None => ("—".into(), "—".into(), "—".into()),
    };
    [
        s.a_name.clone(),
        s.b_name.clone(),
        s.edge.name().to_string(),
        s.continuity.name().to_string(),
        gap,
        angle,
        dev,
    ]
}

pub fn show(ui: &mut egui::Ui, seams: &Seams) {
    ui.separator();
    ui.strong("Seams").on_hover_text(
        "Each join measured on the meshes at the display depth (docs/math.md §11.3): \
         the largest gap, the largest angle between the normals, and the curvature \
         deviation (κA − κB)/(|κA| + |κB|) across the seam",
    );
    if seams.lines.is_empty() {
        ui.label(egui::RichText::new("one patch: no seams").weak());
        return;
    }
    egui::Grid::new("seam_table")
        .striped(true)
        .spacing([8.0, 2.0])
        .show(ui, |ui| {
            for h in ["A", "B", "edge", "cont.", "gap", "angle", "κ dev"] {
                ui.label(egui::RichText::new(h).strong());
            }
            ui.end_row();
            for s in &seams.lines {
                let c = cells(s);
                let [r, g, b] = s.verdict.color();
                for (i, text) in c.iter().enumerate() {
                    if i == 3 {
                        ui.label(
                            egui::RichText::new(text)
                                .strong()
                                .color(egui::Color32::from_rgb(r, g, b)),
                        )
                        .on_hover_text(format!(
                            "{} {}: gap ≤ {GAP_MEETS:e} × the scene's size{}{}",
                            s.continuity.name(),
                            s.verdict.name(),
                            if s.continuity.name() != "G0" {
                                format!(", angle ≤ {ANGLE_MEETS_DEG}°")
                            } else {
                                String::new()
                            },
                            if s.continuity.name() == "G2" {
                                format!(", |κ dev| ≤ {CURVATURE_MEETS}")
                            } else {
                                String::new()
                            },
                        ));
                    } else {
                        ui.label(text);
                    }
                }
                ui.end_row();
            }
        });
    ui.label(egui::RichText::new("green: meets its continuity · amber: near · red: fails").weak());
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::editor::seams::Verdict;
    use streamline_kernel::joins::{Continuity, Edge, SeamReport};

    #[test]
    fn cells_show_the_report_or_dashes() {
        let mut s = SeamLine {
            a_name: "hood".into(),
            b_name: "wing".into(),
            edge: Edge::Last,
            continuity: Continuity::G1,
            points: Vec::new(),
            report: None,
            verdict: Verdict::Unmeasured,
            hidden: false,
        };
        assert_eq!(cells(&s)[4..], ["—", "—", "—"]);
        s.report = Some(SeamReport {
            gap: 0.0,
            angle_deg: 0.1234,
            curvature_dev: -3.5e-5,
            samples: Vec::new(),
        });
        assert_eq!(
            cells(&s),
            ["hood", "wing", "Last", "G1", "0", "0.123°", "-3.50e-5"].map(String::from)
        );
    }
}
