//! The selection: the handles chosen (a list, the first primary: Shift-click
//! and a Shift box add to it) and the one under the pointer.

use super::handles::{HandleId, HandleKind, Handles};
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
    pub fn follow(&mut self, handles: &Handles) {
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
    handles: Res<Handles>,
    mut selection: ResMut<Selection>,
) {
    let _meter = meter.start();
    if !handles.is_changed() || handles.editable.is_empty() {
        return;
    }
    if selection.iter().any(|h| handles.find(h).is_none()) {
        selection.follow(&handles);
    }
}

/// Marks a handle entity that is selected: a control tangent of the net or
/// of the initial curve, or a detail (a tangent of a deeper level that has
/// no detail yet has no entity to mark).
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Selected;

/// The handle entity of `id`, if it has one.
fn entity_of(patch: &PatchRef, id: HandleId) -> Option<Entity> {
    let index = patch.index();
    match id.kind {
        HandleKind::SurfaceTangent { level: 0 } => (id.row < index.surface.rows()
            && id.col < index.surface.cols())
        .then(|| index.surface.get(id.row, id.col)),
        HandleKind::SurfaceTangent { level } => {
            index.details.get(&(level, id.row, id.col)).copied()
        }
        HandleKind::InitialTangent => index.initial.get(id.col).copied(),
    }
}

/// Keeps the [`Selected`] marker on exactly the selected handles' entities.
pub(super) fn mark_selected(
    mut commands: Commands,
    selection: Res<Selection>,
    patch: PatchRef,
    marked: Query<Entity, With<Selected>>,
) {
    if !selection.is_changed() && !patch.design_changed() {
        return;
    }
    let want: Vec<Entity> = selection
        .iter()
        .filter_map(|h| entity_of(&patch, h))
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
