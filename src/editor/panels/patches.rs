//! Patches: the patches of a design (docs/math.md §11; docs/editor.md,
//! "Several patches"). Lists each patch (its name, where it starts and
//! with what continuity, hidden or not); choosing one makes it the patch
//! that handle edits act on ([`ActivePatch`]); the chosen patch can be
//! renamed, hidden or deleted, and a new patch started on one of its edges
//! ("New patch on edge…": edge, continuity, net size, length). Everything
//! is sent as an [`Edit::Patch`] ([`PatchAction::edit`]), applied by the
//! edit stage: rename, hide, delete and add are one undo step each;
//! choosing (`SetPatch`) sets [`ActivePatch`] and is not an undo step. The
//! section computes nothing.

use super::patch_actions::*;
use crate::ecs::joined::{ActivePatch, Joined, JoinedDesign, PatchHidden, PatchSlot, PatchStart};
use crate::ecs::patch::PatchKernel;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;
use streamline_kernel::joins::{Continuity, Edge};

/// The section's own state: the rename field and the form.
#[derive(Resource, Debug, Default)]
pub struct PatchesForm {
    /// The rename field, and the patch it was filled for.
    pub rename: (Option<Entity>, String),
    /// The new patch's settings.
    pub new: NewPatchForm,
    /// The form is open.
    pub open: bool,
}

/// What the section reads of each patch.
type PatchItem = (
    Entity,
    &'static PatchSlot,
    &'static PatchStart,
    Has<PatchHidden>,
    Option<&'static JoinedDesign>,
    Option<&'static PatchKernel>,
);

/// What only the Patches section touches.
#[derive(SystemParam)]
pub struct PatchesSection<'w, 's> {
    patches: Query<'w, 's, PatchItem>,
    first: Query<'w, 's, (Entity, &'static PatchKernel), Without<Joined>>,
    pub active: Res<'w, ActivePatch>,
    pub form: ResMut<'w, PatchesForm>,
    /// A right click on a patch's boundary (`seams::boundary`).
    pub request: ResMut<'w, crate::editor::seams::boundary::NewPatchRequest>,
}

impl PatchesSection<'_, '_> {
    /// The patches in the document's order.
    pub fn rows(&self) -> Vec<PatchRow> {
        let mut rows: Vec<PatchRow> = self
            .patches
            .iter()
            .map(|(e, slot, start, hidden, joined, kernel)| {
                let start = match *start {
                    PatchStart::Curve => None,
                    PatchStart::Edge {
                        parent,
                        edge,
                        continuity,
                    } => Some((
                        self.patches
                            .get(parent)
                            .map(|p| p.1.name.clone())
                            .unwrap_or_else(|_| "?".into()),
                        edge,
                        continuity,
                    )),
                };
                let rows = joined
                    .map(|j| j.0.net().rows())
                    .or(kernel.map(|k| k.design.net().rows()))
                    .unwrap_or(0);
                PatchRow {
                    entity: e,
                    name: slot.name.clone(),
                    index: slot.index,
                    start,
                    hidden,
                    rows,
                }
            })
            .collect();
        rows.sort_by_key(|r| r.index);
        rows
    }

    /// The active patch's entity (`ActivePatch(None)` is the first patch).
    pub fn active_entity(&self) -> Option<Entity> {
        self.active
            .0
            .or_else(|| self.first.iter().next().map(|(e, _)| e))
    }
}

/// The section; edits go out through the panels' `ctx`.
pub fn show(ui: &mut egui::Ui, ctx: &mut super::PanelCtx, p: &mut PatchesSection) {
    let rows = p.rows();
    if rows.len() < 2 {
        ui.label(egui::RichText::new("one patch").weak())
            .on_hover_text(
                "A design of several patches lists them here: open one (e.g. \
             scenes/hood-screen-wing.ron) or start a new patch on an edge below",
            );
    }
    let mut active = p.active_entity();
    let mut actions = Vec::new();
    // a right click on a boundary: that patch, its form open on that edge
    if let Some((name, edge)) = p.request.0.take()
        && let Some(r) = rows.iter().find(|r| r.name == name)
    {
        if Some(r.entity) != active {
            actions.push(PatchAction::Select(name));
            active = Some(r.entity);
        }
        p.form.open = true;
        p.form.new.edge = edge;
        if edge != Edge::End && p.form.new.continuity == Continuity::G2 {
            p.form.new.continuity = Continuity::G1;
        }
    }
    egui::Grid::new("patch_list")
        .striped(true)
        .spacing([8.0, 2.0])
        .show(ui, |ui| {
            for r in &rows {
                let chosen = Some(r.entity) == active || (rows.len() < 2);
                if ui
                    .selectable_label(chosen, &r.name)
                    .on_hover_text("Handle edits act on the chosen patch (a click on its surface chooses it too)")
                    .clicked()
                    && !chosen
                {
                    actions.push(PatchAction::Select(r.name.clone()));
                }
                ui.label(egui::RichText::new(r.start_text()).weak());
                let mut hidden = r.hidden;
                if ui
                    .checkbox(&mut hidden, "hidden")
                    .on_hover_text("Hide the patch: its surface, seams and handles are not drawn nor picked")
                    .changed()
                {
                    actions.push(PatchAction::Hide(r.name.clone(), hidden));
                }
                ui.end_row();
            }
        });
    if let Some(a) = rows.iter().find(|r| Some(r.entity) == active) {
        chosen_patch(ui, p, &rows, a, &mut actions);
    }
    for a in actions {
        apply(ctx, a);
    }
}

/// Rename, delete and the new-patch form for the chosen patch `a`.
fn chosen_patch(
    ui: &mut egui::Ui,
    p: &mut PatchesSection,
    rows: &[PatchRow],
    a: &PatchRow,
    actions: &mut Vec<PatchAction>,
) {
    ui.separator();
    if p.form.rename.0 != Some(a.entity) {
        p.form.rename = (Some(a.entity), a.name.clone());
    }
    ui.horizontal(|ui| {
        ui.label("name");
        let r = ui.add(egui::TextEdit::singleline(&mut p.form.rename.1).desired_width(120.0));
        let to = p.form.rename.1.trim().to_string();
        let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if (ui
            .add_enabled(to != a.name && !to.is_empty(), egui::Button::new("Rename"))
            .on_hover_text("Rename the chosen patch (one undo step)")
            .clicked()
            || enter)
            && to != a.name
            && !to.is_empty()
        {
            actions.push(PatchAction::Rename(a.name.clone(), to));
        }
    });
    let refusal = delete_refusal(rows, a);
    let delete = ui.add_enabled(refusal.is_none(), egui::Button::new("Delete patch"));
    let delete = match &refusal {
        Some(why) => delete.on_disabled_hover_text(why),
        None => delete.on_hover_text("Delete the chosen patch (one undo step)"),
    };
    if delete.clicked() {
        actions.push(PatchAction::Remove(a.name.clone()));
    }
    if let Some(why) = &refusal
        && a.index > 0
    {
        ui.label(egui::RichText::new(why).weak());
    }
    let header = egui::CollapsingHeader::new(format!("New patch on an edge of `{}`…", a.name))
        .id_salt("new_patch")
        .open(p.form.open.then_some(true));
    let shown = header.show(ui, |ui| new_patch_form(ui, p, rows, a, actions));
    if shown.header_response.clicked() {
        p.form.open = !p.form.open;
    }
}

fn new_patch_form(
    ui: &mut egui::Ui,
    p: &mut PatchesSection,
    rows: &[PatchRow],
    a: &PatchRow,
    actions: &mut Vec<PatchAction>,
) {
    let f = &mut p.form.new;
    if f.name.is_empty() {
        f.name = (rows.len() + 1..)
            .map(|k| format!("patch{k}"))
            .find(|n| rows.iter().all(|r| r.name != *n))
            .unwrap_or_default();
    }
    egui::Grid::new("new_patch_form")
        .spacing([8.0, 2.0])
        .show(ui, |ui| {
            ui.label("edge");
            ui.horizontal(|ui| {
                for (e, tip) in [
                    (
                        Edge::End,
                        "The curve of the streamlines' last points: a chain",
                    ),
                    (
                        Edge::First,
                        "The first streamline: the new patch leaves it across",
                    ),
                    (
                        Edge::Last,
                        "The last streamline: the new patch leaves it across",
                    ),
                ] {
                    ui.radio_value(&mut f.edge, e, e.name()).on_hover_text(tip);
                }
            });
            ui.end_row();
            ui.label("continuity");
            ui.horizontal(|ui| {
                for (c, tip) in [
                    (Continuity::G0, "Position: the new patch starts on the edge"),
                    (
                        Continuity::G1,
                        "Tangency: the normals agree across the seam",
                    ),
                    (
                        Continuity::G2,
                        "Curvature (End only): the two patches are one net cut at the seam",
                    ),
                ] {
                    ui.radio_value(&mut f.continuity, c, c.name())
                        .on_hover_text(tip);
                }
            });
            ui.end_row();
            if f.edge == Edge::End {
                f.rows = a.rows;
            }
            ui.label("rows");
            ui.add_enabled(
                f.edge != Edge::End,
                egui::DragValue::new(&mut f.rows).range(2..=64),
            )
            .on_disabled_hover_text("A chain has the rows of the patch it continues");
            ui.end_row();
            ui.label("columns");
            ui.add(egui::DragValue::new(&mut f.cols).range(2..=64));
            ui.end_row();
            ui.label("length");
            ui.add(
                egui::DragValue::new(&mut f.length)
                    .range(1e-3..=1e3)
                    .speed(0.01),
            )
            .on_hover_text("The new streamlines' length");
            ui.end_row();
            ui.label("name");
            ui.add(egui::TextEdit::singleline(&mut f.name).desired_width(120.0));
            ui.end_row();
        });
    let refusal = new_patch_refusal(rows, &p.form.new, a);
    let add = ui.add_enabled(refusal.is_none(), egui::Button::new("Add patch"));
    let add = match &refusal {
        Some(why) => add.on_disabled_hover_text(why),
        None => add.on_hover_text("Start the new patch on this edge (one undo step)"),
    };
    if let Some(why) = &refusal {
        ui.label(egui::RichText::new(why).weak());
    }
    if add.clicked() {
        actions.push(PatchAction::Add {
            from: a.name.clone(),
            form: p.form.new.clone(),
        });
        p.form.new.name.clear();
    }
}

/// Sends what the designer asked for (module documentation).
fn apply(ctx: &mut super::PanelCtx, a: PatchAction) {
    ctx.send(a.edit());
}
