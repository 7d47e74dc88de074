//! A triangle mesh (OBJ or STL) as a design's reference, for display and
//! measuring only (docs/math.md §12, eq. 12.8; docs/fit.md "Triangle
//! meshes"): `faces` lists it, `fit` refuses it with the fix, and `build`
//! reports a design's distance to it (its JSON's `"reference"`), as a
//! script's `ExpectReferenceDeviation` does.
//!
//! The outside check: the car (`car1`) exported by `build --depth 4
//! --export car.stl` (binary STL, written by the export code, not by the
//! reader) is the car's own reference. Every point `build` measures at
//! depth 4 is a corner of that file rounded to `f32`, so its distance is at
//! most its rounding, `√3 · 2⁻²⁴` of the largest coordinate (4.2e-7 m; the
//! file cannot hold the points closer: 2.3e-7 measured); at depth 5 the
//! points between those corners are off the triangles by the chord error,
//! far more (3.1e-4, negative control). The document's STL text (ASCII,
//! shortest round-trip decimals, one `solid` per patch, `scene::export::stl_shell`)
//! read as written holds the depth-4 points exactly: their distance is at
//! most 1e-9.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use streamline_kernel::fit::ReferenceFitOptions;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;
use streamline_studio::scene::design::document_io::load;
use streamline_studio::scene::design::{builtin, document_io};
use streamline_studio::scene::export::stl_shell::stl_solids_text;
use streamline_studio::scene::files::reference_link::ReferenceLink;
use streamline_studio::scene::fit::reference::{distances, fit_file};

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

fn fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("crates/reference/tests/data")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("streamline-reference-mesh-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn json(stdout: &str) -> serde_json::Value {
    serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("{e}: {stdout}"))
}

#[test]
fn faces_lists_a_mesh_and_fit_refuses_it() {
    let stl = fixture("tent-binary.stl");
    let (code, stdout, stderr) = run(&["faces", &stl, "--json"]);
    assert_eq!(code, 0, "{stderr}");
    let r = json(&stdout);
    let f = &r["faces"][0];
    assert_eq!(f["kind"], "mesh", "{r}");
    assert_eq!(
        (f["triangles"].as_u64(), f["vertices"].as_u64()),
        (Some(8), Some(9))
    );
    assert_eq!(r["unit"], "metre");
    let (code, stdout, _) = run(&["faces", &fixture("tent-ascii.stl")]);
    assert_eq!(code, 0);
    assert!(
        stdout.contains("face 0: mesh, 8 triangles, 9 vertices (for measuring only, not fitted)")
            && stdout.contains("(line 2)"),
        "{stdout}"
    );
    // negative control: a B-spline face lists no triangles
    let (_, stdout, _) = run(&["faces", &fixture("bicubic.step"), "--json"]);
    assert!(json(&stdout)["faces"][0].get("triangles").is_none());

    let dir = scratch("refuse");
    let out = dir.join("tent.ron");
    let (code, _, stderr) = run(&["fit", &stl, "--out", out.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("face 0 is a triangle mesh")
            && stderr.contains("for display and measuring only")
            && stderr.contains("; fit a STEP or IGES face or an OBJ quad grid"),
        "{stderr}"
    );
    assert!(!out.exists());
    // the scene layer's fit (a script's `Fit`) refuses it at its line
    let link = ReferenceLink {
        path: fixture("tent-ascii.stl").into(),
        face: 0,
    };
    let e = fit_file(&link, &ReferenceFitOptions::default())
        .err()
        .unwrap();
    assert!(
        e.contains("tent-ascii.stl:2:1: face 0 is a triangle mesh"),
        "{e}"
    );
    // and measures against it: a corner is on it, a point 0.5 above the
    // top is 0.5 away
    let d = distances(
        &link,
        &[
            streamline_kernel::DVec3::new(0.5, 0.5, 0.75),
            streamline_kernel::DVec3::new(0.5, 0.5, 1.25),
        ],
    )
    .unwrap();
    assert_eq!(d[0], 0.0);
    assert!((d[1] - 0.5).abs() <= 1e-15, "{d:?}");
}

/// The largest and mean distance `build` reports from the car at `depth` to
/// `stl`.
fn car_deviation(dir: &Path, stl: &Path, depth: u32) -> (f64, f64) {
    let mut scene = builtin::scene("car1").unwrap();
    scene.reference = Some(ReferenceLink {
        path: stl.to_path_buf(),
        face: 0,
    });
    let file = dir.join(format!("car-{depth}.ron"));
    document_io::save_scene(&scene, &file).unwrap();
    let d = depth.to_string();
    let (code, stdout, stderr) = run(&["build", file.to_str().unwrap(), "--depth", &d]);
    assert_eq!(code, 0, "{stderr}");
    let r = json(&stdout);
    let dev = &r["reference"]["deviation"];
    assert!(dev.is_object(), "{r}");
    (dev["max"].as_f64().unwrap(), dev["mean"].as_f64().unwrap())
}

#[test]
fn the_car_measured_against_its_own_stl() {
    let dir = scratch("car");
    let stl = dir.join("car.stl");
    let (code, _, stderr) = run(&[
        "build",
        "car1",
        "--depth",
        "4",
        "--export",
        stl.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let file = streamline_reference::read(&stl).unwrap();
    let info = &file.faces[0].info;
    assert_eq!(info.kind, streamline_reference::SurfaceKind::Mesh);
    let [lo, hi] = info.bbox.unwrap();
    let largest = lo.iter().chain(&hi).fold(0.0f64, |m, x| m.max(x.abs()));
    let rounding = 3f64.sqrt() * largest * 2f64.powi(-24);
    let (max4, mean4) = car_deviation(&dir, &stl, 4);
    let (max5, mean5) = car_deviation(&dir, &stl, 5);
    eprintln!(
        "car against its depth-4 STL ({} triangles): depth 4 max {max4:.3e} mean {mean4:.3e} (f32 rounding {rounding:.3e}); depth 5 max {max5:.3e} mean {mean5:.3e}",
        info.triangles.unwrap()
    );
    assert!(max4 <= rounding && rounding < 1e-6, "{max4} > {rounding}");
    // negative control: the depth-5 points between the corners are off
    assert!(max5 > 100.0 * rounding && mean5 > mean4, "{max5} {mean5}");

    // a script measures the same: `ExpectReferenceDeviation` at display
    // depth 4 within the rounding, at 5 over it (and fails when asked not to)
    let script = dir.join("measure.ron");
    let steps = format!(
        r#"(steps: [
            Load("car-4.ron"),
            SetDisplayDepth(4),
            ExpectReferenceDeviation(max: {rounding:e}),
            SetDisplayDepth(5),
            ExpectReferenceDeviation(max: 1.0, min: Some({:e})),
        ])"#,
        100.0 * rounding
    );
    std::fs::write(&script, &steps).unwrap();
    let (code, out, err) = run(&["play", script.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    std::fs::write(&script, steps.replace("max: 1.0, min", "max: 1e-6, min")).unwrap();
    let (code, out, _) = run(&["play", script.to_str().unwrap()]);
    assert_ne!(code, 0, "negative control: {out}");
    assert!(out.contains("largest distance"), "{out}");

    // the document's STL text (ASCII, shortest round-trip decimals, one
    // `solid` per patch; here the car twice) keeps the points exactly: on
    // it to 1e-9, and every solid is read
    let doc = load(&dir.join("car-4.ron")).unwrap();
    let built = doc.build(4).unwrap();
    let mesh = SurfaceMesh::from_points(built.patches[0].finest_points());
    let ascii = dir.join("car-ascii.stl");
    std::fs::write(&ascii, stl_solids_text(&[("car", &mesh), ("again", &mesh)])).unwrap();
    let read = streamline_reference::read(&ascii).unwrap();
    assert_eq!(
        read.faces[0].info.triangles,
        Some(2 * info.triangles.unwrap())
    );
    let (max4, mean4) = car_deviation(&dir, &ascii, 4);
    let (max5, _) = car_deviation(&dir, &ascii, 5);
    eprintln!(
        "car against its depth-4 ASCII STL: depth 4 max {max4:.3e} mean {mean4:.3e}; depth 5 max {max5:.3e}"
    );
    assert!(max4 <= 1e-9, "{max4}");
    assert!(max5 > 1e-5, "negative control: {max5}");
}
