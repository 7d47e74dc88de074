//! Reading and saving scene files (docs/math.md §11): a [`Scene`] (one
//! surface, [`load_scene`], [`save_scene`]) and a [`Document`] (any number
//! of patches, [`load`], [`save`]). Any version of the scene file is read,
//! every error located and naming its patch; a document is saved as
//! version 2 when there is one patch (the bytes [`save_scene`] writes) and
//! version 3 otherwise, atomically and verified ([`io::write_atomic`]).
//! One surface's reading, [`Scene::parse`], is here too: a version-3 file is
//! read as a document, whose one patch is the scene, so that a file has one
//! parse path whatever reads it. The files themselves (size cap, UTF-8,
//! atomic writing) are [`crate::scene::files::io`], which knows no scene.

use super::document::{Document, PatchScene, Start};
use super::document_check::check_document;
use super::model::Scene;
use crate::scene::files::error::SceneError;
use crate::scene::files::format::SceneFile;
use crate::scene::files::format_v3::{DocumentFile, StartSpec, VERSION_PATCHES, declared_version};
use crate::scene::files::io;
use crate::scene::files::patch_text::PatchText;
use crate::scene::files::reference_link::resolve_in;
use std::path::Path;

impl Document {
    /// From a version-3 file's contents, every error located in `text` and
    /// naming its patch.
    pub fn from_file(f: DocumentFile, file: &Path, text: &str) -> Result<Self, SceneError> {
        let place = PatchText::new(text);
        if f.patches.is_empty() {
            let (line, col) = place.top("patches");
            return Err(SceneError::at(
                file,
                line,
                col,
                "`patches` is empty; a design needs at least one patch, the first starting on its own curve (`initial: Curve(tangents: […], order: 3, length: L, origin: (x, y, z))`)",
            ));
        }
        let mut patches = Vec::with_capacity(f.patches.len());
        for i in 0..f.patches.len() {
            let scene = Scene::from_patch(&f, i, file, &place)?;
            let p = &f.patches[i];
            patches.push(PatchScene {
                name: p.name.clone(),
                start: Start::from_spec(&p.initial),
                design: scene.design,
                details: scene.details,
                tuning: scene.tuning,
                interpolate_tangents: scene.interpolate_tangents,
            });
        }
        let reference = resolve_in(f.reference.as_ref(), file, || place.top("reference"))?;
        let doc = Document {
            name: f.name,
            display_depth: f.display_depth,
            edit_depth: f.edit_depth,
            mirror: f.mirror,
            view: f.view,
            reference,
            patches,
        };
        check_document(&doc, file, &place)?;
        Ok(doc)
    }

    /// Parses a scene file of any version: 1 and 2 as one patch named
    /// [`MAIN_PATCH`](super::document::MAIN_PATCH) (with exactly
    /// [`Scene::parse`]'s errors), 3 as its patches.
    pub fn parse(text: &str, file: &Path) -> Result<Self, SceneError> {
        if declared_version(text) != Some(VERSION_PATCHES) {
            return Scene::parse(text, file).map(Document::from_scene);
        }
        let f: DocumentFile = ron::Options::default()
            .from_str(text)
            .map_err(|e| SceneError::ron(file, text, &e))?;
        Document::from_file(f, file, text)
    }
}

impl Scene {
    /// Parses the RON text of one surface: a version-1 or -2 scene, or a
    /// version-3 design of one patch on its own curve, read as a document
    /// ([`Document::from_file`]) whose one patch is the scene. A design of
    /// several patches is refused saying so (the editor, `build` and a
    /// script's `Load` open every patch: [`Document::parse`]).
    pub fn parse(text: &str, file: &Path) -> Result<Self, SceneError> {
        if text.trim().is_empty() {
            return Err(SceneError::at(
                file,
                1,
                1,
                "the file is empty; a scene is a RON record `( version: 2, tangents: …, … )` — start from scenes/car1.ron",
            ));
        }
        if declared_version(text) != Some(VERSION_PATCHES) {
            let f: SceneFile = ron::Options::default()
                .from_str(text)
                .map_err(|e| SceneError::ron(file, text, &e))?;
            return Scene::from_file(f, file, text);
        }
        let f: DocumentFile = ron::Options::default()
            .from_str(text)
            .map_err(|e| SceneError::ron(file, text, &e))?;
        one_surface(&f, file, text)?;
        let doc = Document::from_file(f, file, text)?;
        Ok(doc.one_scene().expect("one patch, on its own curve"))
    }
}

/// A version-3 file read as one surface: refused, located, when it has
/// several patches or its one patch starts on an edge.
fn one_surface(f: &DocumentFile, file: &Path, text: &str) -> Result<(), SceneError> {
    if f.patches.len() > 1 {
        let names: Vec<String> = f.patches.iter().map(|p| format!("`{}`", p.name)).collect();
        let (line, col) = PatchText::new(text).top("patches");
        return Err(SceneError::at(
            file,
            line,
            col,
            format!(
                "this design has {} patches ({}), and this reader takes one surface only (the editor, `build` and a script's `Load` open several patches); open it there, or give a design of one patch or a version-2 scene",
                names.len(),
                names.join(", ")
            ),
        ));
    }
    if let Some(patch) = f.patches.first()
        && let StartSpec::Edge { patch: on, .. } = &patch.initial
    {
        let (line, col) = PatchText::new(text).in_patch(0, "initial");
        return Err(SceneError::at(
            file,
            line,
            col,
            format!(
                "patch `{}` starts on patch `{on}`, which is not an earlier patch; the first patch starts on its own curve: give it `initial: Curve(tangents: […], order: 3, length: L, origin: (x, y, z))`",
                patch.name
            ),
        ));
    }
    Ok(())
}

/// Reads and validates a scene file of one surface ([`Scene::parse`]).
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    let text = io::read_text(path, io::MAX_SCENE_BYTES)?;
    Scene::parse(&text, path)
}

/// Saves `scene` to `path` atomically and verifies what was written; its
/// reference's path is written relative to `path`'s folder
/// ([`Scene::to_ron_at`], docs/math.md §12).
pub fn save_scene(scene: &Scene, path: &Path) -> Result<(), SceneError> {
    let text = scene.to_ron_at(path);
    let want = scene.to_file_at(path);
    io::write_atomic(path, text.as_bytes(), |written| {
        let back = std::str::from_utf8(written)
            .map_err(|_| "read-back is not UTF-8".to_string())
            .and_then(|t| Scene::parse(t, path).map_err(|e| e.to_string()))?;
        if back.to_file_at(path) != want {
            return Err("read-back differs from the scene".into());
        }
        Ok(())
    })
}

/// Reads and validates a scene file of any version as a document.
pub fn load(path: &Path) -> Result<Document, SceneError> {
    let text = io::read_text(path, io::MAX_SCENE_BYTES)?;
    Document::parse(&text, path)
}

/// Saves `doc` atomically and verified: through [`save_scene`] (version 2, the
/// same bytes) when it has one patch, else as version 3, read back and
/// compared field by field before it replaces the file. The reference's
/// path is written relative to `path`'s folder (docs/math.md §12).
pub fn save(doc: &Document, path: &Path) -> Result<(), SceneError> {
    if let Some(scene) = doc.one_scene() {
        return save_scene(&scene, path);
    }
    let text = doc.to_ron_at(path);
    let want = doc.to_file_at(path);
    io::write_atomic(path, text.as_bytes(), |written| {
        let back = std::str::from_utf8(written)
            .map_err(|_| "read-back is not UTF-8".to_string())
            .and_then(|t| Document::parse(t, path).map_err(|e| e.to_string()))?;
        if back.to_file_at(path) != want {
            return Err("read-back differs from the design".into());
        }
        Ok(())
    })
}
