//! Another active patch (docs/math.md §11): its handles have the same ids
//! as the last one's, so the selection and the hover are cleared and a drag
//! in progress ends (its edits so far stay one undo step).

use super::drag::Drag;
use super::placed::HandleLayout;
use super::selection::Selection;
use bevy::prelude::*;

/// Clears the selection and ends a drag when the placed active patch
/// changed (not at the first placement).
pub(super) fn follow_active(
    meter: Res<crate::ecs::meter::CpuMeter>,
    layout: Res<HandleLayout>,
    mut selection: ResMut<Selection>,
    mut drag: ResMut<Drag>,
    mut shown: Local<Option<Entity>>,
) {
    let _meter = meter.start();
    if !layout.is_changed() || !layout.placed || *shown == layout.active {
        return;
    }
    let first = shown.is_none();
    *shown = layout.active;
    if first {
        return;
    }
    if !selection.is_empty() || selection.hover.is_some() {
        selection.clear();
        selection.hover = None;
    }
    if drag.0.is_some() {
        drag.0 = None;
    }
}
