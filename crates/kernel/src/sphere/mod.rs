//! The Gaussian sphere S²: tangents as points of it, and how two of them blend.
//!
//! - [`tangent`]: the validated unit vector at the kernel's boundary.
//! - [`antipodal`]: which neighbours a build blends about the fixed axis
//!   (the designer's warning).
//! - [`blend`]: `(1−u) a ⊕ u b` (Eq. 33), midpoints and quarters, the
//!   trig-free fixed blend of the hot loops (docs/math.md §1).

pub mod antipodal;
pub mod blend;
pub mod tangent;
