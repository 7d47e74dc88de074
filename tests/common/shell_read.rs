//! Reading exported shells back with OpenCascade (tests/python/check_shell.py):
//! the points files it measures, and what its readings must say.

use glam::DVec3;
use std::path::Path;
use streamline_kernel::nurbs::{FitOptions, PatchGrid, SeamSpec, ShellError, ShellFace, fit_shell};
use streamline_studio::scene::design::document::Document;

/// Face `i`'s points as `x y z` lines, a file in `dir` named for `tag`.
pub fn point_file(dir: &Path, tag: &str, i: usize, points: &[DVec3]) -> String {
    let path = dir.join(format!("{tag}-{i}.xyz"));
    let text: String = points
        .iter()
        .map(|q| format!("{:?} {:?} {:?}\n", q.x, q.y, q.z))
        .collect();
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// OpenCascade's reading `r` of a file of `faces`: as many faces, valid,
/// each within its tolerance of its points.
pub fn valid_within(tag: &str, faces: &[ShellFace], r: &serde_json::Value) {
    assert_eq!(r["faces"], faces.len(), "{tag}: {r}");
    assert_eq!(r["valid"], true, "{tag}: {r}");
    for (f, d) in faces.iter().zip(r["deviation"].as_array().unwrap()) {
        let d = d.as_f64().unwrap();
        assert!(
            d <= f.tolerance,
            "{tag}: face {} is {d} from its points, over {}",
            f.name,
            f.tolerance
        );
    }
}

/// The largest angle between the faces' normals along the edge `faces`
/// share (at least 32 points).
pub fn seam_angle(r: &serde_json::Value, faces: [usize; 2]) -> f64 {
    let s = r["seams"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["faces"] == serde_json::json!(faces))
        .unwrap_or_else(|| panic!("no shared edge between faces {faces:?}: {r}"));
    assert!(s["samples"].as_u64().unwrap() >= 32);
    s["max_angle_deg"].as_f64().unwrap()
}

/// The shell of `doc` sampled at `depth`, every patch measured at its check
/// grid as it lies (no start held: docs/math.md §11.5).
pub fn shell_as_it_lies(doc: &Document, depth: u32) -> Result<(), ShellError> {
    let built = doc.build(depth + 1).unwrap();
    let grids: Vec<PatchGrid> = (doc.patches.iter().zip(&built.patches))
        .map(|(p, s)| PatchGrid::from_stack(&p.name, s, depth, p.design.scheme().curve()).unwrap())
        .collect();
    let specs: Vec<SeamSpec> = (built.seams.iter())
        .map(|s| SeamSpec {
            a: s.a,
            b: s.b,
            join: s.join,
        })
        .collect();
    fit_shell(&grids, &specs, &FitOptions::DEFAULT).map(|_| ())
}
