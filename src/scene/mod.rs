//! The model layer: scene files (RON, versioned), their validation with
//! located errors, atomic saving, edits and scripts, mesh export, and OBJ triangle meshes. Depends on the
//! kernel and serde/ron only (no Bevy).

pub mod builtin;
pub mod cad;
pub mod cad_text;
pub mod document;
pub mod document_build;
pub mod document_check;
pub mod document_deviation;
pub mod document_export;
pub mod document_fit;
pub mod document_io;
pub mod document_mirror;
pub mod edit;
pub mod error;
pub mod export;
pub mod format;
pub mod format_v3;
pub mod glb;
pub mod iges;
pub mod io;
pub mod job;
pub mod model;
pub mod numbers;
pub mod obj;
pub mod obj_shell;
pub mod patch_edit;
pub mod patch_text;
pub mod reference_fit;
pub mod reference_link;
pub mod script;
pub mod spec_kernel;
pub mod step;
pub mod step_shell;
pub mod stl_shell;
pub mod usd;

pub use document::Document;
pub use error::SceneError;
pub use format::SceneFile;
pub use model::Scene;
