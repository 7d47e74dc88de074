//! Edits of a design's patches (docs/math.md §11): add a patch on another's
//! edge, choose the patch that handle edits act on, remove, rename, hide.
//! The editor sends them as [`super::edit::Edit::Patch`]; a script names
//! each by its variant (`AddPatch(name: "tail", from: ("main", End), …)`,
//! `SetPatch("tail")`). The ECS edit stage applies them
//! (`src/ecs/joined/edits.rs`). `SetPatch` is a choice, not a change of the
//! design, so it is not an undo step; the others are one undo step each.

use crate::scene::files::format::Finite;
use crate::scene::files::format_v3::{ContinuitySpec, EdgeSpec};
use serde::{Deserialize, Serialize};

/// One edit of the design's patches.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum PatchEdit {
    /// A new patch `name` starting on `from`'s edge (`(patch, edge)`) with
    /// `continuity`: a `rows × cols` net, its streamlines `length` long. A
    /// chain (`End`) takes the patch's rows (`rows` must be theirs) and
    /// continues its last column; a side join (`First`, `Last`) leaves the
    /// streamline across it.
    AddPatch {
        name: String,
        from: (String, EdgeSpec),
        continuity: ContinuitySpec,
        rows: usize,
        cols: usize,
        length: Finite,
    },
    /// The patch later handle edits act on (the first patch until one is
    /// set). Not an undo step.
    SetPatch(String),
    /// Removes a patch no other patch starts on (not the first).
    RemovePatch(String),
    /// Renames a patch: `(from, to)`.
    RenamePatch(String, String),
    /// Hides (`true`) or shows a patch: it is not drawn nor picked. Not
    /// written to the file.
    HidePatch(String, bool),
}

impl PatchEdit {
    /// A short description for logs and stats.
    pub fn label(&self) -> String {
        match self {
            PatchEdit::AddPatch {
                name,
                from: (a, edge),
                continuity,
                ..
            } => format!("add patch `{name}` on `{a}` ({edge:?}, {continuity:?})"),
            PatchEdit::SetPatch(n) => format!("edit patch `{n}`"),
            PatchEdit::RemovePatch(n) => format!("remove patch `{n}`"),
            PatchEdit::RenamePatch(a, b) => format!("rename patch `{a}` to `{b}`"),
            PatchEdit::HidePatch(n, true) => format!("hide patch `{n}`"),
            PatchEdit::HidePatch(n, false) => format!("show patch `{n}`"),
        }
    }

    /// Whether it gets an undo step (choosing the patch to edit does not).
    pub fn is_undoable(&self) -> bool {
        !matches!(self, PatchEdit::SetPatch(_))
    }
}
