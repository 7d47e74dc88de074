//! Reading and saving a [`Document`] (docs/math.md §11): any version of the
//! scene file read, every error located and naming its patch; saved as
//! version 2 when there is one patch (the bytes [`io::save`] writes) and
//! version 3 otherwise, atomically and verified as [`io::write_atomic`] does.

use super::document::{Document, PatchScene, Start};
use super::document_check::check_document;
use super::error::SceneError;
use super::format_v3::{DocumentFile, VERSION_PATCHES, declared_version};
use super::io;
use super::model::Scene;
use super::patch_text::PatchText;
use super::reference_link::resolve_in;
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
    /// [`MAIN_PATCH`] (with exactly [`Scene::parse`]'s errors), 3 as its patches.
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

/// Reads and validates a scene file of any version as a document.
pub fn load(path: &Path) -> Result<Document, SceneError> {
    let text = io::read_text(path, io::MAX_SCENE_BYTES)?;
    Document::parse(&text, path)
}

/// Saves `doc` atomically and verified: through [`io::save`] (version 2, the
/// same bytes) when it has one patch, else as version 3, read back and
/// compared field by field before it replaces the file. The reference's
/// path is written relative to `path`'s folder (docs/math.md §12).
pub fn save(doc: &Document, path: &Path) -> Result<(), SceneError> {
    if let Some(scene) = doc.one_scene() {
        return io::save(&scene, path);
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
