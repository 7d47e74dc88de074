//! Starting from what exists on the command line (docs/math.md §12,
//! docs/fit.md): `faces` lists a STEP or IGES file's faces, `fit` writes a
//! streamline design within the tolerance of one of them.
//!
//! - The deviation `fit` reports is what OpenCascade measures: the saved
//!   design's mesh points at the fit depth furthest from the face by our
//!   measure, and every 97th of the others, projected on the file's face by
//!   `GeomAPI_ProjectPointOnSurf` and on its border curves
//!   (tests/python/check_fit.py, in the test
//!   virtual environment that `scripts/setup.sh --tests` makes; the test
//!   fails, never skips, without it).
//! - The same face written in metres, millimetres and inches (files that
//!   OpenCascade wrote, crates/reference/tests/data) gives the same design.
//! - Bad input is an error that names the file and the fix, and exits 2; a
//!   fit that stops at its net cap still writes its best design and exits 1.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use streamline_kernel::fit::distances_to_reference;
use streamline_studio::scene::design::document_io;

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

/// A reference file: the reader's fixtures, or the shipped references
/// (`scenes/references`).
fn data(name: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let shipped = root.join("scenes/references").join(name);
    match shipped.is_file() {
        true => shipped,
        false => root.join("crates/reference/tests/data").join(name),
    }
    .to_string_lossy()
    .into_owned()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("streamline-reference-cli-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn fit_json(file: &str, extra: &[&str], out: &Path) -> serde_json::Value {
    let mut args = vec!["fit", file, "--json", "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    let (code, stdout, stderr) = run(&args);
    assert_eq!(code, 0, "{stderr}");
    serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("{e}: {stdout}"))
}

#[test]
fn the_deviation_fit_reports_is_what_opencascade_measures() {
    let dir = scratch("occ");
    for (file, face) in [
        ("bicubic.step", 0),
        ("cylinder.igs", 0),
        ("two-faces.step", 0),
        ("hood.step", 0),
        ("duct.igs", 0),
        ("roof.step", 0),
    ] {
        let path = data(file);
        let out = dir.join(format!("{file}.ron"));
        let r = fit_json(&path, &["--face", &face.to_string()], &out);
        eprintln!("{file}: {r}");
        for key in [
            "net",
            "depth",
            "tolerance",
            "deviation",
            "within",
            "seconds",
        ] {
            assert!(r.get(key).is_some(), "{key} missing: {r}");
        }
        assert_eq!(r["within"], true, "{r}");
        let tol = r["tolerance"].as_f64().unwrap();
        let ours = r["deviation"]["to_reference"]["max"].as_f64().unwrap();
        assert!(ours <= tol && r["deviation"]["from_reference"]["max"].as_f64().unwrap() <= tol);
        // the saved design, built at the fit depth: its points furthest
        // from the face by our measure, and a spread of the others, measured
        // by OpenCascade
        let scene = document_io::load_scene(&out).unwrap();
        let depth = r["depth"].as_u64().unwrap() as u32;
        assert_eq!(scene.display_depth, depth);
        let built = scene.design.build(depth).unwrap();
        let points = built.points.data();
        let surface = streamline_reference::read(Path::new(&path)).unwrap();
        let ds = distances_to_reference(surface.surface(face).unwrap(), points).unwrap();
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&a, &b| ds[b].total_cmp(&ds[a]));
        let mut picked: Vec<usize> = order[..200.min(order.len())].to_vec();
        picked.extend((0..points.len()).step_by(97));
        let xyz = dir.join(format!("{file}.xyz"));
        let write = |lift: f64| {
            let text: String = picked
                .iter()
                .map(|&i| {
                    let p = points[i];
                    format!("{:.17e} {:.17e} {:.17e}\n", p.x, p.y, p.z + lift)
                })
                .collect();
            std::fs::write(&xyz, text).unwrap();
            common::opencascade_lines(
                "check_fit.py",
                &[Path::new(&path), Path::new(&face.to_string()), &xyz],
            )
            .remove(0)
        };
        let occ = write(0.0);
        let theirs = occ["max"].as_f64().unwrap();
        eprintln!(
            "{file}: {} points, {} measured by OpenCascade: ours {ours:.12e}, OpenCascade {theirs:.12e}",
            points.len(),
            picked.len()
        );
        assert!(
            (ours - theirs).abs() <= 1e-9 * theirs.max(1e-12),
            "{file}: we report {ours}, OpenCascade measures {theirs}"
        );
        // point by point
        let each = occ["distances"].as_array().unwrap();
        for (&i, d) in picked.iter().zip(each) {
            let d = d.as_f64().unwrap();
            assert!(
                (ds[i] - d).abs() <= 1e-9 * tol,
                "point {i}: {} vs {d}",
                ds[i]
            );
        }
        // negative control: the same points lifted by three tolerances are
        // not within it, by OpenCascade's measure
        assert!(write(3.0 * tol)["max"].as_f64().unwrap() > tol);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn one_face_in_metres_millimetres_and_inches_fits_to_one_design() {
    let dir = scratch("units");
    let reports: Vec<serde_json::Value> = ["bicubic.step", "bicubic-mm.step", "bicubic-inch.igs"]
        .iter()
        .map(|f| fit_json(&data(f), &[], &dir.join(format!("{f}.ron"))))
        .collect();
    for r in &reports[1..] {
        assert_eq!(r["net"], reports[0]["net"], "{r}");
        // (the files hold their poles to 10–13 digits: the designs agree to
        // far below the tolerance, not to the last bit)
        let a = reports[0]["deviation"]["to_reference"]["max"]
            .as_f64()
            .unwrap();
        let b = r["deviation"]["to_reference"]["max"].as_f64().unwrap();
        let tol = r["tolerance"].as_f64().unwrap();
        assert!((a - b).abs() <= 1e-3 * tol, "{a} vs {b}");
        assert!((tol - reports[0]["tolerance"].as_f64().unwrap()).abs() <= 1e-9 * tol);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn faces_lists_every_face() {
    let (code, stdout, stderr) = run(&["faces", &data("two-faces.step"), "--json"]);
    assert_eq!(code, 0, "{stderr}");
    let r: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    let faces = r["faces"].as_array().unwrap();
    assert_eq!(faces.len(), 2, "{r}");
    assert_eq!(faces[0]["kind"], "bspline");
    assert_eq!(faces[1]["kind"], "plane");
    for f in faces {
        for key in [
            "index", "degrees", "poles", "closed", "trimmed", "area", "bbox",
        ] {
            assert!(f.get(key).is_some(), "{key} missing: {f}");
        }
    }
    let (code, stdout, _) = run(&["faces", &data("trimmed.step")]);
    assert_eq!(code, 0);
    assert!(stdout.contains("trimmed"), "{stdout}");
}

#[test]
fn bad_input_names_the_file_and_the_fix() {
    let dir = scratch("bad");
    let out = dir.join("x.ron");
    let out = out.to_str().unwrap();
    let two = data("two-faces.step");
    // a face past the end
    let (code, _, err) = run(&["fit", &two, "--face", "7", "--out", out]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("two-faces.step") && err.contains("--face"),
        "{err}"
    );
    // a face that is a plane, not a B-spline
    let (code, _, err) = run(&["fit", &two, "--face", "1", "--out", out]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("plane"), "{err}");
    // not a scene to write
    let (code, _, err) = run(&["fit", &two, "--out", "x.obj"]);
    assert_eq!(code, 2);
    assert!(err.contains(".ron"), "{err}");
    // a file that does not exist, and one of another kind
    let (code, _, err) = run(&["faces", "/nonexistent/panel.step"]);
    assert_eq!(code, 2);
    assert!(err.contains("/nonexistent/panel.step"), "{err}");
    let (code, _, err) = run(&["faces", out]);
    assert_eq!(code, 2);
    assert!(err.to_lowercase().contains("step"), "{err}");
    // options out of range
    let (code, _, err) = run(&["fit", &two, "--depth", "9", "--out", out]);
    assert_eq!(code, 2);
    assert!(err.contains("depth"), "{err}");
    let (code, _, err) = run(&["fit", &two, "--max-net", "4by4", "--out", out]);
    assert_eq!(code, 2);
    assert!(err.contains("RxC"), "{err}");
    assert!(!Path::new(out).exists(), "nothing written on a refusal");
    // a net capped below what the face needs: the best design, and why
    let (code, _, err) = run(&[
        "fit",
        &data("bicubic.step"),
        "--max-net",
        "4x4",
        "--out",
        out,
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("not within"), "{err}");
    assert!(document_io::load_scene(Path::new(out)).is_ok());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_shipped_designs_are_what_fit_makes_of_their_references() {
    let dir = scratch("shipped");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references");
    for (design, reference) in [
        ("hood.ron", "hood.step"),
        ("duct.ron", "duct.igs"),
        ("roof.ron", "roof.step"),
        ("scan.ron", "scan.obj"),
    ] {
        let shipped = document_io::load_scene(&root.join(design)).unwrap();
        let link = shipped
            .reference
            .clone()
            .expect("a fitted design names its reference");
        assert_eq!(
            std::fs::canonicalize(&link.path).unwrap(),
            std::fs::canonicalize(root.join(reference)).unwrap()
        );
        let out = dir.join(design);
        let r = fit_json(&data(reference), &[], &out);
        assert_eq!(r["within"], true, "{r}");
        let fresh = document_io::load_scene(&out).unwrap();
        assert_eq!(
            fresh.design.net().data(),
            shipped.design.net().data(),
            "{design}"
        );
        assert_eq!(
            fresh.design.params().s.data(),
            shipped.design.params().s.data()
        );
        assert_eq!(fresh.display_depth, shipped.display_depth);
        // within the tolerance of the reference, measured on the shipped file
        let file = streamline_reference::read(&link.path).unwrap();
        let built = shipped.design.build(shipped.display_depth).unwrap();
        let ds =
            distances_to_reference(file.surface(link.face).unwrap(), built.points.data()).unwrap();
        let max = ds.iter().copied().fold(0.0, f64::max);
        eprintln!(
            "{design}: net {}, max {max:.3e}, tolerance {}",
            r["net"], r["tolerance"]
        );
        assert!(max <= r["tolerance"].as_f64().unwrap());
    }
    let _ = std::fs::remove_dir_all(&dir);
}
