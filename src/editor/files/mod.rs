//! The file dialogs: new, open, save, export and recent files with the
//! unsaved-changes prompt (`open_save`, with what a file is picked for,
//! `path_action`, the editor's own files, `editor_dirs`, and the prompts,
//! `dialogs`), the File ▸ New ▸ New design… dialog (`new_design`), File ▸
//! Import surface… (`import`, its state `import_form`: a design fitted to
//! a STEP, IGES or OBJ face, on a thread of its own: `fit_job`), File ▸
//! Reference… (`reference`: a reference attached without a fit), the faces
//! of a file as both list them (`face_list`), and the file browser every
//! file is picked in (`file_browser`). Autosave and recovery
//! read the screenshot run's request, which stands above the panels, so
//! `autosave.rs` stands beside the editor's `mod.rs`, above every room.

pub(super) mod dialogs;
mod editor_dirs;
mod face_list;
pub(super) mod file_browser;
pub mod fit_job;
pub mod import;
mod import_form;
pub mod new_design;
pub mod open_save;
mod path_action;
pub mod reference;
