//! The editor's components of the handle entities (docs/architecture.md,
//! "Entities"): where each handle is drawn ([`Placed`]), the refined
//! tangents of the edit depth as entities of their own ([`RefinedHandle`]),
//! the mirrored half's copies ([`MirroredHandle`]), and what is not per
//! handle ([`HandleLayout`]: the edit depth, the arrows' length cap, the
//! entities of the refined cells and of the copies, by position).
//!
//! Every handle the editor shows or picks is an entity, a child of the
//! patch: the net's control tangents ([`crate::ecs::patch::SurfaceHandle`])
//! and the initial curve's ([`crate::ecs::patch::InitialHandle`]) carry a
//! [`HandleId`] and a [`Placed`] once placed; a refined cell is a
//! [`RefinedHandle`] entity; a mirrored copy is a [`MirroredHandle`] entity
//! with a [`Placed`] and no [`HandleId`], so that nothing picks it.

use super::handle_id::{Handle, HandleId};
use bevy::prelude::*;
use streamline_kernel::DVec3;

/// Where a handle is drawn, in kernel coordinates: its streamline point, its
/// unit direction (its point on the Gaussian sphere) and the drawn length.
/// Compared bit for bit, so that the placing system's `set_if_neq` marks
/// changed exactly the handles that moved.
#[derive(Component, Debug, Clone, Copy)]
pub struct Placed {
    /// Its streamline point.
    pub base: DVec3,
    /// The unit tangent.
    pub dir: DVec3,
    /// Drawn length.
    pub length: f64,
}

fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

impl PartialEq for Placed {
    fn eq(&self, o: &Self) -> bool {
        bits(self.base) == bits(o.base)
            && bits(self.dir) == bits(o.dir)
            && self.length.to_bits() == o.length.to_bits()
    }
}

impl Placed {
    /// The handle `id` placed here.
    pub fn handle(&self, id: HandleId) -> Handle {
        Handle {
            id,
            base: self.base,
            dir: self.dir,
            length: self.length,
        }
    }
}

impl From<&Handle> for Placed {
    fn from(h: &Handle) -> Self {
        Placed {
            base: h.base,
            dir: h.dir,
            length: h.length,
        }
    }
}

/// A tangent of the edit depth's level (above 0) of the active patch: one
/// entity per cell, a child of that patch, spawned when the edit depth, the
/// active patch or that level's shape changes, despawned when the edit
/// depth goes back to 0. Its direction is the level's
/// tangent; turning it edits the detail at its cell (`docs/math.md §5`).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RefinedHandle {
    /// The level (the edit depth).
    pub level: u32,
    /// Row at that level.
    pub row: usize,
    /// Column at that level.
    pub col: usize,
}

/// With mirror symmetry on (`docs/math.md §9`): the reflected copy of a
/// control tangent, on the other half; drawn dimmed, never picked (it has
/// no [`HandleId`]).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MirroredHandle {
    /// The control tangent it reflects.
    pub of: HandleId,
}

/// How a placed handle entity is drawn, by its patch (docs/editor.md,
/// "Several patches"): the active patch's as today, every other patch's
/// dimmed (thin, faint, never picked), a hidden patch's
/// ([`crate::ecs::joined::PatchHidden`]) not at all. Written by one
/// system, with `set_if_neq`, so `Changed<PatchRole>` means it changed.
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub enum PatchRole {
    /// A handle of the active patch: drawn and picked.
    #[default]
    Active,
    /// A handle of another patch: drawn dimmed, never picked.
    Dimmed,
    /// A handle of a hidden patch: not drawn, never picked.
    Hidden,
}

/// What the placement knows that is not one handle's: the edit depth the
/// handles were placed for, the cap on the arrows' length, and the entities
/// of the refined cells and the mirrored copies by position (the net's and
/// the initial curve's are in [`crate::ecs::patch::PatchIndex`]).
#[derive(Resource, Debug, Default)]
pub struct HandleLayout {
    /// The edit depth the handles belong to.
    pub edit_depth: u32,
    /// The cap on the arrows' length the handles were placed with.
    pub cap: f64,
    /// Whether a placement ran (the handles have their [`Placed`]).
    pub placed: bool,
    /// The active patch's cells of the edit depth (above 0): `(rows, cols)`
    /// and their entities, row-major, children of that patch (a chain's
    /// seam column's cells have no place: neither drawn nor picked).
    pub refined: Option<((usize, usize), Vec<Entity>)>,
    /// The mirrored copies, in the order they are placed.
    pub mirrored: Vec<Entity>,
    /// Handles placed again by the last placement (all of them, or the rows
    /// of the control tangents whose handle entities changed).
    pub moved: usize,
    /// The patch whose handles were placed as the active ones (shown and
    /// picked, [`crate::ecs::joined::ActivePatch`] resolved: the first
    /// patch when it names none or no patch); `None` before a placement.
    pub active: Option<Entity>,
    /// Whether that patch is a joined one (docs/math.md §11): its handles
    /// are placed at the edit depth on its stack, as the first patch's are
    /// on its levels (its details are kept and built, docs/math.md §11.4),
    /// and the first patch's handles are dimmed.
    pub active_joined: bool,
}

impl HandleLayout {
    /// The refined cell `(row, col)`'s entity at `level`, if it has one.
    pub fn refined_at(&self, level: u32, (row, col): (usize, usize)) -> Option<Entity> {
        let ((rows, cols), v) = self.refined.as_ref()?;
        (level == self.edit_depth && level > 0 && row < *rows && col < *cols)
            .then(|| v[row * cols + col])
    }
}
