//! The census: the world's entities counted by queries (`build --json`'s
//! `"entities"`, the Stats panel), in all and patch by patch.
//!
//! A design of several patches (docs/math.md §11): the first patch owns
//! its handles, levels and streamlines as entities (the incremental
//! pipeline); a later, joined patch owns only its net handles as entities:
//! its levels and streamline points are values of its `PatchSurface` (a
//! kernel `Stack`, built whole by the joins), so it counts 0 level and 0
//! streamline entities, and its `stack_depths` says how many depths that
//! stack holds. The counts per patch ([`Census::per_patch`]) are made by
//! `crate::ecs::joined::census`, which knows the patches' names and stacks
//! ([`census`] here leaves them empty).

use super::components::*;
use crate::ecs::components::{Streamline, SubdivisionLevel};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;

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
    /// Patch by patch, in the document's order (made by
    /// `crate::ecs::joined::census`; empty from [`census`] and [`CensusQuery`]).
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

/// The counting queries, for a system.
#[derive(SystemParam)]
pub struct CensusQuery<'w, 's> {
    patches: Query<'w, 's, (), With<Patch>>,
    surface: Query<'w, 's, (), With<SurfaceHandle>>,
    initial: Query<'w, 's, (), With<InitialHandle>>,
    detail: Query<'w, 's, (), With<DetailHandle>>,
    levels: Query<'w, 's, (), With<SubdivisionLevel>>,
    streamlines: Query<'w, 's, (), With<Streamline>>,
}

impl CensusQuery<'_, '_> {
    /// The counts now (without [`Census::per_patch`]).
    pub fn count(&self) -> Census {
        Census {
            patches: self.patches.iter().count(),
            handles: HandleCensus {
                surface: self.surface.iter().count(),
                initial: self.initial.iter().count(),
                detail: self.detail.iter().count(),
            },
            levels: self.levels.iter().count(),
            streamlines: self.streamlines.iter().count(),
            per_patch: Vec::new(),
        }
    }
}

/// The census of `world` (outside the schedule: the command line, tests),
/// without [`Census::per_patch`] (`crate::ecs::joined::census::census` adds it).
pub fn census(world: &mut World) -> Census {
    fn n<F: bevy::ecs::query::QueryFilter>(world: &mut World) -> usize {
        world.query_filtered::<(), F>().iter(world).count()
    }
    Census {
        patches: n::<With<Patch>>(world),
        handles: HandleCensus {
            surface: n::<With<SurfaceHandle>>(world),
            initial: n::<With<InitialHandle>>(world),
            detail: n::<With<DetailHandle>>(world),
        },
        levels: n::<With<SubdivisionLevel>>(world),
        streamlines: n::<With<Streamline>>(world),
        per_patch: Vec::new(),
    }
}
