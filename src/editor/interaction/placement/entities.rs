//! Writing the placed handles on their entities: every [`Placed`] with
//! `set_if_neq` (only a handle whose place differs bit for bit is marked
//! changed), the mirrored copies' entities and the active patch's refined
//! cells' entities (spawned as children of their patch, despawned when no
//! longer shown).

use super::super::handle_id::Handle;
use super::super::placed::{HandleLayout, MirroredHandle, Placed, RefinedHandle};
use bevy::prelude::*;

/// The entities the placement writes: every [`Placed`], the copies' and the
/// refined cells' own components.
#[derive(bevy::ecs::system::SystemParam)]
pub(crate) struct PlacedEntities<'w, 's> {
    pub(super) commands: Commands<'w, 's>,
    pub(super) placed: Query<'w, 's, &'static mut Placed>,
    mirrored: Query<'w, 's, &'static mut MirroredHandle>,
    refined: Query<'w, 's, &'static ChildOf, With<RefinedHandle>>,
}

impl PlacedEntities<'_, '_> {
    /// Writes handle `h`'s place on entity `e` (marked changed only when it
    /// differs), or gives `e` its id and place when it has none yet.
    pub(super) fn put(&mut self, e: Entity, h: &Handle) {
        let p = Placed::from(h);
        match self.placed.get_mut(e) {
            Ok(mut old) => {
                old.set_if_neq(p);
            }
            Err(_) => {
                self.commands.entity(e).try_insert((h.id, p));
            }
        }
    }

    /// Despawns the entities `v` (the refined cells or the copies).
    fn despawn(&mut self, v: &[Entity]) {
        for &e in v {
            self.commands.entity(e).try_despawn();
        }
    }
}

/// The active patch's cells of the edit depth (above 0): the shape of the
/// grid of their entities and the handles placed on it (a cell without a
/// handle, a chain's seam column, gets an entity with no place: neither
/// drawn nor picked).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Refined {
    /// `(rows, cols)` of the cells.
    pub shape: (usize, usize),
    /// The placed handles, each at its cell.
    pub handles: Vec<Handle>,
}

/// The mirrored copies on their entities: the same entities when their
/// number is the same, else new ones.
pub(super) fn place_copies(
    patch: Entity,
    copies: &[Handle],
    layout: &mut HandleLayout,
    out: &mut PlacedEntities,
) {
    let alive = layout.mirrored.len() == copies.len()
        && layout.mirrored.iter().all(|&e| out.mirrored.contains(e));
    if !alive {
        let old = std::mem::take(&mut layout.mirrored);
        out.despawn(&old);
        layout.mirrored = copies
            .iter()
            .map(|h| {
                let c = (MirroredHandle { of: h.id }, Placed::from(h));
                out.commands.spawn((c, ChildOf(patch))).id()
            })
            .collect();
        return;
    }
    for (h, &e) in copies.iter().zip(&layout.mirrored) {
        if let Ok(mut m) = out.mirrored.get_mut(e) {
            m.set_if_neq(MirroredHandle { of: h.id });
        }
        if let Ok(mut p) = out.placed.get_mut(e) {
            p.set_if_neq(Placed::from(h));
        }
    }
}

/// The edit depth's cells of patch `patch` on their entities (above 0):
/// the same entities while the patch, the level and its shape stay, else
/// new ones; none at depth 0 or when `refined` is `None`. `layout` still
/// holds what was placed before (its edit depth).
pub(super) fn place_refined(
    patch: Entity,
    edit: u32,
    refined: Option<Refined>,
    layout: &mut HandleLayout,
    out: &mut PlacedEntities,
) {
    let Some(Refined { shape, handles }) = refined.filter(|_| edit > 0) else {
        if let Some((_, old)) = layout.refined.take() {
            out.despawn(&old);
        }
        return;
    };
    let cols = shape.1;
    let keep = layout.refined.as_ref().is_some_and(|(s, v)| {
        *s == shape
            && layout.edit_depth == edit
            && v.len() == shape.0 * shape.1
            && v.iter()
                .all(|&e| out.refined.get(e).is_ok_and(|c| c.parent() == patch))
    });
    if keep {
        let entities = layout.refined.as_ref().map(|(_, v)| v.clone());
        let entities = entities.unwrap_or_default();
        for h in &handles {
            if let Some(&e) = entities.get(h.id.row * cols + h.id.col) {
                out.put(e, h);
            }
        }
        return;
    }
    if let Some((_, old)) = layout.refined.take() {
        out.despawn(&old);
    }
    let mut at: Vec<Option<&Handle>> = vec![None; shape.0 * shape.1];
    for h in &handles {
        if h.id.row < shape.0 && h.id.col < cols {
            at[h.id.row * cols + h.id.col] = Some(h);
        }
    }
    let entities = at
        .iter()
        .enumerate()
        .map(|(k, h)| {
            let cell = RefinedHandle {
                level: edit,
                row: k / cols.max(1),
                col: k % cols.max(1),
            };
            let mut e = out.commands.spawn((cell, ChildOf(patch)));
            if let Some(h) = h {
                e.insert((h.id, Placed::from(*h)));
            }
            e.id()
        })
        .collect();
    layout.refined = Some((shape, entities));
}
