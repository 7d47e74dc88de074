//! The headless command line: JSON on stdin, JSON on stdout; bad input exits 2
//! with a one-line message on stderr, never a panic.

#[cfg(feature = "app")]
pub mod bench;
#[cfg(feature = "app")]
mod build;
#[cfg(feature = "app")]
mod command;
#[cfg(feature = "app")]
mod editor;
#[cfg(feature = "app")]
mod faces;
#[cfg(feature = "app")]
mod fit;
#[cfg(feature = "fuzz")]
pub mod fuzz;
pub mod geometry;
pub mod input;
#[cfg(feature = "app")]
mod interpolate;
#[cfg(feature = "app")]
mod play;

#[cfg(feature = "app")]
pub use command::{Cli, Command, main, run};
pub use input::CliError;
