//! The exports of a design: the format chosen by the file's extension and
//! the mesh files ([`mod@format`]), the whole export ([`document`]), and one
//! writer per format: STEP ([`step`], [`step_shell`]), IGES ([`iges`]),
//! OBJ ([`obj_shell`]), STL ([`stl_shell`]), binary glTF ([`glb`]), with
//! the names ([`cad_text`]) and numbers ([`numbers`]) of the CAD files.

pub mod cad_text;
pub mod document;
pub mod format;
pub mod glb;
pub mod iges;
pub mod numbers;
pub mod obj_shell;
pub mod step;
pub mod step_shell;
pub mod stl_shell;
