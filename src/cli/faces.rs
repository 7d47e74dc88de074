//! `faces FILE [--json]`: the faces of a STEP or IGES file that a design can
//! be fitted to (`docs/math.md §12`), the surface of an OBJ point grid, or
//! the triangle mesh of an OBJ or STL file (kind `mesh`, with its triangle
//! and vertex counts: measured against, never fitted), one per line or as
//! one JSON object.

use super::input::{CliError, write_stdout};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;
use streamline_reference::{FaceInfo, ReferenceFile};

/// Arguments of `faces`.
#[derive(Debug, Args)]
pub struct FacesArgs {
    /// A STEP (.step, .stp), IGES (.igs, .iges), OBJ or STL file.
    file: PathBuf,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct FacesReport<'a> {
    file: String,
    unit: &'a str,
    metres_per_unit: f64,
    faces: Vec<FaceInfo>,
}

/// Reads a reference file, its errors as the command line's.
pub fn read_reference(file: &std::path::Path) -> Result<ReferenceFile, CliError> {
    streamline_reference::read(file).map_err(|e| CliError::Usage(e.to_string()))
}

/// Runs `faces`.
pub fn run(a: FacesArgs) -> Result<(), CliError> {
    let file = read_reference(&a.file)?;
    let faces = file.infos();
    if a.json {
        return write_stdout(&FacesReport {
            file: a.file.display().to_string(),
            unit: &file.unit,
            metres_per_unit: file.metres_per_unit,
            faces,
        });
    }
    println!(
        "{}: {} face{} (lengths in {}, converted to metres)",
        a.file.display(),
        faces.len(),
        if faces.len() == 1 { "" } else { "s" },
        file.unit
    );
    for f in &faces {
        println!("  {}", describe(f));
    }
    Ok(())
}

/// One line about a face: index, kind, degrees and poles, closed, trimmed,
/// area and size.
fn describe(f: &FaceInfo) -> String {
    let kind = serde_json::to_value(f.kind)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default();
    let mut s = format!("face {}: {kind}", f.index);
    if let (Some([p, q]), Some([m, n])) = (f.degrees, f.poles) {
        s += &format!(", degrees {p} × {q}, {m} × {n} poles");
    }
    if let (Some(t), Some(v)) = (f.triangles, f.vertices) {
        s += &format!(", {t} triangles, {v} vertices (for measuring only, not fitted)");
    }
    for (closed, periodic, dir) in [
        (f.closed[0], f.periodic[0], "u"),
        (f.closed[1], f.periodic[1], "v"),
    ] {
        if periodic {
            s += &format!(", periodic in {dir}");
        } else if closed {
            s += &format!(", closed in {dir}");
        }
    }
    if f.trimmed {
        s += ", trimmed (fitted over its parameter box)";
    }
    s += &format!(", area {:.6} m²", f.area);
    if let Some([lo, hi]) = f.bbox {
        s += &format!(
            ", size {:.4} × {:.4} × {:.4} m",
            hi[0] - lo[0],
            hi[1] - lo[1],
            hi[2] - lo[2]
        );
    }
    if f.triangles.is_some() {
        // a mesh's entity says its counts, given above
        if f.line > 0 {
            s += &format!(" (line {})", f.line);
        }
    } else {
        s += &format!(" ({}, line {})", f.entity, f.line);
    }
    s
}
