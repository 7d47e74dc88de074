//! The headless command line through the real binary: JSON in, JSON out, exit
//! code 2 and a one-line message for bad input.

use std::io::Write;
use std::process::{Command, Stdio};

fn run(args: &[&str], stdin: &str) -> (i32, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary runs");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(stdin.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn vecs(json: &str) -> Vec<[f64; 3]> {
    serde_json::from_str(json).expect("JSON array of vectors")
}

const FIVE: &str = "[[1,0,0.2],[0.8,0.6,0.1],[0.2,0.9,0.4],[-0.3,0.8,0.6],[-0.7,0.4,0.5]]";

#[test]
fn cli_curve_counts_table1() {
    for (scheme, depth, n) in [
        ("chaikin", "7", 386),
        ("cubic-bspline", "7", 259),
        ("four-point", "6", 257),
    ] {
        let (code, out, err) = run(&["curve", "--scheme", scheme, "--depth", depth], FIVE);
        assert_eq!(code, 0, "{scheme}: {err}");
        let v = vecs(&out);
        assert_eq!(v.len(), n, "{scheme} depth {depth}");
        assert!(
            v.iter()
                .all(|p| ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() < 1e-12)
        );
    }
    let (code, out, _) = run(
        &["curve", "--scheme", "qi", "--order", "4", "--samples", "11"],
        FIVE,
    );
    assert_eq!(code, 0);
    assert_eq!(vecs(&out).len(), 11);
}

#[test]
fn cli_surface_and_integrate() {
    let rows = "[[[1,0,0],[1,0.2,0],[1,0.4,0.1]],[[1,0,0.3],[1,0.1,0.3],[1,0.2,0.3]],[[1,0,0],[1,0,0],[1,0,0]]]";
    let (code, out, err) = run(
        &[
            "surface", "--scheme", "kobbelt", "--depth", "2", "--order", "t-first",
        ],
        rows,
    );
    assert_eq!(code, 0, "{err}");
    let r: Vec<Vec<[f64; 3]>> = serde_json::from_str(&out).unwrap();
    assert_eq!((r.len(), r[0].len()), (9, 9));
    let (code, out, err) = run(
        &["integrate"],
        r#"{"tangents": [[1,0,0],[0,1,0],[1,0,0]], "s": [0,1,2], "anchor": 1, "origin": [5,5,5]}"#,
    );
    assert_eq!(code, 0, "{err}");
    let p = vecs(&out);
    // points at arc lengths 0, 0.5, 1.5, 2; the one at s=1 (middle of segment 1) is the origin
    assert_eq!(p.len(), 4);
    assert_eq!(p[1], [5.0, 4.5, 5.0]);
    assert_eq!(p[2], [5.0, 5.5, 5.0]);
}

#[test]
fn cli_bad_input_exit_2_one_line() {
    let cases: &[(&[&str], &str, &str)] = &[
        (
            &["curve", "--scheme", "chaikin"],
            "[[1,0,0],[0,0,0]]",
            "tangent 1 is the zero vector",
        ),
        (
            &["curve", "--scheme", "chaikin"],
            "[[1,0,0],[0,1",
            "stdin:1:",
        ),
        (
            &["curve", "--scheme", "chaikin"],
            "[[1,0,0],[1e999,0,0]]",
            "stdin:1:",
        ),
        (
            &["curve", "--scheme", "four-point", "--omega", "3"],
            FIVE,
            "omega 3 is outside",
        ),
        (
            &["curve", "--scheme", "chaikin", "--depth", "30"],
            FIVE,
            "past the deepest level allowed (16)",
        ),
        (
            &["curve", "--scheme", "qi", "--order", "9"],
            FIVE,
            "QI curve order 9",
        ),
        (
            &["curve", "--scheme", "cubic-bspline"],
            "[[1,0,0]]",
            "at least 3 tangents",
        ),
        (
            &["surface", "--scheme", "kobbelt"],
            "[[[1,0,0],[1,0,0]],[[1,0,0]]]",
            "row 1 has 1 tangents",
        ),
        (
            &["integrate"],
            r#"{"tangents": [[1,0,0],[0,1,0]], "s": [0,0]}"#,
            "does not increase",
        ),
        (
            &["integrate"],
            r#"{"tangents": [[1,0,0],[0,1,0]], "s": [0,1], "bogus": 1}"#,
            "unknown field",
        ),
        (
            &["integrate"],
            r#"{"tangents": [[1,0,0],[0,1,0]], "s": [0,1], "anchor": 7}"#,
            "anchor 7 is out of range",
        ),
        (&["curve", "--scheme", "nope"], "[]", "invalid value"),
    ];
    // 100 tangents refined 16 times: 6.5 million, over the 4 million cap
    let hundred = format!("[{}]", vec!["[1,0,0],[0,1,0]"; 50].join(","));
    let (code, _, err) = run(&["curve", "--scheme", "chaikin", "--depth", "16"], &hundred);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("over the cap of 4000000"), "{err}");
    // a QI curve sampled 10^11 times would need 2.4 TB: refused, not a crash
    let (code, _, err) = run(
        &["curve", "--scheme", "qi", "--samples", "100000000000"],
        "[[1,0,0],[0,1,0],[0,0,1],[1,1,0]]",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("over the cap of 4000000"), "{err}");
    // a sample count the renderer does not offer: clap's usage error, before
    // any window opens
    for args in [
        &["--msaa", "3"][..],
        &["screenshot", "--msaa", "16", "--out", "never.png"],
    ] {
        let (code, _, err) = run(args, "");
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains("give 1 (off), 2, 4 or 8"), "{args:?}: {err}");
    }
    for (args, input, needle) in cases {
        let (code, out, err) = run(args, input);
        assert_eq!(code, 2, "{args:?} {input}: exit code, stderr {err}");
        assert!(out.is_empty(), "{args:?}: nothing on stdout");
        assert!(
            err.contains(needle),
            "{args:?}: stderr {err:?} should mention {needle:?}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        if !args.contains(&"nope") {
            assert_eq!(
                err.trim_end().lines().count(),
                1,
                "{args:?}: one line: {err:?}"
            );
        }
    }
}

#[test]
fn cli_bench_json_rows() {
    let (code, out, err) = run(&["bench", "--json", "--millis", "5"], "");
    assert_eq!(code, 0, "{err}");
    let names: Vec<String> = out
        .lines()
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            assert!(v["median_ns"].as_f64().unwrap() > 0.0 && v["runs"].as_u64().unwrap() > 0);
            v["name"].as_str().unwrap().to_string()
        })
        .collect();
    for want in [
        "curve/chaikin/d7",
        "curve/cubic-bspline/d7",
        "curve/four-point/d6",
        "curve/qi-k3/257",
        "curve/qi-k4/257",
        "curve/qi-k5/257",
        "surface/kobbelt/9x6/d3/full",
        "surface/kobbelt/9x6/d5/full",
        "fit/car/d5",
        "export/hood-screen-wing/d4/step",
        "ecs/car/d6/drag-cold",
        "reference-fit/roof/d5",
        "reference-deviation/car/d5",
    ] {
        assert!(
            names.iter().any(|n| n == want),
            "bench row {want} in {names:?}"
        );
    }
}

#[test]
fn cli_help_on_every_subcommand() {
    for sub in [
        "curve",
        "surface",
        "integrate",
        "bench",
        "play",
        "build",
        "screenshot",
        "interpolate",
    ] {
        let (code, out, _) = run(&[sub, "--help"], "");
        assert_eq!(code, 0);
        assert!(out.contains("Usage"), "{sub} --help");
    }
}

#[test]
fn cli_build_prints_stats_and_exports() {
    let dir = std::env::temp_dir().join(format!("ss-build-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/car1.ron");
    let stl = dir.join("car.stl");
    let (code, out, err) = run(
        &[
            "build",
            scene,
            "--depth",
            "3",
            "--export",
            stl.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["streamlines"], 41);
    assert_eq!(v["points_per_streamline"], 66);
    assert_eq!(v["levels"][3], serde_json::json!([41, 65]));
    // Eq. 65: each streamline's length is exactly s_n − s_0 (to rounding).
    assert!(
        v["length_error"]["max_abs"].as_f64().unwrap() < 1e-12,
        "{out}"
    );
    assert_eq!(
        v["length_error"]["per_streamline"]
            .as_array()
            .unwrap()
            .len(),
        41
    );
    assert!(v["timings_us"]["us_blend"].as_f64().unwrap() > 0.0);
    let bytes = std::fs::read(&stl).unwrap();
    assert_eq!(bytes.len(), 84 + 50 * 2 * 40 * 65);
    // Bad scene file: exit 2, file:line:col.
    let bad = dir.join("bad.ron");
    std::fs::write(&bad, "(version: 1, tangents: [[(0,0,0)]])").unwrap();
    let (code, _, err) = run(&["build", bad.to_str().unwrap()], "");
    assert_eq!(code, 2);
    assert!(err.contains(&format!("{}:1:", bad.display())), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "one line: {err}");
    // Depth past the cap: exit 2.
    let (code, _, err) = run(&["build", "car1", "--depth", "13"], "");
    assert_eq!(code, 2, "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `build --export` of the fitted B-spline surface (docs/math.md §10): the format by
/// the extension, the fit in the JSON report; refusals exit 2, write nothing
/// and keep the old file.
#[test]
fn cli_build_exports_step_and_iges_with_the_fit() {
    let dir = std::env::temp_dir().join(format!("ss-cad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, head) in [
        ("car.step", "ISO-10303-21;"),
        ("car.stp", "ISO-10303-21;"),
        ("car.igs", "Streamline Studio"),
        ("car.IGES", "Streamline Studio"),
    ] {
        let path = dir.join(name);
        let (code, out, err) = run(
            &[
                "build",
                "car1",
                "--depth",
                "4",
                "--export",
                path.to_str().unwrap(),
            ],
            "",
        );
        assert_eq!(code, 0, "{name}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let fit = &v["fit"];
        assert_eq!(fit["degree"], serde_json::json!([3, 3]), "{out}");
        let tol = fit["tolerance"].as_f64().unwrap();
        let max = fit["max_deviation"].as_f64().unwrap();
        let mean = fit["mean_deviation"].as_f64().unwrap();
        assert!(0.0 < mean && mean <= max && max <= tol, "{out}");
        assert!(fit["poles"][0].as_u64().unwrap() >= 4 && fit["seconds"].as_f64().unwrap() > 0.0);
        // one patch lists its face as several patches list theirs
        let faces = v["faces"].as_array().expect("a CAD export lists its faces");
        assert_eq!(faces.len(), 1, "{out}");
        let f = &faces[0];
        assert_eq!(
            (&f["poles"], &f["depth"]),
            (&fit["poles"], &fit["depth"]),
            "{out}"
        );
        assert_eq!(
            (&f["max_deviation"], &f["tolerance"]),
            (&fit["max_deviation"], &fit["tolerance"])
        );
        assert!(
            std::fs::read_to_string(&path).unwrap().starts_with(head),
            "{name}"
        );
    }
    // an absolute tolerance and a degree per direction
    let path = dir.join("loose.step");
    let (code, out, err) = run(
        &[
            "build",
            "car1",
            "--depth",
            "4",
            "--export",
            path.to_str().unwrap(),
            "--tolerance",
            "0.01",
            "--degree",
            "4,2",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["fit"]["tolerance"], 0.01);
    assert_eq!(v["fit"]["degree"], serde_json::json!([4, 2]));
    // the mesh formats report no fit
    let glb = dir.join("car.glb");
    let (code, out, _) = run(
        &[
            "build",
            "car1",
            "--depth",
            "3",
            "--export",
            glb.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0);
    assert!(
        serde_json::from_str::<serde_json::Value>(&out)
            .unwrap()
            .get("fit")
            .is_none()
    );
    // refusals keep the old file
    let old = dir.join("old.step");
    std::fs::write(&old, "old").unwrap();
    for (args, want) in [
        (vec!["--tolerance", "0"], "positive finite"),
        (vec!["--tolerance", "nan"], "positive finite"),
        (vec!["--relative-tolerance", "-1e-4"], "positive finite"),
        (vec!["--degree", "6"], "outside 2 to 5"),
        (vec!["--degree", "1,3"], "outside 2 to 5"),
        (vec!["--degree", "three"], "whole number"),
        (
            vec!["--tolerance", "1e-9"],
            "the deepest an export samples (the closest it came was",
        ),
    ] {
        let mut a = vec![
            "build",
            "car1",
            "--depth",
            "2",
            "--export",
            old.to_str().unwrap(),
        ];
        a.extend(&args);
        let (code, _, err) = run(&a, "");
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "one line: {err}");
        assert_eq!(std::fs::read_to_string(&old).unwrap(), "old", "{args:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `interpolate` (paper 002): JSON report, the control mesh written with the
/// input's vertex count and faces, a surface by subdivision, bad meshes exit 2.
#[test]
fn cli_interpolate_writes_the_control_mesh() {
    let dir = std::env::temp_dir().join(format!("streamline-cli-pi-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/meshes/snail.obj");
    let out = dir.join("ctrl.obj");
    let surf = dir.join("surf.obj");
    let (code, stdout, stderr) = run(
        &[
            "interpolate",
            input,
            "--method",
            "fast",
            "--tolerance",
            "1e-6",
            "--out",
            out.to_str().unwrap(),
            "--subdivide",
            "1",
            "--surface",
            surf.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    let j: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(j["vertices"], 871);
    assert_eq!(j["faces"], 1653);
    assert_eq!(j["boundary_loops"], 1);
    assert_eq!(j["converged"], true);
    assert!(j["max_error"].as_f64().unwrap() < 1e-6, "{j}");
    for key in ["method", "iterations", "avg_error", "seconds"] {
        assert!(j.get(key).is_some(), "{key} in {j}");
    }
    // the control mesh keeps the input's faces, line for line
    let faces = |p: &std::path::Path| -> Vec<String> {
        std::fs::read_to_string(p)
            .unwrap()
            .lines()
            .filter(|l| l.starts_with("f "))
            .map(str::to_string)
            .collect()
    };
    let given: Vec<String> = faces(std::path::Path::new(input));
    assert_eq!(faces(&out), given, "same faces in the same order");
    let v = std::fs::read_to_string(&out)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("v "))
        .count();
    assert_eq!(v, 871);
    assert_eq!(faces(&surf).len(), 4 * 1653, "one level of subdivision");
    // bad meshes: exit 2, one line naming the file and the element
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nf 1 2 3\n").unwrap();
    let (code, _, stderr) = run(&["interpolate", bad.to_str().unwrap()], "");
    assert_eq!(code, 2);
    assert!(
        stderr.contains("bad.obj")
            && stderr.contains("vertex 4 is used by no face")
            && stderr.lines().count() == 1,
        "{stderr}"
    );
    let (code, _, stderr) = run(&["interpolate", input, "--tolerance", "-1"], "");
    assert_eq!(code, 2, "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `play w.ron` from the script's own folder: a bare file name's folder is
/// the current one, so its Save and Export steps write beside it.
#[test]
fn cli_play_a_script_named_by_a_bare_file_name() {
    let dir = std::env::temp_dir().join(format!("ss-play-bare-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("w.ron"),
        "(steps: [\n    Load(\"builtin:minimal\"),\n    Save(\"out/w.ron\"),\n    Export(\"out/w.obj\"),\n])\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
        .args(["play", "w.ron"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.join("out/w.ron").is_file() && dir.join("out/w.obj").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Antipodal neighbours (docs/math.md §1) are warnings naming the tangents:
/// in `build --json` (`"warnings"`, empty for the shipped car), as a
/// `warning:` line of `play` after the step that made them, and gone again
/// after the step that undoes it. The same scene through `build` reports the
/// same pair from its own levels.
#[test]
fn antipodal_blends_are_warnings() {
    let dir = std::env::temp_dir().join(format!("streamline-antipodal-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let (code, out, err) = run(&["build", "car1", "--depth", "3"], "");
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        v["warnings"],
        serde_json::json!([]),
        "the car blends no antipodes"
    );
    let script = dir.join("antipodal.ron");
    let scene = dir.join("antipodal-scene.ron");
    std::fs::write(
        &script,
        r#"(steps: [
    Load("builtin:car1"),
    SetDirection(row: 2, col: 4, dir: (1.0, 0.0, 0.5)),
    SetDirection(row: 2, col: 5, dir: (-1.0, 0.0, -0.5)),
    Save("antipodal-scene.ron"),
    Undo,
])"#,
    )
    .unwrap();
    let (code, out, err) = run(&["play", script.to_str().unwrap()], "");
    assert_eq!(code, 0, "{out}{err}");
    let lines: Vec<&str> = out.lines().collect();
    let warning = lines
        .iter()
        .position(|l| l.contains("warning: antipodal blend between (2, 4) and (2, 5)"))
        .unwrap_or_else(|| panic!("no warning line:\n{out}"));
    assert!(
        lines[warning].starts_with("step   3 warning:"),
        "after the step that made it: {out}"
    );
    assert_eq!(
        lines.iter().filter(|l| l.contains("warning:")).count(),
        1,
        "said once, not again after every step:\n{out}"
    );
    let (code, out, err) = run(&["build", scene.to_str().unwrap()], "");
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let w = v["warnings"].as_array().expect("a list");
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].as_str()
            .unwrap()
            .starts_with("antipodal blend between (2, 4) and (2, 5): "),
        "{w:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
