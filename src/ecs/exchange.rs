//! Settings and outcome of exports (docs/math.md §10, docs/cad.md): the fit's
//! degree and tolerance for STEP and IGES, the analysis colours a glTF
//! export carries, and what the last export wrote (for the command line's
//! report and the editor's File section).

use crate::scene::export::document::DocumentExported;
use bevy::prelude::*;
use std::path::PathBuf;
use streamline_kernel::nurbs::FitOptions;

/// How `Edit::Export` writes.
#[derive(Resource, Debug, Clone, Default)]
pub struct ExportSettings {
    /// Degree and tolerance of the B-spline fit (STEP, IGES).
    pub fit: FitOptions,
    /// Linear RGBA per mesh vertex for glTF's `COLOR_0` (set while an
    /// analysis map is shown), `None` otherwise.
    pub colors: Option<Vec<[f32; 4]>>,
}

/// What the last successful export wrote.
#[derive(Resource, Debug, Clone, Default)]
pub struct LastExport {
    /// The file and what was written: its format, patches and, for STEP
    /// and IGES, every face with its fit's figures.
    pub written: Option<(PathBuf, DocumentExported)>,
}
