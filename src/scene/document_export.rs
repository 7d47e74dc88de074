//! Export of a design of several patches (docs/math.md §10, §11; docs/cad.md,
//! "Several patches"): [`export_document`] chooses the format by the file's
//! extension, as [`super::export::export_scene`] does for one patch, and
//! writes every patch (and, with the mirror on, every patch's reflection,
//! [`super::document_mirror`]) into one file, atomically and verified:
//!
//! - STEP: one `ADVANCED_FACE` per patch in one shell, each seam one
//!   `EDGE_CURVE` ([`super::step_shell`]), every patch sampled at one depth,
//!   raised until the fit meets the tolerance ([`super::document_fit`]);
//! - IGES: one entity 128 per patch, each fitted alone as the one-patch file
//!   is ([`super::iges::iges_faces_text`]);
//! - OBJ: one `o <name>` object per patch, its vertices row by row ([`super::obj_shell`]);
//! - glTF: one node and one mesh per patch, named for it ([`super::glb::glb_parts_bytes`]);
//! - STL: ASCII, one `solid <name>` per patch ([`super::stl_shell`]).
//!
//! A design of one patch is written exactly as today's one-patch export
//! writes its scene (a mirrored one as one face over both halves).

use super::cad::samples;
use super::document::Document;
use super::document_build::BuiltDocument;
use super::document_fit::{DocumentFit, FaceFit, built_to, fit_document};
use super::document_mirror::{mirror_plane, mirror_shell, mirrored, mirrored_names};
use super::error::SceneError;
use super::export::{
    ExportOptions, Exported, Format, export_scene, file_name, fit_refused, utc_now,
};
use super::glb::{GlbPart, glb_parts_bytes};
use super::io::write_atomic;
use super::step_shell::{MirrorFaces, write_fitted};
use super::{glb, iges, obj_shell, stl_shell};
use std::path::Path;
use streamline_kernel::nurbs::{FitOptions, ShellFace, ShellFit};
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;

/// How to export a document.
#[derive(Debug, Clone, Default)]
pub struct DocumentExportSettings {
    /// The depth of the mesh and the first sampling depth of the fit; the
    /// design's display depth when `None`.
    pub depth: Option<u32>,
    /// The fit of STEP and IGES files (tolerance, degree).
    pub fit: FitOptions,
    /// Analysis colours for glTF's `COLOR_0`: one list per patch (linear
    /// RGBA, one per vertex of its mesh at the depth); a reflected patch
    /// takes its original's.
    pub colors: Option<Vec<Vec<[f32; 4]>>>,
}

/// What [`export_document`] wrote.
#[derive(Debug, Clone)]
pub struct DocumentExported {
    /// The format.
    pub format: Format,
    /// The names of the patches written, in the file's order (the
    /// reflections `<name>-mirror` after the originals).
    pub patches: Vec<String>,
    /// The mesh depth, or for STEP and IGES the depth sampled.
    pub depth: u32,
    /// For STEP and IGES of several patches, the faces written (reflections included).
    pub faces: Vec<ShellFace>,
    /// For STEP and IGES of several patches, the fit of the originals.
    pub fit: Option<DocumentFit>,
    /// For a mirrored STEP shell, the faces `(i, N + i)` whose first
    /// streamline (in the mirror plane) is one edge.
    pub mirror_seams: Vec<(usize, usize)>,
    /// A design of one patch: what the one-patch export wrote.
    pub one: Option<Exported>,
}

/// A mesh turned over: triangles wound the other way, normals negated (a
/// reflected patch's mesh, docs/math.md §9, faces the way its original does).
pub fn turned(mut mesh: SurfaceMesh) -> SurfaceMesh {
    for t in mesh.indices.chunks_exact_mut(3) {
        t.swap(1, 2);
    }
    for n in &mut mesh.normals {
        *n = -*n;
    }
    mesh
}

/// Writes `doc` (built as `built`; built again when the export needs other
/// depths) to `path` in the format its extension names (module docs).
/// Nothing is written when the build, the fit or the write fails (the old
/// file is kept); the error names the file, and the patch where one is at fault.
pub fn export_document(
    doc: &Document,
    built: &BuiltDocument,
    path: &Path,
    settings: &DocumentExportSettings,
) -> Result<DocumentExported, SceneError> {
    let format = Format::of(path)?;
    let depth = settings.depth.unwrap_or(doc.display_depth);
    if let Some(scene) = doc.one_scene() {
        return export_one(doc, &scene, depth, path, settings, format);
    }
    if format.is_cad() {
        return export_faces(doc, built, depth, path, settings, format);
    }
    let b = built_to(doc, built, depth)
        .map_err(|e| SceneError::file(path, format!("{e}; nothing was written")))?;
    let all = mirrored(doc, &b);
    let names = mirrored_names(doc);
    let n = doc.patches.len();
    let meshes: Vec<SurfaceMesh> = all
        .patches
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let m = SurfaceMesh::from_points(&s.points[depth as usize]);
            if i < n { m } else { turned(m) }
        })
        .collect();
    for (name, m) in names.iter().zip(&meshes) {
        if m.positions.iter().any(|p| !p.is_finite()) {
            return Err(SceneError::file(
                path,
                format!("patch `{name}` has a non-finite point; nothing was written"),
            ));
        }
    }
    let named: Vec<(&str, &SurfaceMesh)> = names.iter().map(String::as_str).zip(&meshes).collect();
    let count = named.len();
    match format {
        Format::Obj => {
            let text = obj_shell::obj_meshes_text(&named);
            write_atomic(path, text.as_bytes(), |b| verify_obj(b, count))?;
        }
        Format::Stl => {
            let text = stl_shell::stl_solids_text(&named);
            write_atomic(path, text.as_bytes(), |b| stl_shell::verify(b, count))?;
        }
        Format::Glb => {
            let colors = settings.colors.as_ref();
            if let Some(c) = colors
                && (c.len() != n
                    || c.iter()
                        .zip(&meshes)
                        .any(|(c, m)| c.len() != m.positions.len()))
            {
                return Err(SceneError::file(
                    path,
                    "the analysis colours are not one per vertex of every patch; nothing was written",
                ));
            }
            let parts: Vec<GlbPart> = named
                .iter()
                .enumerate()
                .map(|(i, (name, mesh))| GlbPart {
                    name,
                    mesh,
                    colors: colors.map(|c| c[i % n].as_slice()),
                })
                .collect();
            let bytes = glb_parts_bytes(&parts)
                .map_err(|e| SceneError::file(path, format!("{e}; nothing was written")))?;
            write_atomic(path, &bytes, glb::verify)?;
        }
        Format::Step | Format::Iges => unreachable!("the CAD formats are fitted"),
    }
    Ok(DocumentExported {
        format,
        patches: names,
        depth,
        faces: Vec::new(),
        fit: None,
        mirror_seams: Vec::new(),
        one: None,
    })
}

/// The OBJ written has `objects` objects.
fn verify_obj(bytes: &[u8], objects: usize) -> Result<(), String> {
    let text = std::str::from_utf8(bytes).map_err(|_| "not UTF-8".to_string())?;
    let found = text.lines().filter(|l| l.starts_with("o ")).count();
    if found != objects {
        return Err(format!("{found} objects, not {objects}"));
    }
    Ok(())
}

/// A design of one patch, as the one-patch export writes its scene: the
/// mesh the editor shows at `depth` (details, tuning, both halves of a mirror).
fn export_one(
    doc: &Document,
    scene: &super::model::Scene,
    depth: u32,
    path: &Path,
    settings: &DocumentExportSettings,
    format: Format,
) -> Result<DocumentExported, SceneError> {
    let points = samples(scene, depth)
        .map_err(|e| SceneError::file(path, format!("{e}; nothing was written")))?
        .points;
    let mesh = SurfaceMesh::from_points(&points);
    let opts = ExportOptions {
        fit: settings.fit,
        colors: settings.colors.as_ref().and_then(|c| c.first().cloned()),
    };
    let out = export_scene(scene, &mesh, depth, path, &opts)?;
    Ok(DocumentExported {
        format,
        patches: vec![doc.patches[0].name.clone()],
        depth: out.fit.as_ref().map_or(depth, |f| f.depth),
        faces: Vec::new(),
        fit: None,
        mirror_seams: Vec::new(),
        one: Some(out),
    })
}

/// STEP (one shell) or IGES (one entity 128 each) of several patches.
fn export_faces(
    doc: &Document,
    built: &BuiltDocument,
    depth: u32,
    path: &Path,
    settings: &DocumentExportSettings,
    format: Format,
) -> Result<DocumentExported, SceneError> {
    let how = if format == Format::Step {
        FaceFit::Shell
    } else {
        FaceFit::Alone
    };
    let fit =
        fit_document(doc, built, depth, &settings.fit, how).map_err(|e| fit_refused(path, e))?;
    let names = mirrored_names(doc);
    let shell = ShellFit {
        faces: fit.faces.clone(),
        seams: fit.seams.clone(),
    };
    let (mut shell, shared) = match mirror_plane(doc) {
        Some(plane) => {
            let m = mirror_shell(&shell, &fit.grids, &plane);
            (m.shell, m.shared)
        }
        None => (shell, Vec::new()),
    };
    for (f, name) in shell.faces.iter_mut().zip(&names) {
        f.name.clone_from(name);
    }
    let mirror = doc.mirror.then_some(MirrorFaces {
        originals: doc.patches.len(),
        shared: &shared,
    });
    let mut mirror_seams = Vec::new();
    if format == Format::Step {
        write_fitted(path, &doc.name, &shell, mirror)?;
        mirror_seams = shared;
    } else {
        write_iges(path, &doc.name, &shell.faces)?;
    }
    Ok(DocumentExported {
        format,
        patches: names,
        depth: fit.depth,
        faces: shell.faces,
        fit: Some(fit),
        mirror_seams,
        one: None,
    })
}

/// The IGES file of `faces`, one entity 128 each, atomically and verified.
fn write_iges(path: &Path, name: &str, faces: &[ShellFace]) -> Result<(), SceneError> {
    let tol = faces
        .iter()
        .map(|f| f.tolerance)
        .fold(f64::INFINITY, f64::min);
    let (y, mo, d, h, mi, se) = utc_now();
    let stamp = format!("{y:04}{mo:02}{d:02}.{h:02}{mi:02}{se:02}");
    let file_name = file_name(path);
    let info = iges::IgesInfo {
        name,
        file_name: &file_name,
        resolution: (tol / 10.0).min(1e-6),
        timestamp: &stamp,
    };
    let surfaces: Vec<_> = faces.iter().map(|f| &f.surface).collect();
    let text = iges::iges_faces_text(&surfaces, &info);
    let n = faces.len();
    write_atomic(path, text.as_bytes(), |b| iges::verify_faces(b, n))
}
