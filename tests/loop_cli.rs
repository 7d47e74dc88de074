//! Loop surfaces on the command line (docs/math.md §7, docs/loop.md).
//! - USD out: `interpolate … --out control.usda` read back with Pixar's own
//!   library (PyPI `usd-core` in the test virtual environment that
//!   `scripts/venv.sh` makes at `$STREAMLINE_VENV`, default
//!   `~/.cache/streamline-venv`): points, face counts, indices, the scheme and
//!   the boundary token as written; `--boundary paper` refused. Fails (never
//!   skips) without the venv.
//! - An unknown `--boundary` is a usage error listing the three.
//! - Meshes OpenSubdiv would refuse or treat differently (an edge of three
//!   faces, a vertex joining two fans) are refused with their place, under
//!   every rule.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn venv_python() -> PathBuf {
    common::venv_python("Pixar's usd-core")
}

/// Reads the mesh with `pxr` and prints it as JSON.
const READ: &str = r#"
import json, sys
from pxr import Usd, UsdGeom
stage = Usd.Stage.Open(sys.argv[1])
prim = stage.GetDefaultPrim()
mesh = UsdGeom.Mesh(prim)
assert prim.IsA(UsdGeom.Mesh), prim
print(json.dumps({
    "points": [list(p) for p in mesh.GetPointsAttr().Get()],
    "counts": list(mesh.GetFaceVertexCountsAttr().Get()),
    "indices": list(mesh.GetFaceVertexIndicesAttr().Get()),
    "scheme": str(mesh.GetSubdivisionSchemeAttr().Get()),
    "boundary": str(mesh.GetInterpolateBoundaryAttr().Get()),
}))
"#;

fn obj_vertices_and_faces(path: &Path) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut v = Vec::new();
    let mut f = Vec::new();
    for l in text.lines() {
        let w: Vec<&str> = l.split_whitespace().collect();
        match w.first() {
            Some(&"v") => v.push([1, 2, 3].map(|k| w[k].parse::<f64>().unwrap())),
            Some(&"f") => f.push([1, 2, 3].map(|k| w[k].parse::<u32>().unwrap() - 1)),
            _ => {}
        }
    }
    (v, f)
}

#[test]
fn usda_control_mesh_reads_back_in_pixars_usd() {
    let py = venv_python();
    let dir = std::env::temp_dir().join(format!("streamline-usd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/meshes/snail.obj");
    for (rule, token) in [
        ("edge-only", "edgeOnly"),
        ("edge-and-corner", "edgeAndCorner"),
    ] {
        let usda = dir.join(format!("{rule}.usda"));
        let obj = dir.join(format!("{rule}.obj"));
        for out in [&usda, &obj] {
            let (code, stdout, stderr) = run(&[
                "interpolate",
                input,
                "--method",
                "fast",
                "--tolerance",
                "1e-7",
                "--boundary",
                rule,
                "--out",
                out.to_str().unwrap(),
            ]);
            assert_eq!(code, 0, "{stderr}");
            let j: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
            assert_eq!(j["boundary"], rule, "{j}");
        }
        let read = Command::new(&py)
            .arg("-c")
            .arg(READ)
            .arg(&usda)
            .output()
            .unwrap();
        assert!(
            read.status.success(),
            "usd-core could not read {}: {}",
            usda.display(),
            String::from_utf8_lossy(&read.stderr)
        );
        let j: serde_json::Value = serde_json::from_slice(&read.stdout).unwrap();
        let (verts, faces) = obj_vertices_and_faces(&obj);
        assert_eq!(j["scheme"], "loop");
        assert_eq!(j["boundary"], token);
        let counts: Vec<u64> = serde_json::from_value(j["counts"].clone()).unwrap();
        assert_eq!(counts.len(), faces.len());
        assert!(counts.iter().all(|&c| c == 3), "all triangles");
        let idx: Vec<u32> = serde_json::from_value(j["indices"].clone()).unwrap();
        assert_eq!(idx, faces.concat(), "the input's faces, in order");
        let pts: Vec<[f64; 3]> = serde_json::from_value(j["points"].clone()).unwrap();
        assert_eq!(pts.len(), verts.len());
        for (i, (p, v)) in pts.iter().zip(&verts).enumerate() {
            // USD holds point3f: each coordinate is the float nearest ours
            // (compared as floats: serde_json may read a double 1 ulp off)
            for k in 0..3 {
                assert_eq!(p[k] as f32, v[k] as f32, "point {i} coordinate {k}");
            }
        }
    }
    // 002's rule: refused before any work, naming the two rules that work
    let paper = dir.join("paper.usda");
    let (code, _, stderr) = run(&[
        "interpolate",
        input,
        "--boundary",
        "paper",
        "--out",
        paper.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("edge-only") && stderr.contains("edge-and-corner") && !paper.exists(),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn unknown_boundary_rule_is_a_usage_error_listing_the_three() {
    let input = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/meshes/snail.obj");
    let (code, _, stderr) = run(&["interpolate", input, "--boundary", "smooth"]);
    assert_eq!(code, 2, "{stderr}");
    for r in ["paper", "edge-only", "edge-and-corner"] {
        assert!(stderr.contains(r), "{r} in {stderr}");
    }
}

#[test]
fn meshes_opensubdiv_would_treat_differently_are_refused_with_their_place() {
    let dir = std::env::temp_dir().join(format!("streamline-nonmanifold-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // three faces on edge 1–2; two fans sharing vertex 1 (a bow tie)
    let cases = [
        (
            "edge.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
            "edge 1–2 is shared by 3 faces",
        ),
        (
            "fans.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv -1 0 0\nv -1 -1 0\nf 1 2 3\nf 1 4 5\n",
            "vertex 1 joins separate fans of faces",
        ),
    ];
    for (name, text, want) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        for rule in ["paper", "edge-only", "edge-and-corner"] {
            let (code, _, stderr) =
                run(&["interpolate", path.to_str().unwrap(), "--boundary", rule]);
            assert_eq!(code, 2, "{stderr}");
            assert!(
                stderr.contains(&format!("{}:", path.display()))
                    && stderr.contains(want)
                    && stderr.trim().lines().count() == 1,
                "{name} {rule}: {stderr}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
