//! The census: the world's entities counted by queries (`build --json`'s
//! `"entities"`, the Stats panel).

use super::components::*;
use crate::ecs::components::{Streamline, SubdivisionLevel};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;

/// How many entities of each kind the world holds.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Census {
    /// Patch entities.
    pub patches: usize,
    /// Tangent handles by kind.
    pub handles: HandleCensus,
    /// Subdivision-level entities.
    pub levels: usize,
    /// Streamline entities.
    pub streamlines: usize,
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
    /// The counts now.
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
        }
    }
}

/// The census of `world` (outside the schedule: the command line, tests).
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
    }
}
