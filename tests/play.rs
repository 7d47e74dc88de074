//! Runs every script in tests/scripts through the ECS (headless), and checks
//! the `play` subcommand's exit codes.

use std::path::Path;
use std::process::Command;
use streamline_studio::ecs::playback;
use streamline_studio::scene::{design::builtin, edits::script::Script};

#[test]
fn every_script_passes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scripts");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    names.sort();
    assert!(
        names.len() >= 10,
        "at least 10 scripts, found {}",
        names.len()
    );
    let mut failed = Vec::new();
    for path in &names {
        let script = Script::load(path).unwrap_or_else(|e| panic!("{e}"));
        let report = playback::play(&script, &dir, builtin::default_scene());
        println!("== {}", path.display());
        for l in &report.lines {
            println!("{l}");
        }
        if !report.passed() {
            failed.push(path.display().to_string());
        }
    }
    assert!(failed.is_empty(), "scripts failed: {failed:?}");
    // Script 08 exported the surface: parse the OBJ back and check the STL size.
    let obj = std::fs::read_to_string(dir.join("out/08-car.obj")).unwrap();
    let v = obj.lines().filter(|l| l.starts_with("v ")).count();
    let vn = obj.lines().filter(|l| l.starts_with("vn ")).count();
    let mut faces = 0;
    for l in obj.lines().filter(|l| l.starts_with("f ")) {
        faces += 1;
        for corner in l[2..].split_whitespace() {
            let (a, b) = corner.split_once("//").expect("v//vn corners");
            let (a, b): (usize, usize) = (a.parse().unwrap(), b.parse().unwrap());
            assert!(
                a >= 1 && a <= v && b >= 1 && b <= vn,
                "index out of range in `{l}`"
            );
        }
    }
    for l in obj
        .lines()
        .filter(|l| l.starts_with("v ") || l.starts_with("vn "))
    {
        assert!(
            l.split_whitespace()
                .skip(1)
                .all(|x| x.parse::<f64>().is_ok_and(f64::is_finite))
        );
    }
    assert_eq!(v, 41 * 66, "41 streamlines of 66 points at depth 3");
    assert_eq!(v, vn);
    assert_eq!(faces, 2 * 40 * 65);
    // An independent OBJ reader (tobj) agrees.
    let (models, _) =
        tobj::load_obj(dir.join("out/08-car.obj"), &tobj::LoadOptions::default()).unwrap();
    let m = &models[0].mesh;
    assert_eq!(m.positions.len(), 3 * v);
    assert_eq!(m.normals.len(), 3 * vn);
    assert_eq!(m.indices.len(), 3 * faces);
    assert!(m.positions.iter().all(|x| x.is_finite()));
    let stl = std::fs::read(dir.join("out/08-car.stl")).unwrap();
    let tris = u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize;
    assert_eq!(tris, faces);
    assert_eq!(stl.len(), 84 + 50 * tris);
    // the same mesh as binary glTF, read back by the gltf crate
    let glb = gltf::Gltf::open(dir.join("out/08-car.glb")).unwrap();
    let prim = glb.meshes().next().unwrap().primitives().next().unwrap();
    assert_eq!(prim.get(&gltf::Semantic::Positions).unwrap().count(), v);
    assert_eq!(prim.get(&gltf::Semantic::Normals).unwrap().count(), v);
    // and the fitted B-spline surface at depth 4 (OpenCascade reads such
    // files back in tests/cad_export.rs)
    let step = std::fs::read_to_string(dir.join("out/08-car.step")).unwrap();
    assert_eq!(step.matches("B_SPLINE_SURFACE_WITH_KNOTS(").count(), 1);
    assert_eq!(step.matches("ADVANCED_FACE(").count(), 1);
    let iges = std::fs::read_to_string(dir.join("out/08-car.igs")).unwrap();
    assert!(iges.lines().all(|l| l.len() == 80));
    walkthrough_export_has_both_halves(&dir);
}

/// Script 21 (the authoring walk-through) exported a mirrored design: one
/// mesh of both halves (9 doubled control rows → 129 streamlines of 82
/// points at depth 4), equal to its reflection in the plane y = 0 (the
/// initial curve starts at 0 along +y), read back by tobj.
fn walkthrough_export_has_both_halves(dir: &Path) {
    let (models, _) = tobj::load_obj(
        dir.join("out/21-walkthrough.obj"),
        &tobj::LoadOptions::default(),
    )
    .unwrap();
    assert_eq!(models.len(), 1, "both halves in one mesh");
    let m = &models[0].mesh;
    let v = m.positions.len() / 3;
    assert_eq!(v, 129 * 82, "129 streamlines of 82 points");
    assert_eq!(
        m.indices.len(),
        3 * 2 * 128 * 81,
        "one mesh over both halves"
    );
    let key = |x: f64, y: f64, z: f64| {
        (
            (x * 1e4).round() as i64,
            (y * 1e4).round() as i64,
            (z * 1e4).round() as i64,
        )
    };
    let points: std::collections::HashSet<_> = m
        .positions
        .chunks(3)
        .map(|p| key(p[0], p[1], p[2]))
        .collect();
    let mirrored = m
        .positions
        .chunks(3)
        .filter(|p| points.contains(&key(p[0], -p[1], p[2])))
        .count();
    assert!(
        mirrored as f64 >= 0.99 * v as f64,
        "{mirrored} of {v} vertices have their reflection (y → −y)"
    );
    assert!(
        m.positions.chunks(3).any(|p| p[1] < -0.5) && m.positions.chunks(3).any(|p| p[1] > 0.5),
        "both sides of y = 0"
    );
    let stl = std::fs::read(dir.join("out/21-walkthrough.stl")).unwrap();
    let tris = u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize;
    assert_eq!(tris, 2 * 128 * 81, "the STL holds both halves too");
}

#[test]
fn play_exit_codes() {
    let bin = env!("CARGO_BIN_EXE_streamline-studio");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let ok = Command::new(bin)
        .args(["play"])
        .arg(dir.join("scripts/11-minimal-flat.ron"))
        .output()
        .unwrap();
    assert_eq!(
        ok.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let out = String::from_utf8_lossy(&ok.stdout);
    assert!(out.lines().count() >= 8, "one line per step:\n{out}");
    // An expectation that fails: exit 1.
    let tmp = std::env::temp_dir().join(format!("ss-fail-{}.ron", std::process::id()));
    std::fs::write(
        &tmp,
        "(steps: [Load(\"builtin:minimal\"), ExpectScene(streamlines: Some(3))])",
    )
    .unwrap();
    let fail = Command::new(bin).arg("play").arg(&tmp).output().unwrap();
    assert_eq!(fail.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&fail.stdout).contains("FAIL streamlines is 5, expected 3"));
    // A broken script: exit 2 with file:line:col.
    std::fs::write(&tmp, "(steps: [\n  Jump,\n])").unwrap();
    let bad = Command::new(bin).arg("play").arg(&tmp).output().unwrap();
    assert_eq!(bad.status.code(), Some(2));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(
        err.contains(&format!("{}:2:", tmp.display())) && err.contains("unknown variant `Jump`"),
        "{err}"
    );
    let _ = std::fs::remove_file(&tmp);
}

/// Scripts write only inside their own folder, links resolved: a symbolic
/// link inside the folder that leads elsewhere is refused, and nothing is
/// written outside (docs/reliability.md, "Scripts are data").
#[test]
fn a_link_out_of_the_script_folder_is_refused() {
    let base = std::env::temp_dir().join(format!("streamline-link-{}", std::process::id()));
    let (dir, outside) = (base.join("scripts"), base.join("outside"));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::create_dir_all(&outside).unwrap();
    std::os::unix::fs::symlink(&outside, dir.join("out")).unwrap();
    std::os::unix::fs::symlink(outside.join("x.ron"), dir.join("file-link.ron")).unwrap();
    let text = r#"(steps: [
        Save("out/scene.ron"),
        ExpectError("through a symbolic link"),
        Save("file-link.ron"),
        ExpectError("through a symbolic link"),
        Export("inside/ok.obj"),
    ])"#;
    let script = Script::parse(text, Path::new("links.ron")).unwrap();
    let report = playback::play(&script, &dir, builtin::default_scene());
    assert!(report.passed(), "{}", report.lines.join("\n"));
    assert_eq!(
        std::fs::read_dir(&outside).unwrap().count(),
        0,
        "nothing was written outside"
    );
    assert!(
        dir.join("inside/ok.obj").is_file(),
        "a plain path inside works"
    );
    let _ = std::fs::remove_dir_all(&base);
}
