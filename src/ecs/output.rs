//! The output stage: saving and exporting the whole design (every patch:
//! a design of several is exported as `build --export` writes it), after
//! the mesh is up to date.

use super::edit_error::EditError;
use super::exchange::{ExportSettings, LastExport};
use super::messages::{Edit, EditMessage};
use super::resources::*;
use crate::scene::design::document::{Document, MAIN_PATCH};
use crate::scene::design::document_build::BuiltDocument;
use crate::scene::design::document_io;
use crate::scene::export::document::{DocumentExportSettings, export_document};
use bevy::prelude::*;

#[allow(clippy::too_many_arguments)]
pub(crate) fn write_files(
    meter: Res<super::meter::CpuMeter>,
    mut reader: MessageReader<EditMessage>,
    mut model: ResMut<Model>,
    patch: super::patch::PatchRef,
    joined: super::joined::JoinedRead,
    surface: Res<SurfaceData>,
    mut log: ResMut<EditLog>,
    settings: Res<ExportSettings>,
    mut last: ResMut<LastExport>,
) {
    let _meter = meter.start();
    let mut scene = None;
    for msg in reader.read() {
        if !matches!(msg.edit, Edit::Save(_) | Edit::Export(_)) {
            continue;
        }
        let scene = match &scene {
            Some(s) => s,
            None => match patch.scene() {
                Ok(s) => scene.insert(s),
                Err(e) => {
                    log.entries.push(Err(EditError::Assemble(e)));
                    continue;
                }
            },
        };
        match &msg.edit {
            // the design: version 2 for one patch (the bytes io::save writes), 3 for several
            Edit::Save(path) => {
                let doc = joined.document(scene.clone());
                match document_io::save(&doc, path) {
                    Ok(()) => {
                        model.path = Some(path.clone());
                        model.unsaved = false;
                        log.entries.push(Ok(saved_note(path, &doc)));
                    }
                    Err(e) => log.entries.push(Err(EditError::Save(e))),
                }
            }
            Edit::Export(path) => {
                // every patch, as `build --export` writes them (docs/math.md §11);
                // one patch with the colours of the map shown, if they are its mesh's
                let doc = joined.document(scene.clone());
                let several = joined.several();
                let colors = (settings.colors.as_ref())
                    .filter(|c| !several && c.len() == surface.points.data().len())
                    .map(|c| vec![c.clone()]);
                let opts = DocumentExportSettings {
                    depth: Some(scene.display_depth),
                    fit: settings.fit,
                    colors,
                };
                // built by the export at the depths it needs
                let unbuilt = BuiltDocument {
                    depth: 0,
                    patches: Vec::new(),
                    seams: Vec::new(),
                };
                match export_document(&doc, &unbuilt, path, &opts) {
                    Ok(out) => {
                        // the format, the patches of several, and the fit
                        // of STEP and IGES or the triangles of one mesh
                        let mut what = vec![out.format.name().to_string()];
                        if several {
                            what.push(format!(
                                "{} patches: {}",
                                out.patches.len(),
                                out.patches.join(", ")
                            ));
                        }
                        match out.fit_summary() {
                            Some(fit) => what.push(fit),
                            None if !several => {
                                what.push(format!("{} triangles", surface.triangle_count()))
                            }
                            None => {}
                        }
                        log.entries.push(Ok(format!(
                            "exported {} ({})",
                            path.display(),
                            what.join(", ")
                        )));
                        last.written = Some((path.clone(), out));
                    }
                    Err(e) => log.entries.push(Err(EditError::Export(e))),
                }
            }
            _ => {}
        }
    }
}

/// What a save says: the file, and for one renamed patch that version 2
/// (what a one-patch design saves as, so that the last release reads it)
/// keeps no patch name.
fn saved_note(path: &std::path::Path, doc: &Document) -> String {
    match doc.patches.as_slice() {
        [p] if p.name != MAIN_PATCH => format!(
            "saved {} as version 2 (one patch, readable by the last release), which has no patch names: `{}` opens again as `{MAIN_PATCH}`; a design of several patches saves as version 3 and keeps every name",
            path.display(),
            p.name
        ),
        _ => format!("saved {}", path.display()),
    }
}
