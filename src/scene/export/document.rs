//! Export of a design (docs/math.md §10, §11; docs/cad.md, "Several
//! patches"): [`export_document`] chooses the format by the file's
//! extension and writes every patch (and, with the mirror on, every patch's
//! reflection, [`crate::scene::design::document_mirror`]) into one file, atomically and
//! verified, through one writer per format:
//!
//! - STEP: one `ADVANCED_FACE` per patch in one shell, each seam one
//!   `EDGE_CURVE` ([`super::step_shell`]), every patch sampled at one depth,
//!   raised until the fit meets the tolerance ([`crate::scene::fit::document`]);
//! - IGES: one entity 128 per patch, the STEP shell's faces ([`super::iges`]);
//! - OBJ: one `o <name>` object per patch, its vertices row by row ([`super::obj_shell`]);
//! - glTF: one node and one mesh per patch, named for it ([`super::glb`]);
//! - STL: binary for one patch, ASCII with one `solid <name>` per patch
//!   for several ([`super::stl_shell`]).
//!
//! A design of one patch is the case of one part: its surface as shown
//! ([`crate::scene::fit::surface::shown_document`]: a mirrored one as one surface over both
//! halves), named for the design, its face fitted alone
//! ([`crate::scene::fit::surface::fit_scene`]).

use super::format::{Format, file_name, fit_refused, utc_now, write_meshes};
use super::glb::GlbPart;
use super::iges;
use super::step_shell::{MirrorFaces, write_fitted};
use crate::scene::design::document::Document;
use crate::scene::design::document_build::BuiltDocument;
use crate::scene::design::document_mirror::{mirror_plane, mirror_shell, mirrored, mirrored_names};
use crate::scene::design::model::Scene;
use crate::scene::files::error::SceneError;
use crate::scene::files::io::write_atomic;
use crate::scene::fit::document::{DocumentFit, FaceFit, built_to, fit_document};
use crate::scene::fit::surface::{fit_scene, shown_document};
use std::borrow::Cow;
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
    /// For STEP and IGES, the faces written, in the file's order: one per
    /// patch (reflections included), each with its surface, deviation and
    /// tolerance; a design of one patch writes one face. Empty for a mesh.
    pub faces: Vec<ShellFace>,
    /// For STEP and IGES, the seconds the fit took (the builds not
    /// counted); 0 for a mesh.
    pub seconds: f64,
    /// For STEP and IGES of several patches, the fit of the originals with
    /// the points each face was fitted to and checked at.
    pub fit: Option<DocumentFit>,
    /// For a mirrored STEP shell, the faces `(i, N + i)` whose first
    /// streamline (in the mirror plane) is one edge.
    pub mirror_seams: Vec<(usize, usize)>,
}

impl DocumentExported {
    /// One line per face written by a STEP or IGES export: its poles,
    /// degree and largest deviation within its tolerance, named when there
    /// are several; none for a mesh.
    pub fn face_lines(&self) -> Vec<String> {
        (self.faces.iter())
            .map(|f| {
                let (p, q) = f.surface.degree();
                let (nu, nv) = f.surface.pole_counts();
                let named = match self.faces.len() {
                    1 => String::new(),
                    _ => format!("`{}` ", f.name),
                };
                format!(
                    "{named}{nu}x{nv} poles, degree {p}x{q}, largest deviation {:.2e} <= {:.2e}",
                    f.deviation.max, f.tolerance
                )
            })
            .collect()
    }

    /// What the fit of a STEP or IGES export made, for the designer: the
    /// depth sampled, each face's line ([`Self::face_lines`]) and the time;
    /// `None` for a mesh.
    pub fn fit_summary(&self) -> Option<String> {
        let faces = self.face_lines();
        (!faces.is_empty()).then(|| {
            format!(
                "sampled at depth {}, {}; {:.1} ms",
                self.depth,
                faces.join("; "),
                self.seconds * 1e3
            )
        })
    }
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
    let one = doc.one_scene();
    if format.is_cad() {
        return match &one {
            Some(scene) => export_face(doc, scene, depth, path, settings, format),
            None => export_faces(doc, built, depth, path, settings, format),
        };
    }
    let unwritten =
        |e: &dyn std::fmt::Display| SceneError::file(path, format!("{e}; nothing was written"));
    let build = || built_to(doc, built, depth).map_err(|e| unwritten(&e));
    let (all, names) = match &one {
        // the surface shown: both halves of a mirror as one, named for the design
        Some(scene) if doc.mirror => {
            let shown = shown_document(scene).map_err(|e| unwritten(&e))?;
            let b = shown.build(depth).map_err(|e| unwritten(&e))?;
            (Cow::Owned(b), vec![doc.name.clone()])
        }
        Some(_) => (build()?, vec![doc.name.clone()]),
        None => (
            Cow::Owned(mirrored(doc, build()?.as_ref())),
            mirrored_names(doc),
        ),
    };
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
    let colors = settings.colors.as_ref().filter(|_| format == Format::Glb);
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
    let parts: Vec<GlbPart> = names
        .iter()
        .zip(&meshes)
        .enumerate()
        .map(|(i, (name, mesh))| GlbPart {
            name,
            mesh,
            colors: colors.map(|c| c[i % n].as_slice()),
        })
        .collect();
    write_meshes(path, format, &parts)?;
    let patches = match one {
        Some(_) => vec![doc.patches[0].name.clone()],
        None => names,
    };
    Ok(DocumentExported {
        format,
        patches,
        depth,
        faces: Vec::new(),
        seconds: 0.0,
        fit: None,
        mirror_seams: Vec::new(),
    })
}

/// STEP or IGES of a design of one patch: its surface as shown, fitted
/// alone ([`fit_scene`]) and written as a shell of one face, or one entity
/// 128, named for the design.
fn export_face(
    doc: &Document,
    scene: &Scene,
    depth: u32,
    path: &Path,
    settings: &DocumentExportSettings,
    format: Format,
) -> Result<DocumentExported, SceneError> {
    let fit = fit_scene(scene, depth, &settings.fit).map_err(|e| fit_refused(path, e))?;
    let r = &fit.fit.report;
    // the writers read the surface, the name and the tolerance
    let face = ShellFace {
        name: doc.name.clone(),
        deviation: r.deviation,
        tolerance: r.tolerance,
        surface: fit.fit.surface,
        v: (Vec::new(), Vec::new()),
    };
    let shell = ShellFit {
        faces: vec![face],
        seams: Vec::new(),
    };
    if format == Format::Step {
        write_fitted(path, &doc.name, &shell, None)?;
    } else {
        write_iges(path, &doc.name, &shell.faces)?;
    }
    Ok(DocumentExported {
        format,
        patches: vec![doc.patches[0].name.clone()],
        depth: fit.depth,
        faces: shell.faces,
        seconds: fit.seconds,
        fit: None,
        mirror_seams: Vec::new(),
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
    // IGES writes the shell's faces, each an entity of its own: their
    // edges meet exactly, and a face is measured as the shell measures it
    // (docs/math.md §11.5)
    let fit = fit_document(doc, built, depth, &settings.fit, FaceFit::Shell)
        .map_err(|e| fit_refused(path, e))?;
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
        seconds: fit.seconds,
        fit: Some(fit),
        mirror_seams,
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
    write_atomic(path, text.as_bytes(), |b| iges::verify(b, n))
}
