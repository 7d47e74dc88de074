//! From a refined net of tangents to a surface (paper 000, §2 and §5; docs/math.md §4).
//!
//! - [`integrate`]: one row of tangents integrated into an arc-length
//!   streamline (Eq. 65).
//! - [`initial_curve`]: the curve `S(s_a, t)` every streamline starts on (Eq. 1).
//! - [`surface_mesh`]: the rows of streamlines joined into the surface's
//!   triangle mesh, with vertex normals.

pub mod initial_curve;
pub mod integrate;
pub mod surface_mesh;
