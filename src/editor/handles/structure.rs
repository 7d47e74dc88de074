//! Structure edits in the editor (`docs/math.md §9`): inserting a control
//! row (a streamline) or column before or after an arrow, deleting its row or
//! column. The same actions are offered three ways: the Structure section of
//! the panel, a right-click menu on an arrow (a right press and release
//! without moving; a right drag still orbits) and keys on the selected
//! control arrow ([`KEYS`]). Each sends one `Insert`/`Delete` edit: one undo
//! step, and the new row or column is selected. They act on the first
//! patch: while a joined patch is the active one (docs/math.md §11) the
//! menu and the keys are off.

use super::super::interaction::{
    EditorMode, EditorSet, HandleId, HandleKind, HandleLayout, Selection,
};
use crate::ecs::authoring::AuthorEdit;
use crate::ecs::patch::PatchRef;
use crate::ecs::{Edit, EditMessage};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::input::{egui_wants_any_keyboard_input, egui_wants_any_pointer_input};
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use bevy_state::prelude::in_state;
use streamline_kernel::authoring::Axis;

/// One structure action on the control net, relative to a control cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StructureAction {
    /// A new row (streamline) before the cell's row.
    RowBefore,
    /// A new row after the cell's row.
    RowAfter,
    /// A new column before the cell's column.
    ColumnBefore,
    /// A new column after the cell's column.
    ColumnAfter,
    /// Deletes the cell's row.
    DeleteRow,
    /// Deletes the cell's column.
    DeleteColumn,
}

impl StructureAction {
    /// Every action, in menu order.
    pub const ALL: [StructureAction; 6] = [
        StructureAction::RowBefore,
        StructureAction::RowAfter,
        StructureAction::ColumnBefore,
        StructureAction::ColumnAfter,
        StructureAction::DeleteRow,
        StructureAction::DeleteColumn,
    ];

    /// The menu entry.
    pub fn label(self) -> &'static str {
        match self {
            StructureAction::RowBefore => "Insert row before",
            StructureAction::RowAfter => "Insert row after",
            StructureAction::ColumnBefore => "Insert column before",
            StructureAction::ColumnAfter => "Insert column after",
            StructureAction::DeleteRow => "Delete row",
            StructureAction::DeleteColumn => "Delete column",
        }
    }

    /// Its key on the selected control arrow (see [`KEYS`]).
    pub fn key(self) -> &'static str {
        match self {
            StructureAction::RowBefore => "Shift+R",
            StructureAction::RowAfter => "R",
            StructureAction::ColumnBefore => "Shift+C",
            StructureAction::ColumnAfter => "C",
            StructureAction::DeleteRow => "Delete",
            StructureAction::DeleteColumn => "Shift+Delete",
        }
    }

    /// The edit at control cell `(row, col)`, and the cell to select after it
    /// (the new row or column; after a delete, the neighbour that took its
    /// place, clamped to the smaller net).
    pub fn edit(
        self,
        (row, col): (usize, usize),
        shape: (usize, usize),
    ) -> (AuthorEdit, (usize, usize)) {
        let (rows, cols) = shape;
        match self {
            StructureAction::RowBefore => (AuthorEdit::insert(Axis::Row, row), (row, col)),
            StructureAction::RowAfter => (AuthorEdit::insert(Axis::Row, row + 1), (row + 1, col)),
            StructureAction::ColumnBefore => (AuthorEdit::insert(Axis::Column, col), (row, col)),
            StructureAction::ColumnAfter => {
                (AuthorEdit::insert(Axis::Column, col + 1), (row, col + 1))
            }
            StructureAction::DeleteRow => (
                AuthorEdit::delete(Axis::Row, row),
                (row.min(rows.saturating_sub(2)), col),
            ),
            StructureAction::DeleteColumn => (
                AuthorEdit::delete(Axis::Column, col),
                (row, col.min(cols.saturating_sub(2))),
            ),
        }
    }

    /// Why it cannot be done on a net of `shape` (a delete keeps 2 × 2, an
    /// insert stays within 64), or `None`.
    pub fn refused(self, shape: (usize, usize)) -> Option<&'static str> {
        let (rows, cols) = shape;
        match self {
            StructureAction::RowBefore | StructureAction::RowAfter if rows >= 64 => {
                Some("the net has 64 rows, the most it may have")
            }
            StructureAction::ColumnBefore | StructureAction::ColumnAfter if cols >= 64 => {
                Some("the net has 64 columns, the most it may have")
            }
            StructureAction::DeleteRow if rows <= 2 => Some("the net keeps at least 2 rows"),
            StructureAction::DeleteColumn if cols <= 2 => Some("the net keeps at least 2 columns"),
            _ => None,
        }
    }
}

/// The keys, as the Structure section and `docs/editor.md` list them.
pub const KEYS: &str = "on the selected control arrow: R / Shift+R insert a row after / before, \
    C / Shift+C a column after / before, Delete / Shift+Delete delete its row / column";

/// The control cell a handle stands for (structure edits act on the control
/// net: a handle of a deeper edit depth has none).
pub fn control_cell(id: HandleId) -> Option<(usize, usize)> {
    match id.kind {
        HandleKind::SurfaceTangent { level: 0 } => Some(id.cell()),
        _ => None,
    }
}

/// Sends `action` at control cell `cell` and selects the cell it names.
pub fn apply(
    action: StructureAction,
    cell: (usize, usize),
    shape: (usize, usize),
    edits: &mut MessageWriter<EditMessage>,
    selection: &mut Selection,
) {
    let (edit, next) = action.edit(cell, shape);
    edits.write(EditMessage::from(Edit::Author(edit)));
    selection.select(HandleId::tangent(0, next.0, next.1));
}

/// The right-click menu: on which handle, where.
#[derive(Resource, Debug, Default, Clone, PartialEq)]
pub struct ArrowMenu {
    /// Open on this control cell, at this window point (logical px).
    pub open: Option<((usize, usize), Vec2)>,
    /// A right press in the 3D view: where, and on which handle.
    press: Option<(Vec2, Option<HandleId>)>,
}

pub struct StructurePlugin;

impl Plugin for StructurePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ArrowMenu>()
            .add_systems(
                Update,
                (
                    right_click.run_if(
                        not(egui_wants_any_pointer_input)
                            .and_then(in_state(EditorMode::Streamline)),
                    ),
                    keys.run_if(
                        not(egui_wants_any_keyboard_input)
                            .and_then(in_state(EditorMode::Streamline))
                            .and_then(super::super::files::open_save::no_file_dialog),
                    ),
                )
                    .in_set(EditorSet::Input),
            )
            .add_systems(
                EguiPrimaryContextPass,
                menu.run_if(in_state(EditorMode::Streamline)),
            );
    }
}

/// How far (px) a right press may move and still be a click, not an orbit.
const CLICK_SLOP: f32 = 4.0;

/// A right click (press and release within [`CLICK_SLOP`]) on a control
/// arrow opens the menu; anywhere else, or a right drag (the camera's orbit),
/// does not.
fn right_click(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    window: Single<&Window, With<PrimaryWindow>>,
    layout: Res<HandleLayout>,
    mut selection: ResMut<Selection>,
    mut menu: ResMut<ArrowMenu>,
) {
    let _meter = meter.start();
    let Some(cursor) = window.cursor_position() else {
        return;
    };
    if layout.active_joined {
        // a joined patch's net is reshaped in its Patches section, not here
        menu.press = None;
        return;
    }
    if buttons.just_pressed(MouseButton::Right) {
        menu.press = Some((cursor, selection.hover));
    }
    if buttons.just_released(MouseButton::Right)
        && let Some((at, hovered)) = menu.press.take()
        && at.distance(cursor) <= CLICK_SLOP
        && let Some(id) = hovered
        && let Some(cell) = control_cell(id)
    {
        selection.select(id);
        menu.open = Some((cell, cursor));
    }
}

/// The structure keys on the selected control arrow.
fn keys(
    meter: Res<crate::ecs::meter::CpuMeter>,
    keys: Res<ButtonInput<KeyCode>>,
    patch: PatchRef,
    layout: Res<HandleLayout>,
    mut selection: ResMut<Selection>,
    mut edits: MessageWriter<EditMessage>,
) {
    let _meter = meter.start();
    if layout.active_joined {
        return;
    }
    let held = |k: [KeyCode; 2]| keys.any_pressed(k);
    if held([KeyCode::ControlLeft, KeyCode::ControlRight])
        || held([KeyCode::AltLeft, KeyCode::AltRight])
    {
        return;
    }
    let shift = held([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
    let action = if keys.just_pressed(KeyCode::KeyR) {
        Some(if shift {
            StructureAction::RowBefore
        } else {
            StructureAction::RowAfter
        })
    } else if keys.just_pressed(KeyCode::KeyC) {
        Some(if shift {
            StructureAction::ColumnBefore
        } else {
            StructureAction::ColumnAfter
        })
    } else if keys.just_pressed(KeyCode::Delete) {
        Some(if shift {
            StructureAction::DeleteColumn
        } else {
            StructureAction::DeleteRow
        })
    } else {
        None
    };
    let (Some(action), Some(cell)) = (action, selection.primary().and_then(control_cell)) else {
        return;
    };
    let st = patch.structure();
    apply(action, cell, (st.rows, st.cols), &mut edits, &mut selection);
}

/// Draws the right-click menu; a click on an entry sends its edit, a click
/// elsewhere or Esc closes it.
fn menu(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    patch: PatchRef,
    handles: Res<HandleLayout>,
    mut menu: ResMut<ArrowMenu>,
    mut selection: ResMut<Selection>,
    mut edits: MessageWriter<EditMessage>,
) -> Result {
    let _meter = meter.start();
    let Some((cell, at)) = menu.open else {
        return Ok(());
    };
    // the net changed shape under it (an undo, a load): close
    let shape = (patch.structure().rows, patch.structure().cols);
    if cell.0 >= shape.0 || cell.1 >= shape.1 || handles.edit_depth != 0 || handles.active_joined {
        menu.open = None;
        return Ok(());
    }
    let ctx = contexts.ctx_mut()?;
    let mut chosen = None;
    let area = egui::Area::new(egui::Id::new("arrow_menu"))
        .order(egui::Order::Foreground)
        .fixed_pos(egui::pos2(at.x + 2.0, at.y + 2.0))
        .show(ctx, |ui| {
            egui::Frame::menu(ui.style()).show(ui, |ui| {
                ui.label(
                    egui::RichText::new(format!("control tangent ({}, {})", cell.0, cell.1))
                        .weak()
                        .small(),
                );
                for (i, a) in StructureAction::ALL.into_iter().enumerate() {
                    if i == 4 {
                        ui.separator();
                    }
                    let refused = a.refused(shape);
                    let b = ui
                        .add_enabled(
                            refused.is_none(),
                            egui::Button::new(a.label()).shortcut_text(a.key()),
                        )
                        .on_disabled_hover_text(refused.unwrap_or_default());
                    if b.clicked() {
                        chosen = Some(a);
                    }
                }
            });
        });
    let outside = ctx.input(|i| i.pointer.any_pressed())
        && !area.response.contains_pointer()
        && chosen.is_none();
    if ctx.input(|i| i.key_pressed(egui::Key::Escape)) || outside {
        menu.open = None;
    }
    if let Some(a) = chosen {
        apply(a, cell, shape, &mut edits, &mut selection);
        menu.open = None;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn structure_actions_name_the_new_row_or_column() {
        let shape = (6, 9);
        let cell = (2, 5);
        let (e, next) = StructureAction::RowBefore.edit(cell, shape);
        assert_eq!(e, AuthorEdit::insert(Axis::Row, 2));
        assert_eq!(next, (2, 5));
        let (e, next) = StructureAction::RowAfter.edit(cell, shape);
        assert_eq!(e, AuthorEdit::insert(Axis::Row, 3));
        assert_eq!(next, (3, 5));
        let (e, next) = StructureAction::ColumnAfter.edit(cell, shape);
        assert_eq!(e, AuthorEdit::insert(Axis::Column, 6));
        assert_eq!(next, (2, 6));
        // the last row deleted: the selection moves to the new last row
        let (e, next) = StructureAction::DeleteRow.edit((5, 8), shape);
        assert_eq!(e, AuthorEdit::delete(Axis::Row, 5));
        assert_eq!(next, (4, 8));
        let (_, next) = StructureAction::DeleteColumn.edit((5, 8), shape);
        assert_eq!(next, (5, 7));
        assert!(StructureAction::DeleteRow.refused((2, 9)).is_some());
        assert!(StructureAction::DeleteColumn.refused((6, 2)).is_some());
        assert!(StructureAction::RowAfter.refused((64, 2)).is_some());
        assert!(StructureAction::ColumnBefore.refused((6, 64)).is_some());
        assert!(
            StructureAction::ALL
                .iter()
                .all(|a| a.refused(shape).is_none())
        );
    }
}
