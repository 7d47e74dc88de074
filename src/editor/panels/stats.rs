//! Stats: sizes, and what the last edit cost stage by stage.

use super::PanelCtx;
use bevy_egui::egui;

pub fn show(ui: &mut egui::Ui, p: &PanelCtx) {
    let net = &p.model.scene.design.net;
    let s = &p.stats;
    let grid = |ui: &mut egui::Ui| {
        let mut row = |k: &str, v: String, tip: &str| {
            ui.label(k).on_hover_text(tip);
            ui.label(v).on_hover_text(tip);
            ui.end_row();
        };
        row(
            "control net",
            format!("{} × {}", net.cols(), net.rows()),
            "Control tangents along × across the streamlines",
        );
        let finest = s
            .levels
            .last()
            .map(|(r, c)| format!("{c} × {r} (level {})", s.levels.len() - 1));
        row(
            "finest level",
            finest.unwrap_or_default(),
            "Tangents along × across at the deepest level built",
        );
        row(
            "tangents",
            s.tangents_total.to_string(),
            "Tangents in all levels",
        );
        row(
            "streamlines",
            s.streamlines.to_string(),
            "Streamlines at the display depth",
        );
        let l = &s.last;
        let mut edit: String = l.edit.chars().take(26).collect();
        if edit.len() < l.edit.len() {
            edit.push('…');
        }
        row(
            "last edit",
            edit,
            "The edit (or edits) of the last frame that had one",
        );
        row(
            "rebuild",
            if l.full_rebuild {
                "full".into()
            } else {
                "incremental".into()
            },
            "Full: the shape of the levels changed; incremental: only dirty windows",
        );
        row(
            "re-blended",
            l.tangents_reblended.to_string(),
            "Tangents blended again over all levels",
        );
        row(
            "details",
            l.details_reapplied.to_string(),
            "Multiresolution details applied again",
        );
        row(
            "re-integrated",
            l.streamlines_reintegrated.to_string(),
            "Streamlines integrated again (Eq. 65)",
        );
        row(
            "mesh rows",
            l.mesh_rows.to_string(),
            "Rows of the mesh rewritten",
        );
        row(
            "µs edit",
            format!("{:.0}", l.us_edit),
            "Applying the edit messages",
        );
        row(
            "µs blend",
            format!("{:.0}", l.us_blend),
            "Blending dirty windows on the sphere",
        );
        row(
            "µs integrate",
            format!("{:.0}", l.us_integrate),
            "Integrating changed streamlines",
        );
        row(
            "µs mesh",
            format!("{:.0}", l.us_mesh),
            "Rewriting mesh rows and normals",
        );
        row(
            "frame (ms)",
            format!("{:.2} (max {:.2})", p.timing.last_ms, p.timing.max_ms),
            "CPU time of the model's systems in the last frame with an edit, and the largest of the last 120",
        );
        row(
            "our systems (ms)",
            format!(
                "{:.2} (max {:.2})",
                p.timing.ours_last_ms, p.timing.ours_max_ms
            ),
            "CPU time (thread CPU clocks, so time lost to other programs is not counted) of all our systems — the model's stages and the editor's: mesh upload, arrows, sphere view, analysis, panels — in the last frame with an edit, summed over threads, and the largest of the last 120",
        );
    };
    egui::Grid::new("stats_grid")
        .num_columns(2)
        .striped(true)
        .show(ui, grid);
}
