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

use crate::ecs::Edit;
use crate::ecs::joined::{ActivePatch, Joined, JoinedDesign, PatchHidden, PatchSlot, PatchStart};
use crate::ecs::patch::PatchKernel;
use crate::scene::format::Finite;
use crate::scene::format_v3::{ContinuitySpec, EdgeSpec};
use crate::scene::patch_edit::PatchEdit;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;
use streamline_kernel::joins::{Continuity, Edge};

/// One patch as the section lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchRow {
    /// Its entity.
    pub entity: Entity,
    /// Its name.
    pub name: String,
    /// Its place in the document.
    pub index: usize,
    /// Where it starts: `None` on its own curve, else `(A's name, edge, continuity)`.
    pub start: Option<(String, Edge, Continuity)>,
    /// Hidden by the designer.
    pub hidden: bool,
    /// Its net's rows (a chain on it must have as many).
    pub rows: usize,
}

impl PatchRow {
    /// "curve", or "on hood End, G2".
    pub fn start_text(&self) -> String {
        match &self.start {
            None => "own curve".into(),
            Some((a, e, c)) => format!("on {a} {}, {}", e.name(), c.name()),
        }
    }
}

/// Why patch `p` cannot be deleted (`None`: it can): the first patch holds
/// the design's own curve, and a patch others start on would leave them
/// on nothing.
pub fn delete_refusal(rows: &[PatchRow], p: &PatchRow) -> Option<String> {
    if p.index == 0 {
        return Some(format!(
            "`{}` is the first patch: every other patch starts on it or after it",
            p.name
        ));
    }
    let on: Vec<&str> = rows
        .iter()
        .filter(|r| r.start.as_ref().is_some_and(|(a, ..)| *a == p.name))
        .map(|r| r.name.as_str())
        .collect();
    (!on.is_empty()).then(|| {
        format!(
            "{} start{} on `{}`: delete {} first",
            on.iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", "),
            if on.len() == 1 { "s" } else { "" },
            p.name,
            if on.len() == 1 { "it" } else { "them" }
        )
    })
}

/// Why a new patch with these settings would be refused before it is sent
/// (`None`: send it); the edit stage checks the rest (docs/math.md §11).
pub fn new_patch_refusal(rows: &[PatchRow], form: &NewPatchForm, a: &PatchRow) -> Option<String> {
    let name = form.name.trim();
    if name.is_empty()
        || name.len() > 32
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        return Some("a name of 1–32 letters, digits, `_` or `-`".into());
    }
    if rows.iter().any(|r| r.name == name) {
        return Some(format!(
            "there is a patch `{name}` already: choose another name"
        ));
    }
    if form.edge != Edge::End && form.continuity == Continuity::G2 {
        return Some("G2 on a side edge is future work: choose G0 or G1, or the End edge".into());
    }
    if form.edge == Edge::End && form.rows != a.rows {
        return Some(format!(
            "a chain has the rows of `{}` ({}): set rows to {}",
            a.name, a.rows, a.rows
        ));
    }
    if form.rows < 2 || form.cols < 2 {
        return Some("a net has at least 2 rows and 2 columns".into());
    }
    if !(form.length.is_finite() && form.length > 0.0) {
        return Some("the length is a positive number".into());
    }
    None
}

/// The "New patch on edge…" form.
#[derive(Debug, Clone, PartialEq)]
pub struct NewPatchForm {
    /// The new patch's name.
    pub name: String,
    /// The edge of the chosen patch it starts on.
    pub edge: Edge,
    /// The continuity across it.
    pub continuity: Continuity,
    /// Its net's rows.
    pub rows: usize,
    /// Its net's columns.
    pub cols: usize,
    /// Its streamlines' length.
    pub length: f64,
}

impl Default for NewPatchForm {
    fn default() -> Self {
        NewPatchForm {
            name: String::new(),
            edge: Edge::End,
            continuity: Continuity::G1,
            rows: 5,
            cols: 4,
            length: 1.0,
        }
    }
}

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

/// What the designer asked for.
#[derive(Debug, Clone, PartialEq)]
pub enum PatchAction {
    /// Make this patch the one handle edits act on.
    Select(String),
    /// Rename `(from, to)`.
    Rename(String, String),
    /// Hide (`true`) or show.
    Hide(String, bool),
    /// Delete.
    Remove(String),
    /// Start a new patch on `from`'s edge.
    Add { from: String, form: NewPatchForm },
}

impl PatchAction {
    /// The edit that carries it out.
    pub fn edit(&self) -> Edit {
        Edit::Patch(match self.clone() {
            PatchAction::Select(n) => PatchEdit::SetPatch(n),
            PatchAction::Rename(a, b) => PatchEdit::RenamePatch(a, b),
            PatchAction::Hide(n, h) => PatchEdit::HidePatch(n, h),
            PatchAction::Remove(n) => PatchEdit::RemovePatch(n),
            PatchAction::Add { from, form } => PatchEdit::AddPatch {
                name: form.name.trim().to_string(),
                from: (from, EdgeSpec::from_kernel(form.edge)),
                continuity: ContinuitySpec::from_kernel(form.continuity),
                rows: form.rows,
                cols: form.cols,
                length: Finite(form.length),
            },
        })
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn rows() -> Vec<PatchRow> {
        let row = |name: &str, index, start: Option<(&str, Edge, Continuity)>| PatchRow {
            entity: Entity::PLACEHOLDER,
            name: name.into(),
            index,
            start: start.map(|(a, e, c)| (a.to_string(), e, c)),
            hidden: false,
            rows: 5,
        };
        vec![
            row("hood", 0, None),
            row("screen", 1, Some(("hood", Edge::End, Continuity::G2))),
            row("wing", 2, Some(("hood", Edge::Last, Continuity::G1))),
            row("tail", 3, Some(("screen", Edge::End, Continuity::G1))),
        ]
    }

    /// A patch others start on, and the first patch, cannot be deleted;
    /// the message names the patches in the way.
    #[test]
    fn deleting_is_refused_while_others_start_on_it() {
        let r = rows();
        let hood = delete_refusal(&r, &r[0]).unwrap();
        assert!(hood.contains("first patch"), "{hood}");
        let screen = delete_refusal(&r, &r[1]).unwrap();
        assert_eq!(screen, "`tail` starts on `screen`: delete it first");
        assert_eq!(delete_refusal(&r, &r[2]), None);
        assert_eq!(delete_refusal(&r, &r[3]), None);
    }

    /// The form refuses what §11 refuses, naming the fix, and lets a good
    /// patch through.
    /// The `PatchEdit` an action sends.
    fn patch_edit(a: PatchAction) -> Option<PatchEdit> {
        match a.edit() {
            Edit::Patch(p) => Some(p),
            other => panic!("not a patch edit: {other:?}"),
        }
    }

    /// Each action is the `PatchEdit` the edit stage applies; a choice is none.
    #[test]
    fn actions_are_patch_edits() {
        assert_eq!(
            patch_edit(PatchAction::Select("wing".into())),
            Some(PatchEdit::SetPatch("wing".into()))
        );
        assert_eq!(
            patch_edit(PatchAction::Hide("wing".into(), true)),
            Some(PatchEdit::HidePatch("wing".into(), true))
        );
        let add = PatchAction::Add {
            from: "hood".into(),
            form: NewPatchForm {
                name: " fin ".into(),
                edge: Edge::Last,
                continuity: Continuity::G1,
                rows: 4,
                cols: 3,
                length: 0.5,
            },
        };
        assert_eq!(
            patch_edit(add),
            Some(PatchEdit::AddPatch {
                name: "fin".into(),
                from: ("hood".into(), EdgeSpec::Last),
                continuity: ContinuitySpec::G1,
                rows: 4,
                cols: 3,
                length: Finite(0.5),
            })
        );
    }

    #[test]
    fn the_new_patch_form_refuses_bad_settings() {
        let r = rows();
        let ok = NewPatchForm {
            name: "fin".into(),
            ..default()
        };
        assert_eq!(new_patch_refusal(&r, &ok, &r[0]), None);
        let bad = |f: NewPatchForm| new_patch_refusal(&r, &f, &r[0]).unwrap();
        assert!(
            bad(NewPatchForm {
                name: "wing".into(),
                ..ok.clone()
            })
            .contains("already")
        );
        assert!(
            bad(NewPatchForm {
                name: "a b".into(),
                ..ok.clone()
            })
            .contains("letters")
        );
        assert!(
            bad(NewPatchForm {
                name: "".into(),
                ..ok.clone()
            })
            .contains("letters")
        );
        let side_g2 = NewPatchForm {
            edge: Edge::First,
            continuity: Continuity::G2,
            ..ok.clone()
        };
        assert!(bad(side_g2).contains("future work"));
        let rows6 = NewPatchForm {
            rows: 6,
            ..ok.clone()
        };
        assert!(bad(rows6.clone()).contains("set rows to 5"));
        // a side join may have other rows
        let side = NewPatchForm {
            edge: Edge::Last,
            ..rows6
        };
        assert_eq!(new_patch_refusal(&r, &side, &r[0]), None);
        assert!(
            bad(NewPatchForm {
                length: f64::NAN,
                ..ok
            })
            .contains("positive")
        );
    }
}
