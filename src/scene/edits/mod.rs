//! The changes of the model: [`edit::Edit`] (the only way the model
//! changes), the edits of a design's patches ([`patch_edit`]), and scripts
//! of steps ([`script`]).

pub mod edit;
pub mod patch_edit;
pub mod script;
