//! The model layer: scene files (RON, versioned), their validation with
//! located errors, atomic saving, scripts, mesh export, and OBJ triangle meshes. Depends on the
//! kernel and serde/ron only (no Bevy).

pub mod builtin;
pub mod error;
pub mod export;
pub mod format;
pub mod io;
pub mod job;
pub mod model;
pub mod obj;
pub mod script;

pub use error::SceneError;
pub use format::SceneFile;
pub use model::Scene;
