//! Several patches in the world (docs/math.md §11; docs/architecture.md,
//! "Several patches"): the patches of a document after its first are
//! [`crate::ecs::patch::Patch`] entities with their net handles as
//! children ([`spawn::spawn_joined`]), built through the kernel's joins
//! into a [`PatchSurface`] each, with a [`SeamState`] per join
//! ([`build`]), and their levels and streamlines as children
//! ([`entities`]). The first patch keeps the incremental pipeline.

pub mod build;
pub mod components;
pub mod entities;
pub mod first;
pub mod g2;
pub mod kept;
pub mod patch_ops;
pub mod spawn;
pub mod world_io;

pub use crate::ecs::components::JoinedChild;
pub use crate::ecs::edit_state::{DocState, JoinedState, StartState, same_design};
pub use components::*;
pub use entities::JoinedEntities;
pub use kept::{KeptPatch, PatchWork};
pub use spawn::{adopt_first, spawn_joined, spawn_joined_patch, spawn_joined_with};
pub use world_io::{JoinedRead, doc_state, document};

use bevy::prelude::*;

/// The joined patches' systems, after the first patch's pipeline has
/// brought its kernel design up to date.
pub struct JoinedPlugin;

impl Plugin for JoinedPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ActivePatch>().add_systems(
            Update,
            (
                build::track_joined,
                build::build_joined,
                entities::sync_joined_entities,
            )
                .chain()
                .in_set(crate::ecs::ModelSet::Mesh)
                // the first patch's mesh normals are read (build::FirstPipeline)
                .after(crate::ecs::mesh::patch_mesh),
        );
    }
}
