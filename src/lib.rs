//! Streamline Studio: design fair free-form surfaces by streamline modeling.
//!
//! Layers (see README, "Architecture"): the geometry kernel is the separate crate
//! [`streamline_kernel`] (glam only); this crate adds the model layer
//! ([`scene`]: scene files, scripts, export), the ECS layer ([`ecs`]: entities,
//! the incremental pipeline, undo, playback), the editor ([`editor`]), the
//! headless command line ([`cli`]) and the shared benchmark workloads ([`workloads`]).
//!
//! Feature `app` (on by default) brings Bevy: the ECS layer, the editor and
//! the binary. Without it the crate is the Bevy-free part (scene files,
//! scripts, OBJ, the JSON commands and the [`fuzz`] targets), which is what
//! the libFuzzer targets in `fuzz/` build on.

pub mod cli;
#[cfg(feature = "app")]
pub mod ecs;
#[cfg(feature = "app")]
pub mod editor;
pub mod fuzz;
pub mod job;
pub mod scene;
#[cfg(feature = "app")]
pub mod workloads;

pub use streamline_kernel as kernel;
