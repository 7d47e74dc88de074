//! The surface on the Gaussian sphere and its subdivision levels (paper 000, §4–5;
//! docs/math.md §3–5, §9).
//!
//! - [`surface`]: tensor-product subdivision of a control net of tangents
//!   (docs/math.md §3); [`params`]: the parameter grids `s`, `t`, `σ` (§4).
//!   The scheme types and one-direction steps are in `scheme.rs` and the
//!   index ranges in `span.rs`, below `dirty_window.rs` (whose windowed step
//!   `surface`'s whole-grid step runs); `surface` re-exports them.
//! - [`design`]: a whole surface (net, parameters, scheme, initial curve) and
//!   its full build; [`builder`]: the same build keeping its buffers;
//!   [`presets`]: the paper's examples (Figs. 2, 8–11).
//! - [`dirty_window`], [`incremental`], [`multires`]: the levels kept between
//!   edits and updated inside the cells an edit touched; details at depth
//!   (docs/math.md §5; docs/architecture.md, "Incremental rebuild, exactly").
//! - [`tangent_interpolation`]: progressive interpolation of the control
//!   tangents by the approximating schemes (docs/math.md §7, on the sphere).
//! - `oracle` (unit tests only): the plain computations the fast paths are
//!   tested against.

pub mod antipodal;
pub mod builder;
pub mod design;
pub mod dirty_window;
pub mod incremental;
pub mod multires;
#[cfg(test)]
mod oracle;
pub mod params;
pub mod presets;
mod scheme;
mod span;
pub mod surface;
pub mod tangent_interpolation;
