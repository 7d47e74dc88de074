//! Export of a design of several patches (docs/cad.md,
//! "Several patches"): the shipped `scenes/hood-screen-wing.ron` (a G2 chain
//! and a G1 side join) at its display depth, from the document built at
//! that depth, as the CLI or the editor hands it to
//! [`crate::scene::export::document::export_document`]:
//!
//! - `export/hood-screen-wing/d4/step`: the STEP shell, everything included
//!   (the build one depth finer for the check grids, the shell's fit, the
//!   text, the atomic write and its verification);
//! - `export/hood-screen-wing/d4/shell-fit`: the shell's fit alone (the
//!   document already built one depth finer);
//! - `export/hood-screen-wing/d4/iges`: the IGES file (the shell's faces);
//! - `export/hood-screen-wing/d4/glb`: the `.glb`, one node and mesh per patch.
//!
//! The rows are left out when the checkout's scene is missing (an installed binary).

use super::workloads::Workload;
use crate::scene::design::document_build::BuiltDocument;
use crate::scene::export::document::{DocumentExportSettings, export_document};
use crate::scene::fit::document::{FaceFit, fit_document};
use crate::scene::{Document, design::document_io};
use std::path::{Path, PathBuf};

fn scene() -> Option<Document> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
    document_io::load(&path).ok()
}

fn scratch(ext: &str) -> PathBuf {
    std::env::temp_dir().join(format!(
        "streamline-bench-export-{}.{ext}",
        std::process::id()
    ))
}

fn export_row(doc: &Document, ext: &'static str) -> Workload {
    let doc = doc.clone();
    let name = format!("export/hood-screen-wing/d{}/{ext}", doc.display_depth);
    Workload::lazy(name, move || {
        let built: BuiltDocument = doc
            .build(doc.display_depth)
            .expect("the shipped scene builds");
        let path = scratch(ext);
        Box::new(move || {
            let out = export_document(&doc, &built, &path, &DocumentExportSettings::default())
                .expect("the shipped scene exports");
            let _ = std::fs::remove_file(&path);
            out.depth as f64 + out.faces.iter().map(|f| f.deviation.max).sum::<f64>()
        })
    })
}

/// The rows (module docs).
pub fn document_export_rows() -> Vec<Workload> {
    let Some(doc) = scene() else {
        return Vec::new();
    };
    let d = doc.display_depth;
    let fit = {
        let doc = doc.clone();
        Workload::lazy(
            format!("export/hood-screen-wing/d{d}/shell-fit"),
            move || {
                let finer = doc.build(d + 1).expect("the shipped scene builds");
                Box::new(move || {
                    let f = fit_document(&doc, &finer, d, &Default::default(), FaceFit::Shell)
                        .expect("the shipped scene fits");
                    f.faces.iter().map(|f| f.deviation.max).sum::<f64>()
                })
            },
        )
    };
    vec![
        export_row(&doc, "step"),
        fit,
        export_row(&doc, "iges"),
        export_row(&doc, "glb"),
    ]
}
