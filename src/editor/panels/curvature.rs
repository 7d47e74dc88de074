//! Curvature: for the selected streamline, its curvature `κ` over arc length
//! `s` and its logarithmic curvature graph (Miura's aesthetic curves:
//! `log(ρ |ds/dρ|)` against `log ρ`, `ρ = 1/κ`), with the fitted slope `α`
//! and the fit's RMS residual (`docs/math.md §9`). The numbers are the
//! kernel's ([`streamline_kernel::aesthetic`]); the plots are egui_plot's
//! (hover values, zoom, pan). Both follow a drag, since they are drawn from
//! the display depth's level each frame the section is open.

use super::PanelCtx;
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::joined::{ActivePatch, PatchStart, PatchSurface, shows_run_cut};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;
use egui_plot::{Line, Plot, PlotPoints, Points};
use streamline_kernel::DVec3;
use streamline_kernel::aesthetic::{LogCurvatureGraph, curvature_profile, log_curvature_graph};

/// The levels the plots read: the first patch's pipeline, or the active
/// patch's built stack (a joined patch's, or the first patch's cut of the
/// G2 run it heads, which is what is drawn).
#[derive(SystemParam)]
pub struct CurvatureSection<'w, 's> {
    levels: Query<'w, 's, (&'static SubdivisionLevel, &'static LevelData)>,
    active: Res<'w, ActivePatch>,
    surfaces: Query<'w, 's, &'static PatchSurface>,
    starts: Query<'w, 's, &'static PatchStart>,
}

impl CurvatureSection<'_, '_> {
    /// Of the active patch (`first` when none is), the number of rows at
    /// depth `edit` and row `row`'s tangents and `s` at depth `depth`
    /// (`row` given the rows at `edit` and at `depth`, [`display_row`]).
    fn row(
        &self,
        first: Entity,
        (edit, depth): (u32, u32),
        row: usize,
    ) -> Option<(usize, &[DVec3], &[f64])> {
        let of = self.active.0.unwrap_or(first);
        let surface = self.surfaces.get(of).ok();
        if of == first && !shows_run_cut(first, self.starts.iter(), surface) {
            let level = |d: u32| self.levels.iter().find(|(l, _)| l.0 == d).map(|(_, d)| d);
            let (e, d) = (level(edit)?, level(depth)?);
            let row = display_row(row, e.0.shape().0, d.0.shape().0);
            let (t, s) = d.row(row);
            return Some((row, t, s));
        }
        let levels = &surface?.stack()?.levels;
        let (e, d) = (levels.get(edit as usize)?, levels.get(depth as usize)?);
        let row = display_row(row, e.tangents.rows(), d.tangents.rows());
        Some((row, d.tangents.row(row), d.params.s.row(row)))
    }
}

/// The streamline of the display depth that corresponds to row `row` of the
/// edit depth (`rows_edit` rows): the same fraction of the way across.
pub fn display_row(row: usize, rows_edit: usize, rows_display: usize) -> usize {
    if rows_edit < 2 || rows_display < 2 {
        return row.min(rows_display.saturating_sub(1));
    }
    let f = row as f64 / (rows_edit - 1) as f64;
    ((f * (rows_display - 1) as f64).round() as usize).min(rows_display - 1)
}

pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx, c: &CurvatureSection) {
    let Some(h) = p.selection.primary().filter(|h| h.is_surface()) else {
        ui.label(
            egui::RichText::new("Select an arrow of the surface: its streamline is plotted here.")
                .weak(),
        );
        return;
    };
    let (edit, depth) = (
        p.patch.structure().edit_depth,
        p.patch.structure().display_depth,
    );
    let Some((row, tangents, s)) = c.row(p.patch.entity(), (edit, depth), h.row) else {
        return;
    };
    let profile = curvature_profile(tangents, s);
    ui.label(format!(
        "streamline {row} of depth {depth} ({} samples)",
        profile.s.len()
    ))
    .on_hover_text("The display depth's streamline through the selected arrow's row");
    let kappa: Vec<[f64; 2]> = profile
        .s
        .iter()
        .zip(&profile.kappa)
        .map(|(&s, &k)| [s, k])
        .collect();
    Plot::new("curvature_profile")
        .height(130.0)
        .x_axis_label("s")
        .y_axis_label("κ")
        .show(ui, |plot| {
            plot.line(Line::new("κ(s)", PlotPoints::from(kappa)).color(egui::Color32::LIGHT_BLUE));
        });
    match log_curvature_graph(&profile) {
        LogCurvatureGraph::Graph {
            points,
            alpha,
            intercept,
            residual,
        } => {
            ui.label(format!("α = {alpha:.3}   residual {residual:.3}"))
                .on_hover_text("Slope of the least-squares line through the graph, and the RMS distance of the points from it: a straight graph (small residual) is a log-aesthetic curve (clothoid α = −1, logarithmic spiral α = 1)");
            let (lo, hi) = points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &(x, _)| {
                    (lo.min(x), hi.max(x))
                });
            let fit = vec![[lo, alpha * lo + intercept], [hi, alpha * hi + intercept]];
            let pts: Vec<[f64; 2]> = points.iter().map(|&(x, y)| [x, y]).collect();
            Plot::new("log_curvature_graph")
                .height(130.0)
                .x_axis_label("log ρ")
                .y_axis_label("log(ρ |ds/dρ|)")
                .show(ui, |plot| {
                    plot.points(
                        Points::new("graph", PlotPoints::from(pts))
                            .radius(2.0)
                            .color(egui::Color32::LIGHT_BLUE),
                    );
                    plot.line(
                        Line::new(format!("fit α = {alpha:.3}"), PlotPoints::from(fit))
                            .color(egui::Color32::from_rgb(255, 200, 60)),
                    );
                });
        }
        LogCurvatureGraph::Circle { kappa } => {
            ui.label(format!(
                "κ is constant ({kappa:.4}): a circle of radius {:.4}; its logarithmic curvature graph is a single point (log ρ = {:.3}), not a line",
                1.0 / kappa,
                (1.0 / kappa).ln()
            ));
        }
        LogCurvatureGraph::Straight => {
            ui.label("κ = 0: a straight line (ρ = ∞), no logarithmic curvature graph");
        }
        LogCurvatureGraph::TooFew => {
            ui.label("Too few samples where ρ changes for a logarithmic curvature graph");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::display_row;

    #[test]
    fn display_rows_keep_the_fraction_across() {
        assert_eq!(display_row(0, 4, 97), 0);
        assert_eq!(display_row(3, 4, 97), 96);
        assert_eq!(display_row(1, 3, 9), 4);
        assert_eq!(display_row(5, 1, 3), 2);
    }
}
