//! The surfaces designers bring as *references*, the shapes a streamline
//! design is fitted to: the B-spline faces of STEP and IGES files, as the
//! kernel's [`NurbsSurface`] in metres.
//!
//! [`read`] takes a `.step`/`.stp`/`.p21` or `.igs`/`.iges` file (or an
//! `.obj` grid of points, or an `.obj` or `.stl` triangle mesh, [`mesh`],
//! for display and measuring only) and returns its faces in file order, each with a [`FaceInfo`] (kind,
//! degrees, pole counts, closed and periodic flags, whether it is trimmed,
//! its area and box) and, for a B-spline face, its surface
//! ([`ReferenceFile::surface`]). STEP text is parsed by the `ruststep`
//! crate and the entities mapped here (`step`); IGES is read
//! by a small fixed-column reader of its own (`iges`). Every error is a
//! [`ReferenceError`] naming the file, and the line and column at fault
//! where there is one; no input makes the reader panic, and the limits of
//! [`error`] bound what a file can make it allocate.

pub mod error;
mod geom;
pub mod grid;
mod iges;
pub mod mesh;
mod step;

pub use error::ReferenceError;

use serde::Serialize;
use std::path::{Path, PathBuf};
use streamline_kernel::fit::TriangleMesh;
use streamline_kernel::nurbs::rational::NurbsSurface;

/// The exchange format of a reference file, from its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// STEP, ISO 10303-21 clear text (`.step`, `.stp`, `.p21`).
    Step,
    /// IGES, fixed-format ASCII (`.igs`, `.iges`).
    Iges,
    /// A regular grid of points: an OBJ of quadrilateral faces (`.obj`),
    /// made a surface by the B-spline fit through its points ([`grid`]);
    /// other OBJ faces are a triangle mesh ([`mesh`]).
    Obj,
    /// A triangle mesh, binary or ASCII STL (`.stl`), for display and
    /// measuring only ([`mesh`]).
    Stl,
}

impl Format {
    /// The extensions read, as an error lists them.
    pub const EXTENSIONS: &'static str = ".step, .stp, .p21 (STEP), .igs, .iges (IGES), .obj (a grid of points or a mesh) or .stl (a mesh)";

    /// The format of `path` from its extension, case-insensitive.
    pub fn from_path(path: &Path) -> Result<Format, ReferenceError> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_lowercase())
            .unwrap_or_default();
        match ext.as_str() {
            "step" | "stp" | "p21" => Ok(Format::Step),
            "igs" | "iges" => Ok(Format::Iges),
            "obj" => Ok(Format::Obj),
            "stl" => Ok(Format::Stl),
            _ => Err(ReferenceError::whole(
                path,
                format!(
                    "{} is not a CAD reference format read here; name a {} file",
                    if ext.is_empty() {
                        "a file without an extension".to_string()
                    } else {
                        format!("the extension .{ext}")
                    },
                    Self::EXTENSIONS
                ),
            )),
        }
    }
}

/// What a face's surface is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SurfaceKind {
    /// A non-rational B-spline surface.
    BSpline,
    /// A rational B-spline surface (weights not all equal).
    Rational,
    /// A plane.
    Plane,
    /// Any other surface (a cylinder, a surface of revolution, …): not read.
    Other,
    /// A B-spline surface fitted through a regular grid of points.
    Grid,
    /// A triangle mesh (OBJ or STL): displayed and measured, not fitted.
    Mesh,
}

impl SurfaceKind {
    /// How messages name it.
    pub fn describe(self) -> &'static str {
        match self {
            SurfaceKind::BSpline => "a B-spline surface",
            SurfaceKind::Rational => "a rational B-spline surface",
            SurfaceKind::Plane => "a plane",
            SurfaceKind::Other => "a surface of another kind",
            SurfaceKind::Grid => "a surface through a grid of points",
            SurfaceKind::Mesh => "a triangle mesh",
        }
    }
}

/// What a face is, as the reference picker lists it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FaceInfo {
    /// Its position in the file's faces (0-based, file order).
    pub index: usize,
    /// Its surface's kind.
    pub kind: SurfaceKind,
    /// The surface's entity: `#12 B_SPLINE_SURFACE_WITH_KNOTS` (STEP; a
    /// complex instance lists its records in parentheses) or `DE 5 (128)`
    /// (IGES: directory entry and entity type).
    pub entity: String,
    /// The line of the surface's entity (STEP: its `#N =`; IGES: its first
    /// parameter line).
    pub line: usize,
    /// B-spline degrees `[in u, in v]`.
    pub degrees: Option<[usize; 2]>,
    /// B-spline pole counts `[in u, in v]`.
    pub poles: Option<[usize; 2]>,
    /// Closed in `[u, v]`, as the file flags it.
    pub closed: [bool; 2],
    /// Periodic in `[u, v]`: the knot vector is not clamped (its first or
    /// last `degree + 1` knots differ).
    pub periodic: [bool; 2],
    /// Whether the face's boundary is not the surface's own four sides
    /// (see the STEP and IGES modules for the rule); always true for a
    /// face that is not a B-spline.
    pub trimmed: bool,
    /// Area in m²: of the whole B-spline surface (Gauss–Legendre of
    /// `|S_u × S_v|` on every knot span, trimming ignored), of a STEP
    /// plane's bounding polygon; 0 when unknown.
    pub area: f64,
    /// Axis-aligned box in metres `[min, max]`, from evaluated points (a
    /// STEP plane's: of its vertices; a mesh's: of its triangles'
    /// corners); `None` when unknown.
    pub bbox: Option<[[f64; 3]; 2]>,
    /// A mesh's triangle count (absent for a surface).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub triangles: Option<usize>,
    /// A mesh's vertex count (absent for a surface).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vertices: Option<usize>,
}

/// One face: its description and, for a B-spline, its surface in metres,
/// or for a triangle mesh its triangles.
#[derive(Debug, Clone)]
pub struct Face {
    pub info: FaceInfo,
    pub surface: Option<NurbsSurface>,
    /// The triangles of a mesh reference ([`SurfaceKind::Mesh`]).
    pub mesh: Option<TriangleMesh>,
    /// For an OBJ mesh of quadrilaterals, why they are not one grid: the
    /// line at fault (0 for none) and the reason.
    pub not_grid: Option<(usize, String)>,
}

/// A reference file's faces.
#[derive(Debug, Clone)]
pub struct ReferenceFile {
    /// The file as it was named.
    pub path: PathBuf,
    pub format: Format,
    /// The file's length unit: "millimetre", "metre", "inch", …
    pub unit: String,
    /// Metres per file unit (surfaces are already scaled by it).
    pub metres_per_unit: f64,
    /// The faces, in file order.
    pub faces: Vec<Face>,
}

/// A face as the format readers give it, before its common description.
pub(crate) struct FaceData {
    pub kind: SurfaceKind,
    pub entity: String,
    pub line: usize,
    pub surface: Option<NurbsSurface>,
    pub mesh: Option<TriangleMesh>,
    pub not_grid: Option<(usize, String)>,
    pub closed: [bool; 2],
    pub trimmed: bool,
    pub area: f64,
    pub bbox: Option<[[f64; 3]; 2]>,
}

/// Whether the knot vector of degree `p` is clamped (first and last `p + 1`
/// knots equal).
fn clamped(k: &[f64], p: usize) -> bool {
    if k.len() < 2 * p + 2 {
        return false;
    }
    let (a, b) = (k[0], k[k.len() - 1]);
    k[..=p].iter().all(|&x| x == a) && k[k.len() - p - 1..].iter().all(|&x| x == b)
}

impl FaceData {
    fn finish(self, index: usize) -> Face {
        let s = self.surface.as_ref();
        let degrees = s.map(|s| {
            let (p, q) = s.degrees();
            [p, q]
        });
        let poles = s.map(|s| {
            let (a, b) = s.pole_counts();
            [a, b]
        });
        let periodic = s.map_or([false; 2], |s| {
            let (p, q) = s.degrees();
            [!clamped(s.knots_u(), p), !clamped(s.knots_v(), q)]
        });
        Face {
            info: FaceInfo {
                index,
                kind: self.kind,
                entity: self.entity,
                line: self.line,
                degrees,
                poles,
                closed: self.closed,
                periodic,
                trimmed: self.trimmed,
                area: self.area,
                bbox: self.bbox,
                triangles: self.mesh.as_ref().map(|m| m.triangles().len()),
                vertices: self.mesh.as_ref().map(|m| m.positions().len()),
            },
            surface: self.surface,
            mesh: self.mesh,
            not_grid: self.not_grid,
        }
    }
}

/// Reads a reference file: its format from the extension, its faces in file
/// order, every B-spline face's surface in metres.
pub fn read(path: &Path) -> Result<ReferenceFile, ReferenceError> {
    let format = Format::from_path(path)?;
    let bytes = error::read_file(path)?;
    parse(path, format, bytes)
}

/// Reads the bytes of a reference file of `format`; `path` names it in
/// errors (what [`read`] does once the file is read; the fuzz targets call
/// it on bytes that were never a file).
pub fn parse(path: &Path, format: Format, bytes: Vec<u8>) -> Result<ReferenceFile, ReferenceError> {
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(ReferenceError::whole(
            path,
            "the file is empty; export the reference again from the CAD system",
        ));
    }
    let (unit, metres_per_unit, faces) = match format {
        Format::Step => {
            let text = match String::from_utf8(bytes) {
                Ok(t) => t,
                Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
            };
            let f = step::read(path, text)?;
            (f.unit, f.metres_per_unit, f.faces)
        }
        Format::Iges => {
            let f = iges::read(path, &bytes)?;
            (f.unit, f.metres_per_unit, f.faces)
        }
        Format::Obj => {
            let f = grid::read(path, &bytes)?;
            (f.unit, f.metres_per_unit, f.faces)
        }
        Format::Stl => (
            "metre".to_string(),
            1.0,
            vec![mesh::read_stl(path, &bytes)?],
        ),
    };
    Ok(ReferenceFile {
        path: path.to_path_buf(),
        format,
        unit,
        metres_per_unit,
        faces: faces
            .into_iter()
            .enumerate()
            .map(|(i, f)| f.finish(i))
            .collect(),
    })
}

/// "2 faces (0 and 1)", as errors count them.
fn count_faces(n: usize) -> String {
    match n {
        0 => "no face".into(),
        1 => "1 face (0)".into(),
        2 => "2 faces (0 and 1)".into(),
        n => format!("{n} faces (0 to {})", n - 1),
    }
}

impl ReferenceFile {
    /// Face `face`, refused for an index past the end.
    pub fn face(&self, face: usize) -> Result<&Face, ReferenceError> {
        self.faces.get(face).ok_or_else(|| {
            ReferenceError::whole(
                &self.path,
                format!(
                    "there is no face {face}: the file has {}; choose one with --face",
                    count_faces(self.faces.len())
                ),
            )
        })
    }

    /// The triangles of face `face` when it is a mesh (`None` for a
    /// surface), refused for an index past the end.
    pub fn mesh(&self, face: usize) -> Result<Option<&TriangleMesh>, ReferenceError> {
        Ok(self.face(face)?.mesh.as_ref())
    }

    /// The surface of face `face`, refused for an index past the end, for
    /// a triangle mesh (for display and measuring only) and for a face
    /// that is not a B-spline.
    pub fn surface(&self, face: usize) -> Result<&NurbsSurface, ReferenceError> {
        let f = self.face(face)?;
        if let Some(s) = &f.surface {
            return Ok(s);
        }
        if f.mesh.is_some() {
            let (line, why) = match &f.not_grid {
                Some((l, why)) => (
                    if *l > 0 { *l } else { f.info.line },
                    format!(", not one grid of quadrilaterals ({why})"),
                ),
                None => (f.info.line, String::new()),
            };
            let msg = format!(
                "face {face} is a triangle mesh ({}){why}: a mesh is for display and measuring only, with no parameters for the streamlines to follow; fit a STEP or IGES face or an OBJ quad grid, and keep the mesh to measure against",
                f.info.entity
            );
            return Err(if line > 0 {
                ReferenceError::at(&self.path, line, 1, msg)
            } else {
                ReferenceError::whole(&self.path, msg)
            });
        }
        let bsplines: Vec<String> = self
            .faces
            .iter()
            .filter(|f| f.surface.is_some())
            .map(|f| f.info.index.to_string())
            .collect();
        let choose = if bsplines.is_empty() {
            "the file has no B-spline face: export the reference's surfaces as B-splines (NURBS)"
                .to_string()
        } else {
            format!(
                "choose a B-spline face with --face ({} {})",
                if bsplines.len() == 1 { "face" } else { "faces" },
                bsplines.join(", ")
            )
        };
        Err(ReferenceError::at(
            &self.path,
            f.info.line,
            1,
            format!(
                "face {face} ({}) is {}, not a B-spline surface; {choose}",
                f.info.entity,
                f.info.kind.describe()
            ),
        ))
    }

    /// Every face's description.
    pub fn infos(&self) -> Vec<FaceInfo> {
        self.faces.iter().map(|f| f.info.clone()).collect()
    }
}
