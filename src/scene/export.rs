//! Export: the triangle mesh as Wavefront OBJ with normals (text), binary
//! STL or binary glTF ([`super::glb`]), and the surface as one B-spline
//! surface fitted to it (docs/math.md §10) in STEP ([`super::step`]) or IGES
//! ([`super::iges`]). Every file is written atomically and verified
//! ([`super::io::write_atomic`]); a refused export writes nothing and keeps
//! the old file.

use super::cad::{SceneFit, fit_scene};
use super::error::SceneError;
use super::io::write_atomic;
use super::model::Scene;
use super::{glb, iges, step};
use std::fmt::Write as _;
use std::path::Path;
use streamline_kernel::nurbs::FitOptions;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;

/// The formats [`export`] writes, chosen by the file extension.
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

/// OBJ text: `v`, `vn` and `f a//a b//b c//c` lines.
pub fn obj_text(mesh: &SurfaceMesh, name: &str) -> String {
    let mut s = String::with_capacity(mesh.positions.len() * 80 + mesh.indices.len() * 12);
    let _ = writeln!(s, "# Streamline Studio surface\no {}", sanitize(name));
    for p in &mesh.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for n in &mesh.normals {
        let _ = writeln!(s, "vn {} {} {}", n.x, n.y, n.z);
    }
    for t in mesh.indices.chunks_exact(3) {
        let (a, b, c) = (t[0] + 1, t[1] + 1, t[2] + 1);
        let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
    }
    s
}

pub(super) fn sanitize(name: &str) -> String {
    let n: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if n.is_empty() { "surface".into() } else { n }
}

/// Binary STL bytes: an 80-byte header, the triangle count, then per triangle
/// its face normal and three corners (little-endian `f32`) and a zero `u16`.
pub fn stl_bytes(mesh: &SurfaceMesh) -> Vec<u8> {
    let tris = mesh.indices.len() / 3;
    let mut out = Vec::with_capacity(84 + tris * 50);
    let mut header = [b' '; 80];
    let title = b"Streamline Studio binary STL";
    header[..title.len()].copy_from_slice(title);
    out.extend_from_slice(&header);
    out.extend_from_slice(&(tris as u32).to_le_bytes());
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|i| mesh.positions[t[i] as usize]);
        let n = (b - a).cross(c - a).try_normalize().unwrap_or_default();
        for v in [n, a, b, c] {
            for x in [v.x, v.y, v.z] {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// Writes `mesh` to `path` in the mesh format its extension names (OBJ,
/// STL, glTF without colours); STEP and IGES need the scene
/// ([`export_scene`]).
pub fn export(mesh: &SurfaceMesh, name: &str, path: &Path) -> Result<Format, SceneError> {
    let format = Format::of(path)?;
    if format.is_cad() {
        return Err(SceneError::file(
            path,
            "STEP and IGES hold the fitted B-spline surface, which needs the scene; export from a scene (build --export, a script's Export or the editor)",
        ));
    }
    write_mesh(mesh, name, path, format, None)?;
    Ok(format)
}

fn write_mesh(
    mesh: &SurfaceMesh,
    name: &str,
    path: &Path,
    format: Format,
    colors: Option<&[[f32; 4]]>,
) -> Result<(), SceneError> {
    if mesh.positions.iter().any(|p| !p.is_finite()) {
        return Err(SceneError::file(
            path,
            "the mesh has a non-finite point; nothing was written",
        ));
    }
    let bytes = match format {
        Format::Obj => obj_text(mesh, name).into_bytes(),
        Format::Stl => stl_bytes(mesh),
        Format::Glb => glb::glb_bytes(mesh, name, colors)
            .map_err(|e| SceneError::file(path, format!("{e}; nothing was written")))?,
        Format::Step | Format::Iges => unreachable!("mesh formats only"),
    };
    let verify = |b: &[u8]| match format {
        Format::Glb => glb::verify(b),
        _ => Ok(()),
    };
    write_atomic(path, &bytes, verify)
}

/// A check of written bytes.
type Verify = fn(&[u8]) -> Result<(), String>;

/// How to export a scene.
#[derive(Debug, Clone, Default)]
pub struct ExportOptions {
    /// The fit of STEP and IGES files.
    pub fit: FitOptions,
    /// Analysis colours (linear RGBA, one per mesh vertex) for glTF's `COLOR_0`.
    pub colors: Option<Vec<[f32; 4]>>,
}

/// What an export wrote.
#[derive(Debug, Clone)]
pub struct Exported {
    /// The format.
    pub format: Format,
    /// For STEP and IGES, the fit written.
    pub fit: Option<SceneFit>,
}

/// Writes the scene to `path` in the format its extension names: the mesh
/// `mesh` (the scene built at `depth`) for OBJ, STL and glTF, the B-spline
/// surface fitted at `depth` for STEP and IGES. Nothing is written when
/// the fit or the write fails (the old file is kept).
pub fn export_scene(
    scene: &Scene,
    mesh: &SurfaceMesh,
    depth: u32,
    path: &Path,
    opts: &ExportOptions,
) -> Result<Exported, SceneError> {
    let format = Format::of(path)?;
    if !format.is_cad() {
        write_mesh(mesh, &scene.name, path, format, opts.colors.as_deref())?;
        return Ok(Exported { format, fit: None });
    }
    let fitted = fit_scene(scene, depth, &opts.fit).map_err(|e| fit_refused(path, e))?;
    let file_name = file_name(path);
    let surface = &fitted.fit.surface;
    // the distance uncertainty: a micron, or a tenth of a tighter tolerance
    let uncertainty = (fitted.fit.report.tolerance / 10.0).min(1e-6);
    let (y, mo, d, h, mi, se) = utc_now();
    let (bytes, verify): (Vec<u8>, Verify) = match format {
        Format::Step => {
            let stamp = format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{se:02}");
            let info = step::StepInfo {
                name: &scene.name,
                file_name: &file_name,
                uncertainty,
                timestamp: &stamp,
            };
            (step::step_text(surface, &info).into_bytes(), step::verify)
        }
        _ => {
            let stamp = format!("{y:04}{mo:02}{d:02}.{h:02}{mi:02}{se:02}");
            let info = iges::IgesInfo {
                name: &scene.name,
                file_name: &file_name,
                resolution: uncertainty,
                timestamp: &stamp,
            };
            (iges::iges_text(surface, &info).into_bytes(), iges::verify)
        }
    };
    write_atomic(path, &bytes, verify)?;
    Ok(Exported {
        format,
        fit: Some(fitted),
    })
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
