//! The egui panels: a menu bar (File, Edit, View, Help), a toolbar (undo,
//! redo, frame) and a side panel of
//! sections (File, Patches, Subdivision, Structure, Selection, Display, Fine tuning, Analysis,
//! Loop mesh, Stats). Panels are thin views: they read resources and send
//! edit messages (or change display settings, only when a value really
//! changes); they never compute geometry. What every section reads is
//! [`PanelCtx`]; what only one section touches is that section's own
//! parameter (`FileSection`, `DisplaySection`, …), defined beside it.

mod analysis_section;
mod cad_export;
mod curvature;
mod display;
mod file;
mod group;
mod initial;
mod lengths;
mod loop_mesh;
mod menu_bar;
mod patch_actions;
mod patches;
mod seam_table;
mod selection;
mod stats;
mod structure;
mod subdivision;
mod tuning;

use super::interaction::{
    Drag, DragGroups, DragKind, FrameRequest, HandleQuery, SceneBounds, Selection, ViewArea,
};
use crate::ecs::{Edit, EditLog, EditMessage, History, Model};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};

/// The side panel's sections.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PanelName {
    /// New, open, save, export, recent files.
    File,
    /// The design's patches: choose, rename, hide, delete, add on an edge.
    Patches,
    /// Scheme, ω, blend order, depths.
    Subdivision,
    /// The net's rows and columns: insert, delete; mirror symmetry.
    Structure,
    /// The selected handle: index, x/y/z, rotate, length, reset.
    Selection,
    /// What is drawn: arrows, labels, streamlines, sphere view.
    Display,
    /// Fine tuning: α(s, t), its constraint and plot.
    Tuning,
    /// Curvature comb, Gaussian and mean maps, zebra stripes.
    Analysis,
    /// Loop mesh: open an OBJ and interpolate it with a Loop surface.
    Mesh,
    /// Sizes and the cost of the last edit.
    Stats,
    /// The initial curve: order, length, origin, anchor column, its tangents.
    InitialCurve,
    /// The selected streamline's curvature and logarithmic curvature graph.
    Curvature,
}

impl PanelName {
    /// All sections in panel order.
    pub const ALL: [PanelName; 12] = [
        PanelName::File,
        PanelName::Patches,
        PanelName::Subdivision,
        PanelName::Structure,
        PanelName::Selection,
        PanelName::Display,
        PanelName::Tuning,
        PanelName::Analysis,
        PanelName::Mesh,
        PanelName::Stats,
        PanelName::InitialCurve,
        PanelName::Curvature,
    ];

    /// The section's title and command-line name.
    pub fn name(self) -> &'static str {
        match self {
            PanelName::File => "file",
            PanelName::Patches => "patches",
            PanelName::Subdivision => "subdivision",
            PanelName::Structure => "structure",
            PanelName::Selection => "selection",
            PanelName::Display => "display",
            PanelName::Tuning => "tuning",
            PanelName::Analysis => "analysis",
            PanelName::Mesh => "mesh",
            PanelName::Stats => "stats",
            PanelName::InitialCurve => "initial",
            PanelName::Curvature => "curvature",
        }
    }

    fn tooltip(self) -> &'static str {
        match self {
            PanelName::File => "New, open, save, export, recent files",
            PanelName::Patches => {
                "The design's patches: choose the one handle edits act on, rename, hide, delete, \
                 start a new patch on an edge"
            }
            PanelName::Subdivision => "Scheme, ω, blend order, display and edit depth",
            PanelName::Structure => {
                "Insert and delete rows (streamlines) and columns of the control net; mirror symmetry"
            }
            PanelName::Selection => "The selected handle: direction, rotation, length, reset",
            PanelName::Display => "What is drawn in the 3D view and the sphere view",
            PanelName::Tuning => {
                "Fine tuning: scale the derivative along the streamlines by a B-spline function"
            }
            PanelName::Analysis => {
                "Curvature comb, Gaussian and mean curvature maps, zebra stripes"
            }
            PanelName::Mesh => {
                "Open a triangle mesh (OBJ) and make a Loop surface pass through its vertices"
            }
            PanelName::Stats => "Sizes, and what the last edit cost stage by stage",
            PanelName::InitialCurve => {
                "The initial curve: its order, length, origin, the anchor column, its control tangents"
            }
            PanelName::Curvature => {
                "The selected streamline's curvature over arc length and its logarithmic curvature graph"
            }
        }
    }

    fn title(self) -> &'static str {
        match self {
            PanelName::File => "File",
            PanelName::Patches => "Patches",
            PanelName::Subdivision => "Subdivision",
            PanelName::Structure => "Structure",
            PanelName::Selection => "Selection",
            PanelName::Display => "Display",
            PanelName::Tuning => "Fine tuning",
            PanelName::Analysis => "Analysis",
            PanelName::Mesh => "Loop mesh",
            PanelName::Stats => "Stats",
            PanelName::InitialCurve => "Initial curve",
            PanelName::Curvature => "Curvature",
        }
    }

    /// From its name.
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == s)
    }
}

/// Which sections start open; a screenshot may ask for exactly one.
#[derive(Resource, Debug, Clone)]
pub struct UiState {
    /// Sections open at start.
    pub open: Vec<PanelName>,
    /// Force exactly these open (screenshots), every frame.
    pub force: bool,
}

impl Default for UiState {
    fn default() -> Self {
        UiState {
            open: vec![
                PanelName::Subdivision,
                PanelName::Selection,
                PanelName::Stats,
            ],
            force: false,
        }
    }
}

/// What every section reads, and how sections send edits.
#[derive(SystemParam)]
pub struct PanelCtx<'w, 's> {
    pub model: Res<'w, Model>,
    pub patch: crate::ecs::patch::PatchRef<'w, 's>,
    pub handles: HandleQuery<'w, 's>,
    pub selection: ResMut<'w, Selection>,
    pub edits: MessageWriter<'w, EditMessage>,
    pub groups: ResMut<'w, DragGroups>,
    pub slider_groups: ResMut<'w, SliderGroups>,
    pub ui_state: Res<'w, UiState>,
    pub opened: Res<'w, OpenedScene>,
}

/// The toolbar's and the status line's own state.
#[derive(SystemParam)]
pub struct ToolbarSection<'w> {
    pub history: Res<'w, History>,
    pub log: Res<'w, EditLog>,
    pub warnings: Res<'w, crate::ecs::warnings::BuildWarnings>,
    pub drag: Res<'w, Drag>,
    pub frame: ResMut<'w, FrameRequest>,
    pub bounds: Res<'w, SceneBounds>,
}

/// The sections' own parameters.
#[derive(SystemParam)]
pub struct Sections<'w, 's> {
    bar: ToolbarSection<'w>,
    file: file::FileSection<'w>,
    cad: cad_export::CadExportSection<'w>,
    display: display::DisplaySection<'w>,
    analysis: analysis_section::AnalysisSection<'w>,
    mesh: loop_mesh::MeshSection<'w>,
    stats: stats::StatsSection<'w, 's>,
    curvature: curvature::CurvatureSection<'w, 's>,
    patches: patches::PatchesSection<'w, 's>,
    help: ResMut<'w, menu_bar::HelpWindows>,
}

/// The control net as the scene was opened (the Selection panel's reset).
#[derive(Resource, Debug, Default)]
pub struct OpenedScene {
    net: Option<streamline_kernel::Grid<streamline_kernel::DVec3>>,
    seen: u64,
}

/// The undo group of each slider's current drag.
#[derive(Resource, Debug, Default)]
pub struct SliderGroups(std::collections::HashMap<&'static str, u64>);

impl PanelCtx<'_, '_> {
    /// The primary selected handle's arrow, where the framing buttons and
    /// menu entries aim (`None` with nothing selected).
    pub fn selected_arrow(&self) -> Option<super::interaction::Handle> {
        self.selection.primary().and_then(|h| self.handles.find(h))
    }

    /// Sends one edit.
    pub fn send(&mut self, edit: Edit) {
        self.edits.write(EditMessage::from(edit));
    }

    /// The direction control tangent `(row, col)` had when the scene was opened.
    pub fn opened_direction(&self, row: usize, col: usize) -> Option<streamline_kernel::DVec3> {
        let net = self.opened.net.as_ref()?;
        (row < net.rows() && col < net.cols()).then(|| net.get(row, col))
    }

    /// Selects the edit depth's handle at `(row, col)` (nothing is marked
    /// changed when it already is the selection).
    pub fn select_cell(&mut self, cell: (usize, usize)) {
        let id = self.handles.id_at(cell);
        if self.selection.primary() != Some(id) {
            self.selection.select(id);
        }
    }

    /// The undo group for a change of slider `key`: one per drag, a new one
    /// for each click or key press.
    pub fn slider_group(&mut self, key: &'static str, r: &egui::Response) -> u64 {
        let current = self.slider_groups.0.get(key).copied();
        match current {
            Some(g) if r.dragged() && !r.drag_started() => g,
            _ => {
                let g = self.groups.fresh();
                self.slider_groups.0.insert(key, g);
                g
            }
        }
    }

    /// Sends one edit of a group (a slider drag is one undo step).
    pub fn send_grouped(&mut self, edit: Edit, group: u64) {
        self.edits.write(EditMessage {
            edit,
            group: Some(group),
        });
    }
}

pub struct PanelPlugin;

impl Plugin for PanelPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<UiState>()
            .init_resource::<SliderGroups>()
            .init_resource::<OpenedScene>()
            .init_resource::<patches::PatchesForm>()
            .init_resource::<menu_bar::HelpWindows>()
            .add_systems(Update, track_opened.after(crate::ecs::ModelSet::Output))
            .add_systems(Startup, spawn_ui_camera)
            .add_systems(EguiPrimaryContextPass, panel);
    }
}

/// egui draws through its own camera over the whole window, on top of the
/// 3D view and the sphere inset (each of which has a viewport).
fn spawn_ui_camera(mut commands: Commands, mut settings: ResMut<bevy_egui::EguiGlobalSettings>) {
    use bevy::camera::CameraOutputMode;
    use bevy::camera::visibility::RenderLayers;
    use bevy::render::render_resource::BlendState;
    settings.auto_create_primary_context = false;
    commands.spawn((
        bevy_egui::PrimaryEguiContext,
        Camera2d,
        // egui draws after the 3D views and needs no samples of its own
        // (with them, each frame would copy the window into a multisampled
        // texture and back: dear on a software renderer)
        Msaa::Off,
        RenderLayers::none(),
        Camera {
            order: 10,
            output_mode: CameraOutputMode::Write {
                blend_state: Some(BlendState::ALPHA_BLENDING),
                clear_color: ClearColorConfig::None,
            },
            clear_color: ClearColorConfig::Custom(Color::NONE),
            ..default()
        },
    ));
}

fn track_opened(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: crate::ecs::patch::PatchRef,
    log: Res<EditLog>,
    mut o: ResMut<OpenedScene>,
) {
    let _meter = meter.start();
    let opened = log.frame != o.seen
        && log.entries.iter().any(|e| {
            e.as_ref().is_ok_and(|s| {
                s.starts_with("loaded") || s.starts_with("opened") || s.starts_with("recovered")
            })
        });
    if o.net.is_none() || opened {
        o.net = Some(patch.design().net().clone());
    }
    o.seen = log.frame;
}

/// Every character the panels show, in every text style, rasterised into
/// egui's font atlas on the first pass: a glyph seen for the first time is
/// hinted and drawn into the atlas then, and the first frame of the first drag
/// (the "•" of unsaved changes, new figures) paid up to 1.3 ms for it.
fn warm_glyphs(ctx: &egui::Context) {
    const CHARS: &str = " !\"#$%&'()*+,-./0123456789:;<=>?@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_`abcdefghijklmnopqrstuvwxyz{|}~•×µ°⟲⟳…·ωσαΔκπ−±∞⊗§₁₂⁰“”→←↑↓≤≥–—";
    let fonts: Vec<egui::FontId> = ctx.global_style().text_styles.values().cloned().collect();
    ctx.fonts_mut(|f| {
        for font in fonts {
            f.layout_no_wrap(CHARS.to_owned(), font, egui::Color32::WHITE);
        }
    });
}

/// Text that changes with every edit (the Stats figures, the status line),
/// rewritten at most every [`Self::EVERY`]: while dragging, egui would lay
/// out every figure anew each frame (a new text misses its layout cache),
/// which cost a tenth of the frame budget, and figures that change 120
/// times a second cannot be read anyway.
#[derive(Default)]
pub struct Throttled {
    stats: Vec<(&'static str, String, &'static str)>,
    status: String,
    at: Option<std::time::Instant>,
    dragging: bool,
}

impl Throttled {
    const EVERY: std::time::Duration = std::time::Duration::from_millis(200);

    fn refresh(&mut self, p: &PanelCtx, bar: &ToolbarSection, s: &stats::StatsSection) {
        let now = std::time::Instant::now();
        // at once when a drag starts or ends: "turning …" is laid out in the
        // frame of the press (which has no edit to make), and what the drag
        // did replaces it as soon as it is let go
        let dragging = bar.drag.0.is_some();
        let turned = dragging != self.dragging;
        self.dragging = dragging;
        if !turned
            && self
                .at
                .is_some_and(|at| now.duration_since(at) < Self::EVERY)
        {
            return;
        }
        self.at = Some(now);
        self.stats = stats::rows(p, s);
        self.status = match &bar.drag.0 {
            // the same words for the whole drag (its figures are in the
            // Selection section), and the way out
            Some(d) => format!(
                "turning {} {}: release to keep it, Esc to cancel",
                d.handle.name(),
                match d.kind {
                    DragKind::Trackball { .. } => "on the trackball",
                    DragKind::Sphere => "on the sphere",
                }
            ),
            None => status_text(bar),
        };
    }
}

fn panel(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    mut p: PanelCtx,
    mut sections: Sections,
    mut area: ResMut<ViewArea>,
    mut warmed: Local<bool>,
    mut text: Local<Throttled>,
) -> Result {
    let _meter = meter.start();
    text.refresh(&p, &sections.bar, &sections.stats);
    let ctx = contexts.ctx_mut()?.clone();
    if !*warmed {
        warm_glyphs(&ctx);
        *warmed = true;
    }
    let mut root = egui::Ui::new(
        ctx.clone(),
        "viewport".into(),
        egui::UiBuilder::new()
            .layer_id(egui::LayerId::background())
            .max_rect(ctx.viewport_rect()),
    );
    egui::Panel::top("menu_bar").show(&mut root, |ui| menu_bar::show(ui, &mut p, &mut sections));
    egui::Panel::top("toolbar").show(&mut root, |ui| toolbar(ui, &mut p, &mut sections.bar));
    egui::Panel::bottom("status").show(&mut root, |ui| status(ui, &text.status));
    egui::Panel::left("side_panel")
        .resizable(true)
        .default_size(300.0)
        .size_range(280.0..=520.0)
        .show(&mut root, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                for name in PanelName::ALL {
                    let open = p.ui_state.open.contains(&name);
                    let mut header = egui::CollapsingHeader::new(name.title())
                        .id_salt(name.name())
                        .default_open(open);
                    if p.ui_state.force {
                        header = header.open(Some(open));
                    }
                    // a right click on a patch's boundary opens the Patches section
                    if name == PanelName::Patches && sections.patches.request.0.is_some() {
                        header = header.open(Some(true));
                    }
                    let shown = header.show(ui, |ui| match name {
                        PanelName::File => {
                            file::show(ui, &mut p, &mut sections.file);
                            cad_export::show(
                                ui,
                                &mut p,
                                &mut sections.cad,
                                &mut sections.file.files,
                            );
                        }
                        PanelName::Patches => patches::show(ui, &mut p, &mut sections.patches),
                        PanelName::Subdivision => subdivision::show(ui, &mut p),
                        PanelName::Structure => structure::show(ui, &mut p),
                        PanelName::Selection => {
                            group::show(ui, &mut p);
                            lengths::show(ui, &mut p);
                        }
                        PanelName::Display => display::show(ui, &mut sections.display),
                        PanelName::Tuning => tuning::show(ui, &mut p),
                        PanelName::Analysis => analysis_section::show(ui, &mut sections.analysis),
                        PanelName::Mesh => {
                            loop_mesh::show(ui, &mut sections.mesh, &mut sections.file.files)
                        }
                        PanelName::Stats => {
                            stats::show(ui, &text.stats, &sections.stats.warnings.lines)
                        }
                        PanelName::InitialCurve => initial::show(ui, &mut p),
                        PanelName::Curvature => curvature::show(ui, &mut p, &sections.curvature),
                    });
                    shown.header_response.on_hover_text(name.tooltip());
                }
            });
        });
    let r = root.available_rect_before_wrap();
    let rect = Rect::new(r.min.x, r.min.y, r.max.x, r.max.y);
    if area.0 != Some(rect) {
        area.0 = Some(rect);
    }
    Ok(())
}

fn toolbar(ui: &mut egui::Ui, p: &mut PanelCtx, bar: &mut ToolbarSection) {
    ui.horizontal(|ui| {
        ui.strong("Streamline Studio");
        let name = format!(
            "{}{}",
            p.patch.name(),
            if p.model.unsaved { " •" } else { "" }
        );
        ui.label(egui::RichText::new(name).weak())
            .on_hover_text(match &p.model.path {
                Some(path) => format!("{} (• = unsaved changes)", path.display()),
                None => "a built-in scene, not saved to a file yet (• = unsaved changes)".into(),
            });
        ui.separator();
        let undo = bar.history.undo_len();
        let redo = bar.history.redo_len();
        if ui
            .add_enabled(undo > 0, egui::Button::new("⟲ Undo"))
            .on_hover_text(format!("Undo the last edit (Ctrl+Z); {undo} steps"))
            .on_disabled_hover_text("Nothing to undo")
            .clicked()
        {
            p.send(Edit::Undo);
        }
        if ui
            .add_enabled(redo > 0, egui::Button::new("⟳ Redo"))
            .on_hover_text(format!("Redo (Ctrl+Shift+Z or Ctrl+Y); {redo} steps"))
            .on_disabled_hover_text("Nothing to redo")
            .clicked()
        {
            p.send(Edit::Redo);
        }
        ui.separator();
        if ui
            .button("Frame all")
            .on_hover_text("Fit the whole surface in the view (A or Home)")
            .clicked()
        {
            bar.frame.0 = Some(bar.bounds.all());
        }
        let sel = p.selected_arrow();
        if ui
            .add_enabled(sel.is_some(), egui::Button::new("Frame selected"))
            .on_hover_text("Fit the selected handle in the view (F)")
            .on_disabled_hover_text("Select an arrow first")
            .clicked()
            && let Some(a) = sel
        {
            bar.frame.0 = Some(a.framing(bar.bounds.size()));
        }
    });
}

fn status_text(bar: &ToolbarSection) -> String {
    let text = bar
        .log
        .entries
        .iter()
        .map(|e| match e {
            Ok(s) => s.clone(),
            Err(e) => format!("error: {e}"),
        })
        .filter(|s| !s.is_empty())
        .chain(bar.warnings.lines.iter().map(|w| format!("warning: {w}")))
        .collect::<Vec<_>>()
        .join("; ");
    if text.is_empty() {
        "ready".into()
    } else {
        text
    }
}

fn status(ui: &mut egui::Ui, text: &str) {
    ui.horizontal(|ui| {
        // the key hints first, from the right; the status takes what is left,
        // cut short with its whole text on hover (a warning is long)
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            ui.label(
                egui::RichText::new(
                    "left drag: turn an arrow · right drag: orbit · middle drag: pan · wheel: zoom · Esc: cancel",
                )
                .weak(),
            );
            ui.add_space(12.0);
            ui.with_layout(egui::Layout::left_to_right(egui::Align::Center), |ui| {
                ui.add(egui::Label::new(egui::RichText::new(text).weak()).truncate())
                    .on_hover_text(format!("What the last edit did, and the build's warnings:\n{text}"));
            });
        });
    });
}
