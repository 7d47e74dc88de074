//! The scene file: its forms as read and written (version 1 and 2 in
//! [`mod@format`], version 3 in [`format_v3`]), its located errors
//! ([`error`]), where each patch sits in its text ([`patch_text`]), the
//! reference it names ([`reference_link`]), its specifications as the
//! kernel's types and back ([`spec_kernel`]), and reading and atomic writing
//! of files ([`io`]). Nothing here knows a scene in memory.

pub mod error;
pub mod format;
pub mod format_v3;
pub mod io;
pub mod patch_text;
pub mod reference_link;
pub mod spec_kernel;
