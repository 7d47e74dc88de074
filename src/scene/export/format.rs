//! Export's formats and the mesh files (docs/math.md §10; docs/cad.md):
//! [`Format`], chosen by the file's extension, and [`write_meshes`], which
//! writes the triangle meshes of a design's patches (one part for a design
//! of one patch) as Wavefront OBJ ([`super::obj_shell`]), STL
//! ([`super::stl_shell`]) or binary glTF ([`super::glb`]). The whole export,
//! the fitted B-spline faces of STEP and IGES included, is
//! [`super::document::export_document`]. Every file is written
//! atomically and verified ([`crate::scene::files::io::write_atomic`]); a refused export
//! writes nothing and keeps the old file.

use super::glb::{self, GlbPart};
use super::{obj_shell, stl_shell};
use crate::scene::files::error::SceneError;
use crate::scene::files::io::write_atomic;
use std::path::Path;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;

/// The formats an export writes, chosen by the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `.obj`
    Obj,
    /// `.stl` (binary)
    Stl,
    /// `.glb` (binary glTF 2.0)
    Glb,
    /// `.step`, `.stp` (ISO 10303-21, AP214)
    Step,
    /// `.igs`, `.iges` (IGES 5.3)
    Iges,
}

impl Format {
    /// Every format, in the order the help and the menus list them.
    pub const ALL: [Format; 5] = [
        Format::Obj,
        Format::Stl,
        Format::Glb,
        Format::Step,
        Format::Iges,
    ];

    /// The file extensions that choose it, the usual one first.
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            Format::Obj => &["obj"],
            Format::Stl => &["stl"],
            Format::Glb => &["glb"],
            Format::Step => &["step", "stp"],
            Format::Iges => &["igs", "iges"],
        }
    }

    /// From a path's extension.
    pub fn of(path: &Path) -> Result<Self, SceneError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default();
        Self::ALL
            .into_iter()
            .find(|f| f.extensions().contains(&ext.as_str()))
            .ok_or_else(|| {
                SceneError::file(
                    path,
                    "unknown export format; name the file .obj, .stl, .glb, .step/.stp or .igs/.iges",
                )
            })
    }

    /// Whether the format holds the fitted B-spline surface (STEP, IGES).
    pub fn is_cad(self) -> bool {
        matches!(self, Format::Step | Format::Iges)
    }

    /// Its usual name.
    pub fn name(self) -> &'static str {
        match self {
            Format::Obj => "OBJ",
            Format::Stl => "STL",
            Format::Glb => "glTF",
            Format::Step => "STEP",
            Format::Iges => "IGES",
        }
    }
}

/// Writes `parts` (a patch each, in the file's order; its name, mesh and,
/// for glTF's `COLOR_0`, analysis colours) to `path` in the mesh format
/// `format`: OBJ with one `o <name>` object a part, STL binary for one part
/// and ASCII with one `solid <name>` a part for several (binary STL has no
/// names), glTF with one node and one mesh a part. STEP and IGES hold the
/// fitted surface ([`super::document::export_document`]). Nothing is
/// written when a point is not finite or the write fails.
pub fn write_meshes(path: &Path, format: Format, parts: &[GlbPart]) -> Result<(), SceneError> {
    for p in parts {
        if p.mesh.positions.iter().any(|x| !x.is_finite()) {
            let what = match parts {
                [_] => "the mesh".to_string(),
                _ => format!("patch `{}`", p.name),
            };
            return Err(SceneError::file(
                path,
                format!("{what} has a non-finite point; nothing was written"),
            ));
        }
    }
    let named: Vec<(&str, &SurfaceMesh)> = parts.iter().map(|p| (p.name, p.mesh)).collect();
    let count = parts.len();
    match format {
        Format::Obj => {
            let text = obj_shell::obj_meshes_text(&named);
            write_atomic(path, text.as_bytes(), |b| obj_shell::verify(b, count))
        }
        Format::Stl => match named.as_slice() {
            [(_, mesh)] => write_atomic(path, &stl_shell::stl_bytes(mesh), |_| Ok(())),
            _ => {
                let text = stl_shell::stl_solids_text(&named);
                write_atomic(path, text.as_bytes(), |b| stl_shell::verify(b, count))
            }
        },
        Format::Glb => {
            let bytes = glb::glb_parts_bytes(parts)
                .map_err(|e| SceneError::file(path, format!("{e}; nothing was written")))?;
            write_atomic(path, &bytes, glb::verify)
        }
        Format::Step | Format::Iges => Err(SceneError::file(
            path,
            "STEP and IGES hold the fitted B-spline surface, which needs the scene; export from a scene (build --export, a script's Export or the editor)",
        )),
    }
}

/// Now in UTC: year, month, day, hour, minute, second (days to the civil
/// calendar by Howard Hinnant's `civil_from_days`).
pub(super) fn utc_now() -> (i64, u32, u32, u32, u32, u32) {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    let rem = rem as u32;
    (y, m, d, rem / 3600, rem / 60 % 60, rem % 60)
}

/// A CAD export refused by its fit: the fit's reason, and that the previous
/// file is kept.
pub(super) fn fit_refused(path: &Path, e: impl std::fmt::Display) -> SceneError {
    SceneError::file(
        path,
        format!("{e}; nothing was written (the previous file is kept)"),
    )
}

/// The last component of `path`, as written into a file's header.
pub(super) fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}
