//! Edit messages: the only way the model changes. The editor, scripts and the
//! command line send the same messages, each carrying an [`Edit`] of the
//! model layer (`src/scene/edits/edit.rs`, the very type a script step names).

pub use crate::scene::edits::edit::Edit;
use bevy::prelude::*;

/// An edit, with an optional group: consecutive edits of one group (a drag)
/// make one undo step.
#[derive(Message, Debug, Clone)]
pub struct EditMessage {
    /// The edit.
    pub edit: Edit,
    /// Edits with the same group as the previous one share its undo step.
    pub group: Option<u64>,
}

impl From<Edit> for EditMessage {
    fn from(edit: Edit) -> Self {
        EditMessage { edit, group: None }
    }
}
