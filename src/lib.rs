//! Streamline Studio: design fair free-form surfaces by streamline modeling.
//!
//! Layers (see README, "Architecture"): the geometry kernel is the separate crate
//! [`streamline_kernel`] (glam only); this crate adds the model layer
//! ([`scene`]: scene files, scripts, export), the ECS layer ([`ecs`]: entities,
//! the incremental pipeline, undo, playback), the editor ([`editor`]), the
//! headless command line ([`cli`]) and the shared benchmark workloads ([`workloads`]).

pub mod cli;
pub mod ecs;
pub mod editor;
pub mod scene;
pub mod workloads;

pub use streamline_kernel as kernel;
