//! The selection: the handles chosen (a list, the first primary: Shift-click
//! and a Shift box add to it) and the one under the pointer.

use super::handle_id::{HandleId, HandleKind};
use super::handle_query::HandleQuery;
use crate::ecs::patch::PatchRef;
use bevy::prelude::*;

/// The selected handles and the hovered one.
#[derive(Resource, Debug, Default, Clone, PartialEq)]
pub struct Selection {
    /// Selected, the first one primary (the panels and `F` use it).
    selected: Vec<HandleId>,
    /// Under the pointer in the 3D view.
    pub hover: Option<HandleId>,
}

impl Selection {
    /// The primary selected handle.
    pub fn primary(&self) -> Option<HandleId> {
        self.selected.first().copied()
    }

    /// The primary handle's cell `(row, col)`.
    pub fn cell(&self) -> Option<(usize, usize)> {
        self.primary().map(HandleId::cell)
    }

    /// Whether `id` is selected.
    pub fn contains(&self, id: HandleId) -> bool {
        self.selected.contains(&id)
    }

    /// The selected handles, the primary first.
    pub fn iter(&self) -> impl Iterator<Item = HandleId> + '_ {
        self.selected.iter().copied()
    }

    /// Selects `id` alone (changes nothing when it already is).
    pub fn select(&mut self, id: HandleId) {
        if self.selected != [id] {
            self.selected = vec![id];
        }
    }

    /// How many are selected.
    pub fn len(&self) -> usize {
        self.selected.len()
    }

    /// Whether nothing is selected.
    pub fn is_empty(&self) -> bool {
        self.selected.is_empty()
    }

    /// Adds `id` to the selection, or takes it out when it is in it
    /// (Shift-click).
    pub fn toggle(&mut self, id: HandleId) {
        match self.selected.iter().position(|&h| h == id) {
            Some(i) => {
                self.selected.remove(i);
            }
            None => self.selected.push(id),
        }
    }

    /// Adds handles not yet selected (a Shift box), keeping the primary.
    pub fn extend(&mut self, ids: impl IntoIterator<Item = HandleId>) {
        for id in ids {
            if !self.selected.contains(&id) {
                self.selected.push(id);
            }
        }
    }

    /// Makes the selected `id` the primary one, keeping the others (the
    /// handle a group drag starts from).
    pub fn make_primary(&mut self, id: HandleId) {
        if let Some(i) = self.selected.iter().position(|&h| h == id)
            && i > 0
        {
            let h = self.selected.remove(i);
            self.selected.insert(0, h);
        }
    }

    /// Selects nothing.
    pub fn clear(&mut self) {
        self.selected.clear();
    }

    /// Follows a change of the handles: a selected surface tangent whose
    /// level is no longer the edit depth becomes the edit depth's tangent at
    /// the same cell; handles that no longer exist are dropped.
    pub fn follow(&mut self, handles: &HandleQuery) {
        let moved: Vec<HandleId> = self
            .selected
            .iter()
            .filter_map(|&h| match handles.find(h) {
                Some(_) => Some(h),
                None => match h.kind {
                    HandleKind::SurfaceTangent { .. } => handles.at(h.cell()).map(|a| a.id),
                    HandleKind::InitialTangent => None,
                },
            })
            .collect();
        if moved != self.selected {
            self.selected = moved;
        }
    }
}

/// Drops a selection that no longer exists (after a depth change or a load).
pub(super) fn keep_valid(
    meter: Res<crate::ecs::meter::CpuMeter>,
    handles: HandleQuery,
    mut selection: ResMut<Selection>,
) {
    let _meter = meter.start();
    if !handles.layout_changed() || !handles.layout().placed {
        return;
    }
    if selection.iter().any(|h| handles.find(h).is_none()) {
        selection.follow(&handles);
    }
}

/// Marks a handle entity that is selected: a control tangent of the net or
/// of the initial curve, a refined cell of the edit depth, and the detail
/// at that cell when it has one.
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Selected;

/// The entities of `id`: its handle entity, and its detail's when it is a
/// refined cell with a detail.
fn entities_of(patch: &PatchRef, handles: &HandleQuery, id: HandleId) -> [Option<Entity>; 2] {
    let detail = match id.kind {
        HandleKind::SurfaceTangent { level } if level > 0 => {
            patch.index().details.get(&(level, id.row, id.col)).copied()
        }
        _ => None,
    };
    [handles.entity(id), detail]
}

/// Keeps the [`Selected`] marker on exactly the selected handles' entities.
pub(super) fn mark_selected(
    mut commands: Commands,
    selection: Res<Selection>,
    patch: PatchRef,
    handles: HandleQuery,
    marked: Query<Entity, With<Selected>>,
) {
    if !selection.is_changed() && !patch.design_changed() && !handles.layout_changed() {
        return;
    }
    let want: Vec<Entity> = selection
        .iter()
        .flat_map(|h| entities_of(&patch, &handles, h))
        .flatten()
        .collect();
    for e in &marked {
        if !want.contains(&e) {
            commands.entity(e).remove::<Selected>();
        }
    }
    for e in want {
        if !marked.contains(e) {
            commands.entity(e).try_insert(Selected);
        }
    }
}
