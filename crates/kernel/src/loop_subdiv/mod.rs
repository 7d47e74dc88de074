//! Triangle meshes and Loop subdivision (paper 002; docs/math.md §7).
//!
//! - [`trimesh`]: positions and faces, their topology and validation.
//! - [`subdivide`]: Loop subdivision with boundary rules, and limit points.
//! - [`mesh_interpolation`]: progressive interpolation of a mesh's vertices
//!   by its Loop limit surface.

pub mod mesh_interpolation;
pub mod subdivide;
pub mod trimesh;
