//! Stats: sizes, and what the last edit cost stage by stage.

use super::PanelCtx;
use crate::ecs::Stats;
use crate::ecs::joined::{ActivePatch, JoinedDesign, PatchSlot, PatchSurface, PatchWork};
use crate::ecs::resources::EditStats;
use crate::ecs::warnings::BuildWarnings;
use crate::editor::view::frame_timing::FrameTiming;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;

/// What only the Stats section reads.
#[derive(SystemParam)]
pub struct StatsSection<'w, 's> {
    pub stats: Res<'w, Stats>,
    /// The world's entities, counted by queries (the census of `build --json`).
    pub census: crate::ecs::census::CensusQuery<'w, 's>,
    pub timing: Res<'w, FrameTiming>,
    pub warnings: Res<'w, BuildWarnings>,
    /// The patch the handles act on (`None`: the first).
    pub active: Res<'w, ActivePatch>,
    /// The joined patches' names, designs and built stacks.
    pub joined: Query<
        'w,
        's,
        (
            &'static PatchSlot,
            &'static JoinedDesign,
            &'static PatchSurface,
        ),
    >,
    /// What each joined patch's last build did.
    pub work: Query<'w, 's, &'static PatchWork>,
}

/// A patch's sizes as Stats shows them.
struct Sizes {
    /// Its net, `(cols, rows)`.
    net: (usize, usize),
    /// Its levels' `(rows, cols)`, depth by depth.
    levels: Vec<(usize, usize)>,
    /// Its name (empty for the first patch).
    name: String,
}

/// The active patch's sizes: a joined patch's from its design and stack,
/// `None` for the first patch (read from its pipeline's [`Stats`]).
fn active_sizes(section: &StatsSection) -> Option<Sizes> {
    let (slot, design, surface) = section.joined.get(section.active.0?).ok()?;
    let net = design.0.net();
    let levels = (surface.stack().into_iter())
        .flat_map(|s| s.levels.iter())
        .map(|l| (l.tangents.rows(), l.tangents.cols()))
        .collect();
    Some(Sizes {
        net: (net.cols(), net.rows()),
        levels,
        name: slot.name.clone(),
    })
}

/// The section's rows: name, figure, tooltip.
pub fn rows(p: &PanelCtx, section: &StatsSection) -> Vec<(&'static str, String, &'static str)> {
    let s = &section.stats;
    // the active patch's sizes (a joined patch's, named), else the first's
    let Sizes { net, levels, name } = active_sizes(section).unwrap_or_else(|| {
        let net = p.patch.design().net();
        Sizes {
            net: (net.cols(), net.rows()),
            levels: s.levels.clone(),
            name: String::new(),
        }
    });
    let mut rows: Vec<(&'static str, String, &'static str)> = Vec::with_capacity(21);
    {
        let mut row = |k: &'static str, v: String, tip: &'static str| rows.push((k, v, tip));
        let of = match name.is_empty() {
            true => String::new(),
            false => format!(" (`{name}`)"),
        };
        row(
            "control net",
            format!("{} × {}{of}", net.0, net.1),
            "Control tangents along × across the streamlines, of the active patch",
        );
        let finest =
            (levels.last()).map(|(r, c)| format!("{c} × {r} (level {})", levels.len() - 1));
        row(
            "finest level",
            finest.unwrap_or_default(),
            "Tangents along × across at the deepest level built, of the active patch",
        );
        row(
            "tangents",
            levels.iter().map(|(r, c)| r * c).sum::<usize>().to_string(),
            "Tangents in all levels, of the active patch",
        );
        // the world's entities, counted by queries (the census of `build --json`)
        let c = section.census.count();
        row(
            "streamlines",
            c.streamlines.to_string(),
            "Streamline entities: one per streamline at the display depth",
        );
        let joined = c.per_patch.iter().filter(|p| p.joined).count();
        row(
            "patches",
            match joined {
                0 => c.patches.to_string(),
                j => format!("{} ({j} joined)", c.patches),
            },
            "Patch entities: each owns its handles, a level entity per depth and a streamline entity per row (a joined patch's values are those its join builds)",
        );
        row(
            "handles",
            format!("{} net, {} curve", c.handles.surface, c.handles.initial),
            "Tangent handle entities: the net's control tangents and the initial curve's",
        );
        row(
            "detail handles",
            c.handles.detail.to_string(),
            "Multiresolution detail entities (one per detail)",
        );
        row(
            "level entities",
            c.levels.to_string(),
            "Subdivision-level entities (0 to the deepest depth shown or edited)",
        );
        let l = &s.last;
        // the active joined patch's last build, as its pipeline's for the first
        let work = section.active.0.and_then(|e| section.work.get(e).ok());
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
            if work.map_or(l.full_rebuild, |w| w.whole) {
                "full".into()
            } else {
                "incremental".into()
            },
            "Full: the shape of the levels changed; incremental: only dirty windows (of the active patch's last build)",
        );
        row(
            "re-blended",
            work.map_or(l.tangents_reblended, |w| w.reblended)
                .to_string(),
            "Tangents blended again over all levels (a G2 run's: of its merged net)",
        );
        let placed = work.map(|w| w.rows.map_or(0, |r| r.hi + 1 - r.lo));
        row(
            "re-integrated",
            placed.unwrap_or(l.streamlines_reintegrated).to_string(),
            "Streamlines integrated again (Eq. 65), of the active patch's last build",
        );
        // the first patch's pipeline counts and times its stages; a joined
        // patch's build is one step, timed with the frame's below
        if work.is_none() {
            pipeline_rows(&mut row, l);
        }
        row(
            "warnings",
            section.warnings.lines.len().to_string(),
            "Antipodal blends in the current build: neighbouring tangents that point in opposite directions (listed below the figures)",
        );
        row(
            "frame (ms)",
            format!(
                "{:.2} (max {:.2})",
                section.timing.last_ms, section.timing.max_ms
            ),
            "CPU time of the model's systems in the last frame with an edit, and the largest of the last 120",
        );
        row(
            "our systems (ms)",
            format!(
                "{:.2} (max {:.2})",
                section.timing.ours_last_ms, section.timing.ours_max_ms
            ),
            "CPU time (thread CPU clocks, so time lost to other programs is not counted) of all our systems — the model's stages and the editor's: mesh upload, arrows, sphere view, analysis, panels — in the last frame with an edit, summed over threads, and the largest of the last 120",
        );
    }
    rows
}

/// What the first patch's pipeline did stage by stage in its last edit.
fn pipeline_rows(row: &mut impl FnMut(&'static str, String, &'static str), l: &EditStats) {
    row(
        "details",
        l.details_reapplied.to_string(),
        "Multiresolution details applied again",
    );
    row(
        "placed again",
        l.streamlines_replaced.to_string(),
        "Streamlines moved rigidly to a changed initial curve or anchor (Eq. 1), no tangent re-blended",
    );
    row(
        "mesh rows",
        l.mesh_rows.to_string(),
        "Rows of the mesh rewritten",
    );
    for (key, us, tip) in [
        ("µs edit", l.us_edit, "Applying the edit messages"),
        (
            "µs blend",
            l.us_blend,
            "Blending dirty windows on the sphere",
        ),
        (
            "µs integrate",
            l.us_integrate,
            "Integrating changed streamlines",
        ),
        ("µs mesh", l.us_mesh, "Rewriting mesh rows and normals"),
    ] {
        row(key, format!("{us:.0}"), tip);
    }
}

/// The section, from [`rows`] (refreshed a few times a second, [`super::Throttled`]),
/// then the build's warnings ([`BuildWarnings`]), one line each.
pub fn show(ui: &mut egui::Ui, rows: &[(&'static str, String, &'static str)], warnings: &[String]) {
    two_columns(ui, rows);
    for w in warnings {
        ui.label(
            egui::RichText::new(format!("warning: {w}"))
                .color(egui::Color32::from_rgb(235, 200, 40)),
        );
    }
}

/// The rows as two labels side by side (names, figures), each row with its
/// own tooltip, chosen by where the pointer is. Two labels instead of a grid
/// of 34: this section is open while dragging, when egui lays out every
/// figure anew each frame, and each widget costs time out of the 4 ms frame
/// budget (docs/editor.md, "Frame cost").
fn two_columns(ui: &mut egui::Ui, rows: &[(&'static str, String, &'static str)]) {
    if rows.is_empty() {
        return;
    }
    let mut names = String::with_capacity(rows.len() * 16);
    let mut figures = String::with_capacity(rows.len() * 16);
    for (i, (k, v, _)) in rows.iter().enumerate() {
        if i > 0 {
            names.push('\n');
            figures.push('\n');
        }
        names.push_str(k);
        figures.push_str(v);
    }
    let row_tip = |ui: &mut egui::Ui, r: &egui::Response| {
        let at = ui
            .ctx()
            .pointer_hover_pos()
            .map_or(0.0, |p| p.y - r.rect.top());
        let i = (at / r.rect.height().max(1.0) * rows.len() as f32).floor();
        let (k, _, tip) = rows[(i.max(0.0) as usize).min(rows.len() - 1)];
        ui.label(egui::RichText::new(k).strong());
        ui.label(tip);
    };
    ui.horizontal_top(|ui| {
        let r = ui.add(egui::Label::new(names).selectable(false));
        r.clone().on_hover_ui(|ui| row_tip(ui, &r));
        ui.add_space(12.0);
        let r = ui.add(egui::Label::new(figures).selectable(false));
        r.clone().on_hover_ui(|ui| row_tip(ui, &r));
    });
}
