//! The census: the world's entities counted by queries (`build --json`'s
//! `"entities"`, the Stats panel), in all and patch by patch.
//!
//! A design of several patches (docs/math.md §11): the first patch owns
//! its handles, levels and streamlines as entities (the incremental
//! pipeline); a later, joined patch owns only its net handles as entities:
//! its levels and streamline points are values of its
//! [`crate::ecs::joined::PatchSurface`] (a kernel `Stack`, built whole by
//! the joins), so it counts 0 level and 0 streamline entities, and its
//! `stack_depths` says how many depths that stack holds.

use super::components::*;
use crate::ecs::components::{Streamline, SubdivisionLevel};
use crate::ecs::joined::{PatchSlot, PatchSurface};
use crate::scene::document::MAIN_PATCH;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use std::collections::HashMap;

/// How many entities of each kind the world holds.
#[derive(Debug, Clone, Default, PartialEq, Eq, serde::Serialize)]
pub struct Census {
    /// Patch entities.
    pub patches: usize,
    /// Tangent handles by kind.
    pub handles: HandleCensus,
    /// Subdivision-level entities.
    pub levels: usize,
    /// Streamline entities.
    pub streamlines: usize,
    /// Patch by patch, in the document's order.
    pub per_patch: Vec<PatchCensus>,
}

/// Tangent handles by kind.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct HandleCensus {
    /// Control tangents of the net.
    pub surface: usize,
    /// Control tangents of the initial curve.
    pub initial: usize,
    /// Multiresolution details.
    pub detail: usize,
}

/// One patch's entities (module documentation).
#[derive(Debug, Clone, Default, PartialEq, Eq, serde::Serialize)]
pub struct PatchCensus {
    /// Its name in the document (`main` for a one-patch design).
    pub name: String,
    /// Whether it starts on another patch's edge (built by the joins).
    pub joined: bool,
    /// Its handle entities (net, initial curve, details).
    pub handles: usize,
    /// Its subdivision-level entities (0 for a joined patch).
    pub levels: usize,
    /// Its streamline entities (0 for a joined patch).
    pub streamlines: usize,
    /// Depths held by its built stack of values (`0 ..= d`: d + 1; 0 when
    /// it has none, as a one-patch design's patch).
    pub stack_depths: usize,
}

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

/// The counting queries, for a system.
#[derive(SystemParam)]
pub struct CensusQuery<'w, 's> {
    patches: Query<'w, 's, PatchRow, With<Patch>>,
    children: Query<'w, 's, ChildRow>,
}

impl CensusQuery<'_, '_> {
    /// The counts now.
    pub fn count(&self) -> Census {
        tally(self.patches.iter(), self.children.iter())
    }
}

/// Counts the patches and their children.
fn tally<'a>(
    patches: impl Iterator<
        Item = (
            Entity,
            Option<&'a PatchSlot>,
            bool,
            Option<&'a PatchSurface>,
        ),
    >,
    children: impl Iterator<Item = (&'a ChildOf, bool, bool, bool, bool, bool)>,
) -> Census {
    let mut c = Census::default();
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
    c.patches = per.len();
    let at: HashMap<Entity, usize> = per.iter().enumerate().map(|(i, r)| (r.1, i)).collect();
    for (parent, surface, initial, detail, level, streamline) in children {
        c.handles.surface += surface as usize;
        c.handles.initial += initial as usize;
        c.handles.detail += detail as usize;
        c.levels += level as usize;
        c.streamlines += streamline as usize;
        if let Some(&i) = at.get(&parent.parent()) {
            let p = &mut per[i].2;
            p.handles += (surface || initial || detail) as usize;
            p.levels += level as usize;
            p.streamlines += streamline as usize;
        }
    }
    c.per_patch = per.into_iter().map(|r| r.2).collect();
    c
}

/// The census of `world` (outside the schedule: the command line, tests).
pub fn census(world: &mut World) -> Census {
    fn n<F: bevy::ecs::query::QueryFilter>(world: &mut World) -> usize {
        world.query_filtered::<(), F>().iter(world).count()
    }
    let mut patches = world.query_filtered::<PatchRow, With<Patch>>();
    let mut children = world.query::<ChildRow>();
    let mut c = tally(patches.iter(world), children.iter(world));
    // handles, levels and streamlines that are no patch's child count too
    c.handles = HandleCensus {
        surface: n::<With<SurfaceHandle>>(world),
        initial: n::<With<InitialHandle>>(world),
        detail: n::<With<DetailHandle>>(world),
    };
    c.levels = n::<With<SubdivisionLevel>>(world);
    c.streamlines = n::<With<Streamline>>(world);
    c
}
