//! The model layer: scene files (RON, versioned), their validation with
//! located errors, atomic saving, edits and scripts, exports, and the Loop
//! mesh's OBJ and USD files. Depends on the kernel and serde/ron only (no
//! Bevy).
//!
//! Its rooms, each importing only the rooms listed before it and [`job`]:
//!
//! - [`files`]: the scene file's forms (versions 1–3), its errors, where
//!   each patch sits in its text, the reference it names, and reading and
//!   atomic writing of files;
//! - [`design`]: a scene and a document of several patches in memory, their
//!   checks, their building through the kernel's joins, their mirror, the
//!   built-in scenes, and reading and saving them;
//! - [`edits`]: the edits the model takes, and scripts of steps;
//! - [`fit`]: a design's patches as B-spline faces, its deviation map, and
//!   a design fitted to and measured against its reference;
//! - [`export`]: every export format (STEP, IGES, OBJ, STL, glTF);
//! - [`loop_mesh`]: the Loop mesh's OBJ and USD files;
//! - [`job`], on its own: long work off the editor's frame.

pub mod design;
pub mod edits;
pub mod export;
pub mod files;
pub mod fit;
pub mod job;
pub mod loop_mesh;

pub use design::document::Document;
pub use design::model::Scene;
pub use files::error::SceneError;
pub use files::format::SceneFile;
