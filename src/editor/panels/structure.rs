//! Structure: the control net's size, inserting and deleting rows
//! (streamlines) and columns at the selected arrow or at an index, and mirror
//! symmetry (`docs/math.md §9`). Every button sends one edit (one undo step).

use super::PanelCtx;
use crate::ecs::Edit;
use crate::ecs::authoring::AuthorEdit;
use crate::editor::handles::structure::{self, KEYS, StructureAction};
use bevy_egui::egui;
use streamline_kernel::authoring::Axis;

/// The index fields, kept between frames in egui's memory.
#[derive(Debug, Default, Clone, Copy)]
struct IndexFields {
    row: usize,
    col: usize,
}

pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let id = egui::Id::new("structure_index_fields");
    let mut fields: IndexFields = ui.data(|d| d.get_temp(id)).unwrap_or_default();
    body(ui, p, &mut fields);
    ui.data_mut(|d| d.insert_temp(id, fields));
}

fn body(ui: &mut egui::Ui, p: &mut PanelCtx, fields: &mut IndexFields) {
    let (rows, cols) = {
        let net = p.patch.design().net();
        (net.rows(), net.cols())
    };
    ui.label(format!("Control net: {rows} rows × {cols} columns"))
        .on_hover_text("Rows are streamlines; columns are the tangents along each (2–64 each)");
    let cell = p.selection.primary().and_then(structure::control_cell);
    match cell {
        Some(cell) => {
            ui.label(format!("At the selected arrow ({}, {}):", cell.0, cell.1));
            egui::Grid::new("structure_actions")
                .num_columns(2)
                .show(ui, |ui| {
                    for pair in StructureAction::ALL.chunks(2) {
                        for &a in pair {
                            let refused = a.refused((rows, cols));
                            if ui
                                .add_enabled(refused.is_none(), egui::Button::new(a.label()))
                                .on_hover_text(format!("Key: {}", a.key()))
                                .on_disabled_hover_text(refused.unwrap_or_default())
                                .clicked()
                            {
                                let (edit, next) = a.edit(cell, (rows, cols));
                                p.send(Edit::Author(edit));
                                p.select_cell(next);
                            }
                        }
                        ui.end_row();
                    }
                });
        }
        None => {
            ui.label(
                egui::RichText::new(if p.handles.edit_depth() > 0 {
                    "Structure edits act on the control net: set the edit depth to 0 and select an arrow"
                } else {
                    "Select an arrow to insert or delete at it, or use an index below"
                })
                .weak(),
            );
        }
    }
    ui.label(
        egui::RichText::new(format!("Keys {KEYS}; or right-click an arrow."))
            .weak()
            .small(),
    );
    ui.separator();
    ui.label("At an index (the new row or column gets it):");
    for (axis, name, n, index) in [
        (Axis::Row, "row", rows, &mut fields.row),
        (Axis::Column, "column", cols, &mut fields.col),
    ] {
        *index = (*index).min(n);
        ui.horizontal(|ui| {
            ui.label(format!("{name:<6}"));
            ui.add(egui::DragValue::new(index).range(0..=n))
                .on_hover_text(format!(
                    "0 inserts before the first {name}, {n} after the last; delete takes 0 to {}",
                    n - 1
                ));
            if ui
                .add_enabled(n < 64, egui::Button::new("Insert"))
                .on_hover_text(format!(
                    "A new {name} at index {}: its tangents and parameters from the surface there",
                    *index
                ))
                .on_disabled_hover_text(format!("64 {name}s is the most a net may have"))
                .clicked()
            {
                p.send(Edit::Author(AuthorEdit::insert(axis, *index)));
            }
            let can_delete = n > 2 && *index < n;
            if ui
                .add_enabled(can_delete, egui::Button::new("Delete"))
                .on_hover_text(format!("Delete {name} {}", *index))
                .on_disabled_hover_text(if n <= 2 {
                    format!("the net keeps at least 2 {name}s")
                } else {
                    format!("there is no {name} {} (0 to {})", *index, n - 1)
                })
                .clicked()
            {
                p.send(Edit::Author(AuthorEdit::delete(axis, *index)));
            }
        });
    }
    ui.separator();
    let mut mirror = p.patch.structure().mirror;
    if ui
        .checkbox(&mut mirror, "Mirror symmetry")
        .on_hover_text(
            "The design becomes one half of a symmetric surface, about the plane through the \
             initial curve's start perpendicular to its first tangent; row 0 is the seam (its \
             tangents are turned into the plane) and the surface is G2 across it. The other half \
             is drawn dimmed and cannot be picked; both are analysed and exported.",
        )
        .changed()
    {
        p.send(Edit::Author(AuthorEdit::SetMirror(mirror)));
    }
    if p.patch.structure().mirror {
        ui.label(
            egui::RichText::new("Mirrored: row 0 is the seam; the dimmed half follows the design.")
                .weak()
                .small(),
        );
    }
}
