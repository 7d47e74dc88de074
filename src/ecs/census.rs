//! The census: the world's entities counted by one query (`build --json`'s
//! `"entities"`, the Stats panel), in all and patch by patch.
//!
//! Every patch entity owns its handles as children (net, initial curve,
//! details), a subdivision-level entity per depth and a streamline entity
//! per row of its display depth: the first patch's from its incremental
//! pipeline, a joined patch's (docs/math.md §11) from
//! [`crate::ecs::joined::entities`], their values those of its
//! `PatchSurface` (a kernel `Stack`, whose depths `stack_depths` counts).

use crate::ecs::components::{Streamline, SubdivisionLevel};
use crate::ecs::joined::components::{PatchSlot, PatchSurface};
use crate::ecs::patch::{DetailHandle, InitialHandle, Joined, Patch, SurfaceHandle};
use crate::scene::design::document::MAIN_PATCH;
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
    /// Its subdivision-level entities, one per depth.
    pub levels: usize,
    /// Its streamline entities, one per row of its display depth.
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

/// What a counted entity is: its patch (`None` for one without a parent)
/// and its kind.
type CountedRow = (
    Option<&'static ChildOf>,
    Has<SurfaceHandle>,
    Has<InitialHandle>,
    Has<DetailHandle>,
    Has<SubdivisionLevel>,
    Has<Streamline>,
);

/// The entities counted: handles, levels and streamlines.
type Counted = Or<(
    With<SurfaceHandle>,
    With<InitialHandle>,
    With<DetailHandle>,
    With<SubdivisionLevel>,
    With<Streamline>,
)>;

/// The counting queries, for a system: the patches, and every handle,
/// level and streamline in one query.
#[derive(SystemParam)]
pub struct CensusQuery<'w, 's> {
    patches: Query<'w, 's, PatchRow, With<Patch>>,
    counted: Query<'w, 's, CountedRow, Counted>,
}

impl CensusQuery<'_, '_> {
    /// The counts now.
    pub fn count(&self) -> Census {
        count(self.patches.iter(), self.counted.iter())
    }
}

/// The census of `world` (outside the schedule: the command line, tests).
pub fn census(world: &mut World) -> Census {
    let mut patches = world.query_filtered::<PatchRow, With<Patch>>();
    let mut counted = world.query_filtered::<CountedRow, Counted>();
    count(patches.iter(world), counted.iter(world))
}

/// The totals and each patch's children, the patches in the document's order.
fn count<'a>(
    patches: impl Iterator<
        Item = (
            Entity,
            Option<&'a PatchSlot>,
            bool,
            Option<&'a PatchSurface>,
        ),
    >,
    counted: impl Iterator<Item = (Option<&'a ChildOf>, bool, bool, bool, bool, bool)>,
) -> Census {
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
    let mut c = Census {
        patches: per.len(),
        ..Default::default()
    };
    for (parent, surface, initial, detail, level, streamline) in counted {
        c.handles.surface += surface as usize;
        c.handles.initial += initial as usize;
        c.handles.detail += detail as usize;
        c.levels += level as usize;
        c.streamlines += streamline as usize;
        if let Some(&i) = parent.and_then(|p| at.get(&p.parent())) {
            let p = &mut per[i].2;
            p.handles += (surface || initial || detail) as usize;
            p.levels += level as usize;
            p.streamlines += streamline as usize;
        }
    }
    c.per_patch = per.into_iter().map(|r| r.2).collect();
    c
}
