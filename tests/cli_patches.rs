//! `build --json` on designs of several patches (docs/math.md
//! §11): `"patches"` and `"seams"` come from the world's patch entities and
//! equal the scene library's `Document::build` (an independent path); a
//! one-patch scene reports one patch and no seams and keeps every key.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use streamline_kernel::joins::{Continuity, Edge, Join};
use streamline_kernel::{DQuat, DVec3};
use streamline_studio::scene::design::document::{Document, Start};
use streamline_studio::scene::design::document_io::{load, save};

fn shipped() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron")
}

fn build(scene: &Path) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
        .args(["build", scene.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn tmp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ss-cli-patches-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(format!("{tag}.ron"))
}

/// The report's patches and seams equal `doc.build`'s (to the last bit or two).
fn assert_as_built(r: &Value, doc: &Document) {
    let depth = doc.display_depth;
    let built = doc.build(depth).unwrap();
    let patches = r["patches"].as_array().unwrap();
    assert_eq!(patches.len(), doc.patches.len());
    for (i, p) in patches.iter().enumerate() {
        let pts = &built.patches[i].points[depth as usize];
        assert_eq!(p["name"], doc.patches[i].name.as_str());
        assert_eq!(p["streamlines"], pts.rows());
        assert_eq!(p["points_per_streamline"], pts.cols());
    }
    let seams = r["seams"].as_array().unwrap();
    assert_eq!(seams.len(), built.seams.len());
    for (s, b) in seams.iter().zip(&built.seams) {
        assert_eq!(s["a"], doc.patches[b.a].name.as_str());
        assert_eq!(s["b"], doc.patches[b.b].name.as_str());
        assert_eq!(s["edge"], b.join.edge.name());
        assert_eq!(s["continuity"], b.join.continuity.name());
        for (k, v) in [
            ("gap", b.report.gap),
            ("angle_deg", b.report.angle_deg),
            ("curvature_dev", b.report.curvature_dev),
        ] {
            // serde_json's reader may round the last bit (the ECS test,
            // tests/joined_patches.rs, compares bits)
            let got = s[k].as_f64().unwrap();
            assert!(
                (got - v).abs() <= 4.0 * f64::EPSILON * v.abs(),
                "{k}: {got} vs {v}"
            );
        }
    }
}

#[test]
fn the_shipped_three_patch_scene_reports_its_patches_and_seams_as_the_library_builds_them() {
    let doc = load(&shipped()).unwrap();
    let r = build(&shipped());
    assert_as_built(&r, &doc);
    assert_eq!(r["entities"]["patches"], 3);
    for s in r["seams"].as_array().unwrap() {
        // G2 chain: one net, exact; G1 side: converging with depth (0.18° at depth 4)
        let angle = s["angle_deg"].as_f64().unwrap();
        let bound = if s["continuity"] == "G2" { 1e-9 } else { 0.5 };
        assert!(angle < bound, "{s}");
        assert!(s["gap"].as_f64().unwrap() < 1e-12, "{s}");
    }
}

/// The shipped scene with the screen chained by `continuity`, its first
/// column turned by `degrees` about the streamlines' cross direction.
fn chained(continuity: Continuity, degrees: f64) -> Document {
    let mut doc = load(&shipped()).unwrap();
    doc.patches[1].start = Start::Edge {
        patch: "hood".into(),
        join: Join {
            edge: Edge::End,
            continuity,
        },
    };
    let q = DQuat::from_axis_angle(DVec3::Y, degrees.to_radians());
    for r in 0..doc.patches[1].design.net().rows() {
        let v = doc.patches[1].design.net().get(r, 0);
        doc.patches[1].design.set_tangent(r, 0, q * v).unwrap();
    }
    doc
}

#[test]
fn a_g0_chain_with_a_turned_seam_column_shows_the_angle_and_a_g1_chain_does_not() {
    let g0 = chained(Continuity::G0, 10.0);
    let path = tmp("g0");
    save(&g0, &path).unwrap();
    let r = build(&path);
    assert_as_built(&r, &g0);
    let angle = r["seams"][0]["angle_deg"].as_f64().unwrap();
    assert!(angle > 5.0, "the turned column shows: {angle}°");
    assert!(r["seams"][0]["gap"].as_f64().unwrap() < 1e-12);
    // the control: a G1 chain on the same nets (its seam column is the hood's)
    let g1 = chained(Continuity::G1, 0.0);
    let path = tmp("g1");
    save(&g1, &path).unwrap();
    let r = build(&path);
    assert_as_built(&r, &g1);
    assert_eq!(r["seams"][0]["continuity"], "G1");
    assert!(r["seams"][0]["angle_deg"].as_f64().unwrap() < 1e-6);
}

#[test]
fn a_one_patch_scene_reports_one_patch_main_and_no_seams() {
    let r = build(Path::new(&format!(
        "{}/scenes/car1.ron",
        env!("CARGO_MANIFEST_DIR")
    )));
    let p = r["patches"].as_array().unwrap();
    assert_eq!(p.len(), 1);
    assert_eq!(p[0]["name"], "main");
    assert_eq!(p[0]["streamlines"], r["streamlines"]);
    assert_eq!(p[0]["points_per_streamline"], r["points_per_streamline"]);
    assert_eq!(r["seams"].as_array().unwrap().len(), 0);
    for k in [
        "scene",
        "depth",
        "scheme",
        "blend_order",
        "levels",
        "streamlines",
        "points_per_streamline",
        "triangles",
        "total_length",
        "length_error",
        "timings_us",
        "export",
        "warnings",
        "entities",
    ] {
        assert!(r.get(k).is_some(), "{k}");
    }
}

/// `build --export` of several patches writes them all: a STEP shell of one
/// face per patch, each within its tolerance (the report's `"faces"`), an
/// OBJ object per patch (read back by tobj, each its grid's points), and a
/// refused extension names the file and leaves nothing behind.
#[test]
fn build_exports_every_patch() {
    let dir = tmp("export").parent().unwrap().join("export");
    std::fs::create_dir_all(&dir).unwrap();
    let doc = load(&shipped()).unwrap();
    let built = doc.build(doc.display_depth).unwrap();
    let run = |out: &Path| {
        Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
            .args(["build", shipped().to_str().unwrap(), "--export"])
            .arg(out)
            .output()
            .unwrap()
    };
    let step = dir.join("hsw.step");
    let out = run(&step);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    let faces = r["faces"].as_array().unwrap();
    assert_eq!(faces.len(), doc.patches.len());
    for (f, p) in faces.iter().zip(&doc.patches) {
        assert_eq!(f["name"], p.name.as_str());
        assert!(f["max_deviation"].as_f64().unwrap() <= f["tolerance"].as_f64().unwrap());
    }
    let text = std::fs::read_to_string(&step).unwrap();
    assert_eq!(text.matches("ADVANCED_FACE(").count(), doc.patches.len());
    assert_eq!(
        text.matches("CLOSED_SHELL(").count() + text.matches("OPEN_SHELL(").count(),
        1
    );

    let obj = dir.join("hsw.obj");
    assert!(run(&obj).status.success());
    let (models, _) = tobj::load_obj(&obj, &tobj::LoadOptions::default()).unwrap();
    assert_eq!(models.len(), doc.patches.len());
    for ((m, p), s) in models.iter().zip(&doc.patches).zip(&built.patches) {
        assert_eq!(m.name, p.name);
        let pts = &s.points[doc.display_depth as usize];
        assert_eq!(m.mesh.positions.len(), 3 * pts.rows() * pts.cols());
    }

    let bad = dir.join("hsw.dwg");
    let out = run(&bad);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("hsw.dwg"), "{err}");
    assert!(!bad.exists());
}

/// A design of two patches, the second on its own initial curve with a
/// detail, a fine-tuning function or tangent interpolation: `build` builds
/// it, and a script that loads and saves it writes the second patch's field
/// as it read it (the saved document is the loaded one, field by field).
#[test]
fn a_later_patchs_own_fields_are_kept_through_load_and_save() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/features");
    for (file, key) in [
        ("two-details.ron", "details"),
        ("two-tuning.ron", "tuning"),
        ("two-interpolate.ron", "interpolate_tangents"),
    ] {
        let scene = dir.join(file);
        let out = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
            .args(["build", scene.to_str().unwrap()])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{file}: {err}");

        let work = tmp(&format!("later-{key}")).with_extension("");
        std::fs::create_dir_all(&work).unwrap();
        std::fs::copy(&scene, work.join("two.ron")).unwrap();
        std::fs::write(
            work.join("steps.ron"),
            r#"(steps: [Load("two.ron"), Save("saved.ron")])"#,
        )
        .unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
            .args(["play", work.join("steps.ron").to_str().unwrap()])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{file}: {}",
            String::from_utf8_lossy(&out.stdout)
        );
        let loaded = load(&scene).unwrap();
        let saved = load(&work.join("saved.ron")).unwrap();
        assert_eq!(saved.to_ron(), loaded.to_ron(), "{file}");
        let text = std::fs::read_to_string(work.join("saved.ron")).unwrap();
        let b = text.find("name: \"b\"").unwrap();
        assert!(text[b..].contains(&format!("{key}:")), "{file}: {text}");
        let _ = std::fs::remove_dir_all(&work);
    }
}
