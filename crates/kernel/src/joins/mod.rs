//! Several patches in one design (docs/math.md §11; paper 000 §7, "switch
//! parameters from one (s) to the other (t)"): a patch `B` starts on an edge
//! of an earlier patch `A`, and the join's continuity holds **by
//! construction at every depth**.
//!
//! - [`kinds`]: [`Edge`] (`End`, `First`, `Last`), [`Continuity`] (`G0`–`G2`), [`Join`].
//! - [`stack`]: a patch's levels and points at every depth, what a join reads;
//!   [`parts`]: a patch's net with its details and fine tuning, what is built.
//! - [`chain`]: `edge: End` with G0 or G1 (§11.1); [`merged`]: G2 chains as
//!   one merged net cut at the seams (§11.1); [`g2_state`]: a G2 run kept
//!   between edits, re-blended inside the edit's window; [`patch_state`]:
//!   one patch (on its own curve, a chain or a side join) kept the same way,
//!   brought up to date after an edit of its own or of its parent.
//! - [`edge_curve`]: `A`'s first or last streamline as a curve with normals;
//!   [`side`]: joins on it, G0 or G1 (§11.2).
//! - [`build`]: one join built whole; [`seam`]: the seam report (§11.3).
//! - [`error`]: why a join is refused, and what to do.

pub mod build;
pub mod chain;
pub mod edge_curve;
pub mod error;
mod g2_recut;
pub mod g2_state;
pub mod kinds;
pub mod merged;
pub mod parts;
mod patch_start;
pub mod patch_state;
pub mod seam;
pub mod side;
pub mod stack;

pub use build::join;
pub use error::JoinError;
pub use kinds::{Continuity, Edge, Join};
pub use parts::PatchParts;
pub use seam::{SeamReport, seam_at};
pub use stack::{RowSpan, Stack};
