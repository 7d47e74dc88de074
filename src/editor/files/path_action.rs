//! What a file is picked for in the file browser ([`PathAction`]: its
//! title, its filter, whether it opens or writes).

use crate::scene::export::format::Format;

/// What a file is picked for (in the file browser, `file_browser.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathAction {
    /// Open a scene.
    Open,
    /// Save the scene under a new name.
    SaveAs,
    /// Export the surface (`Edit::Export`; the extension picks the format).
    Export(Format),
    /// Play a script's edits into the scene.
    RunScript,
    /// Open a triangle mesh in the Loop mesh panel.
    OpenMesh,
    /// Write the Loop mesh panel's surface (OBJ).
    ExportMeshSurface,
    /// Write the Loop mesh panel's control mesh (OBJ).
    ExportMeshControl,
    /// Write the Loop mesh panel's control mesh as USD.
    ExportMeshUsd,
    /// Fit a design to a face of a STEP or IGES file or an OBJ grid of
    /// points (File ▸ Import surface…).
    ImportSurface,
    /// Attach a reference to the design without fitting (File ▸
    /// Reference…, `reference.rs`).
    AttachReference,
}

impl PathAction {
    /// The browser's title.
    pub fn title(self) -> String {
        match self {
            PathAction::Open => "Open scene".into(),
            PathAction::SaveAs => "Save scene as".into(),
            PathAction::Export(f) => format!("Export {}", f.name()),
            PathAction::RunScript => "Run script".into(),
            PathAction::OpenMesh => "Open a triangle mesh (Loop mesh)".into(),
            PathAction::ExportMeshSurface => "Export the Loop surface (OBJ)".into(),
            PathAction::ExportMeshControl => "Export the Loop control mesh (OBJ)".into(),
            PathAction::ExportMeshUsd => "Export the Loop control mesh (USD)".into(),
            PathAction::ImportSurface => "Import a surface (STEP, IGES or a grid of points)".into(),
            PathAction::AttachReference => {
                "Reference (STEP, IGES or a grid of points), to compare the design with".into()
            }
        }
    }

    /// The file filter's name and the extensions it shows (the first one is
    /// what a save adds).
    pub fn filter(self) -> (&'static str, &'static [&'static str]) {
        match self {
            PathAction::Open | PathAction::SaveAs | PathAction::RunScript => {
                ("RON files (.ron)", &["ron"])
            }
            PathAction::Export(Format::Obj)
            | PathAction::OpenMesh
            | PathAction::ExportMeshSurface
            | PathAction::ExportMeshControl => ("OBJ meshes (.obj)", &["obj"]),
            PathAction::Export(Format::Stl) => ("STL meshes (.stl)", &["stl"]),
            PathAction::Export(Format::Glb) => ("binary glTF (.glb)", &["glb"]),
            PathAction::Export(Format::Step) => ("STEP (.step, .stp)", &["step", "stp"]),
            PathAction::Export(Format::Iges) => ("IGES (.igs, .iges)", &["igs", "iges"]),
            PathAction::ExportMeshUsd => ("USD text (.usda)", &["usda"]),
            PathAction::ImportSurface => (
                "Surfaces (.step, .stp, .p21, .igs, .iges, .obj)",
                &["step", "stp", "p21", "igs", "iges", "obj"],
            ),
            PathAction::AttachReference => (
                "Surfaces and meshes (.step, .stp, .p21, .igs, .iges, .obj, .stl)",
                &["step", "stp", "p21", "igs", "iges", "obj", "stl"],
            ),
        }
    }

    /// Whether it picks an existing file (else it names one to write).
    pub fn opens(self) -> bool {
        matches!(
            self,
            PathAction::Open
                | PathAction::RunScript
                | PathAction::OpenMesh
                | PathAction::ImportSurface
                | PathAction::AttachReference
        )
    }
}
