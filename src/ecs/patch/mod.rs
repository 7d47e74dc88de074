//! The patch: the root entity of one streamline surface, the parent of its
//! tangent handles (one entity per control tangent of the net, per
//! multiresolution detail, per control tangent of the initial curve), its
//! subdivision levels and its streamlines (docs/architecture.md, "Entities").
//! The handles' components are the design at run time; the scene is
//! assembled from them ([`scene`]) and written back into them
//! ([`scene_io`]); [`track`] turns their changes into the work of the
//! blend stage; [`crate::ecs::census`] counts the entities.

pub mod components;
pub(crate) mod dirty;
mod read;
pub mod scene_io;
pub(crate) mod track;

pub use components::*;
pub use read::PatchRef;
pub use scene_io::{patch_entity, scene, spawn_patch, try_scene};
