//! Documented size limits: depth is capped by the size it would produce, never by a crash.

/// The most tangents one subdivision level may hold (SPEC §8). 4 million tangents are
/// 96 MB of `DVec3` plus the parameter grids and the mesh; beyond that the editor
/// could no longer stay interactive.
pub const MAX_TANGENTS_PER_LEVEL: usize = 4_000_000;

/// The deepest subdivision any API accepts, whatever the size (a guard against
/// overflow in the size arithmetic itself).
pub const MAX_DEPTH: u32 = 16;
