//! The census patch by patch ([`crate::ecs::patch::census`], docs/math.md
//! §11): each patch's name, whether it is joined, and the handle, level and
//! streamline entities it owns (its children). A joined patch owns its net
//! handles only: its levels and points are the values of its
//! [`PatchSurface`] stack, counted as `stack_depths`.

use super::components::{PatchSlot, PatchSurface};
use crate::ecs::components::{Streamline, SubdivisionLevel};
use crate::ecs::patch::census::{Census, PatchCensus};
use crate::ecs::patch::{DetailHandle, InitialHandle, Joined, Patch, SurfaceHandle};
use crate::scene::document::MAIN_PATCH;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use std::collections::HashMap;

/// What a patch is, for the census.
type PatchRow = (
    Entity,
    Option<&'static PatchSlot>,
    Has<Joined>,
    Option<&'static PatchSurface>,
);

/// What a child is, for the census.
type ChildRow = (
    &'static ChildOf,
    Has<SurfaceHandle>,
    Has<InitialHandle>,
    Has<DetailHandle>,
    Has<SubdivisionLevel>,
    Has<Streamline>,
);

/// The counting queries, for a system: the totals and the counts per patch.
#[derive(SystemParam)]
pub struct CensusQuery<'w, 's> {
    totals: crate::ecs::patch::census::CensusQuery<'w, 's>,
    patches: Query<'w, 's, PatchRow, With<Patch>>,
    children: Query<'w, 's, ChildRow>,
}

impl CensusQuery<'_, '_> {
    /// The counts now.
    pub fn count(&self) -> Census {
        let mut c = self.totals.count();
        c.per_patch = per_patch(self.patches.iter(), self.children.iter());
        c
    }
}

/// The census of `world` with the counts per patch (outside the schedule).
pub fn census(world: &mut World) -> Census {
    let mut c = crate::ecs::patch::census::census(world);
    let mut patches = world.query_filtered::<PatchRow, With<Patch>>();
    let mut children = world.query::<ChildRow>();
    c.per_patch = per_patch(patches.iter(world), children.iter(world));
    c
}

/// Counts each patch's children, the patches in the document's order.
fn per_patch<'a>(
    patches: impl Iterator<
        Item = (
            Entity,
            Option<&'a PatchSlot>,
            bool,
            Option<&'a PatchSurface>,
        ),
    >,
    children: impl Iterator<Item = (&'a ChildOf, bool, bool, bool, bool, bool)>,
) -> Vec<PatchCensus> {
    let mut per: Vec<(usize, Entity, PatchCensus)> = patches
        .map(|(e, slot, joined, surface)| {
            let p = PatchCensus {
                name: slot.map_or_else(|| MAIN_PATCH.to_string(), |s| s.name.clone()),
                joined,
                stack_depths: surface
                    .and_then(|s| s.stack())
                    .map_or(0, |s| s.points.len()),
                ..Default::default()
            };
            (slot.map_or(0, |s| s.index), e, p)
        })
        .collect();
    per.sort_by_key(|r| r.0);
    let at: HashMap<Entity, usize> = per.iter().enumerate().map(|(i, r)| (r.1, i)).collect();
    for (parent, surface, initial, detail, level, streamline) in children {
        if let Some(&i) = at.get(&parent.parent()) {
            let p = &mut per[i].2;
            p.handles += (surface || initial || detail) as usize;
            p.levels += level as usize;
            p.streamlines += streamline as usize;
        }
    }
    per.into_iter().map(|r| r.2).collect()
}
