//! Streamline Studio: design fair free-form surfaces by streamline modeling.
//!
//! Layers (see README, "Architecture"): the geometry kernel is the separate crate
//! [`streamline_kernel`] (glam only); this crate adds the model layer
//! ([`scene`]: scene files, scripts, export), the ECS layer ([`ecs`]: entities,
//! the incremental pipeline, undo, playback), the editor ([`editor`]) and the
//! headless command line ([`cli`], with the benchmark workloads beside its
//! `bench` command: [`cli::bench::workloads`]).
//!
//! Feature `app` (on by default) brings Bevy: the ECS layer, the editor and
//! the binary. Without it the crate is the Bevy-free part (scene files,
//! scripts, OBJ, the JSON commands). Feature `fuzz` adds the fuzz harness
//! (`cli::fuzz`, also `fuzz`: each input's target, which panics on a broken
//! invariant): the libFuzzer targets in `fuzz/` build on it without `app`,
//! and the tests turn it on (`tests/fuzz.rs`); a normal build leaves it out.

pub mod cli;
#[cfg(feature = "app")]
pub mod ecs;
#[cfg(feature = "app")]
pub mod editor;
pub mod scene;

#[cfg(feature = "fuzz")]
pub use cli::fuzz;
pub use streamline_kernel as kernel;
