//! A design fitted and measured in scripts and builds (docs/math.md §12,
//! docs/scenes.md): a script's `Fit` step replaces the design with one
//! fitted to a STEP face and keeps the face as its reference;
//! `ExpectReferenceDeviation` measures the design against it (within after
//! the fit and after undo, above once a tangent is turned); a bad face, a
//! missing file, a fit short of its tolerance and a design without a
//! reference are the step's errors, located at the step; `build` reports the
//! distance to the reference, equal to the kernel's own measure of the same
//! points, and the error, still exiting 0, when the file has moved. Each
//! with a negative control.

use std::path::{Path, PathBuf};
use std::process::Command;
use streamline_kernel::fit::distances_to_reference;
use streamline_studio::scene::design::document_io;

/// The hood's tolerance: 1e-4 of its diagonal, in metres (docs/fit.md).
const HOOD_TOLERANCE: f64 = 1.8e-4;

/// Runs the binary: exit code, stdout, stderr.
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

/// A fresh folder holding `refs/hood.step` (a copy of the shipped
/// reference), named by `tag` and the process.
fn folder(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ss-reference-script-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("refs")).unwrap();
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.step");
    std::fs::copy(shipped, d.join("refs/hood.step")).unwrap();
    d
}

/// Writes `steps` as the script `dir/NAME.ron` and plays it: exit code and
/// stdout (every step's line).
fn play(dir: &Path, name: &str, steps: &str) -> (i32, String) {
    let script = dir.join(format!("{name}.ron"));
    std::fs::write(&script, format!("(steps: [\n{steps}\n])\n")).unwrap();
    let (code, out, err) = run(&["play", script.to_str().unwrap()]);
    println!("{out}{err}");
    (code, out)
}

/// The line of step `n`.
fn line(out: &str, n: usize) -> &str {
    let head = format!("step {n:>3} ");
    out.lines()
        .find(|l| l.starts_with(&head))
        .unwrap_or_else(|| panic!("no line for step {n} in\n{out}"))
}

/// The largest and mean distance from the points of the design in `scene`
/// at `depth` (built by the kernel, not the ECS) to face 0 of `reference`,
/// measured by the kernel directly.
fn direct(scene: &Path, reference: &Path, depth: u32) -> (f64, f64) {
    let scene = document_io::load_scene(scene).unwrap();
    let built = scene.design.build(depth).unwrap();
    let file = streamline_reference::read(reference).unwrap();
    let d = distances_to_reference(file.surface(0).unwrap(), &built.mesh.positions).unwrap();
    let max = d.iter().copied().fold(0.0, f64::max);
    (max, d.iter().sum::<f64>() / d.len() as f64)
}

const FIT: &str = r#"Fit(path: "refs/hood.step", face: 0, along: U, tolerance: Relative(1e-4))"#;

#[test]
fn fit_replaces_the_design_and_keeps_the_reference() {
    let dir = folder("replace");
    let (code, out) = play(
        &dir,
        "fit",
        &format!(
            r#"Mark("car"),
            {FIT},
            ExpectScene(display_depth: Some(5), rows: Some(9), cols: Some(8), can_undo: Some(false)),
            ExpectChanged(mark: "car", tolerance: 1e-3),
            Save("out/fitted.ron"),"#
        ),
    );
    assert_eq!(code, 0, "{out}");
    assert!(line(&out, 2).contains("a 9 × 8 net at depth 5"), "{out}");
    // the saved design names the face relative to itself, and reads back
    // resolved to the copy in this folder
    let saved = dir.join("out/fitted.ron");
    let text = std::fs::read_to_string(&saved).unwrap();
    assert!(text.contains(r#"path: "../refs/hood.step""#), "{text}");
    let scene = document_io::load_scene(&saved).unwrap();
    let link = scene
        .reference
        .expect("the fitted design keeps its reference");
    assert_eq!(link.path, dir.join("refs/hood.step"));
    assert_eq!(link.face, 0);
    assert_eq!(scene.display_depth, 5);
    assert_eq!(
        (scene.design.net().rows(), scene.design.net().cols()),
        (9, 8)
    );
    // the same design the `fit` command makes (defaults alike)
    let cli = dir.join("out/cli.ron");
    let (code, _, err) = run(&[
        "fit",
        dir.join("refs/hood.step").to_str().unwrap(),
        "--out",
        cli.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let by_cli = document_io::load_scene(&cli).unwrap();
    assert_eq!(by_cli.design.net(), scene.design.net());
    // negative control: the step's options reach the fit; along v (within
    // 1e-2 of the diagonal) is another design
    let (code, out) = play(
        &dir,
        "along-v",
        r#"Fit(path: "refs/hood.step", along: V, tolerance: Relative(1e-2)),
            ExpectScene(rows: Some(4), cols: Some(15)),"#,
    );
    assert_eq!(code, 0, "{out}");
}

#[test]
fn deviation_holds_within_and_fails_above() {
    let dir = folder("deviation");
    let (code, out) = play(
        &dir,
        "within",
        &format!(
            r#"{FIT},
            ExpectReferenceDeviation(max: {HOOD_TOLERANCE:e}),
            Mark("fitted"),
            Rotate(row: 4, col: 3, axis: (0.0, 0.0, 1.0), degrees: 8.0),
            ExpectReferenceDeviation(max: 1.0, min: Some(5e-4)),
            Undo,
            ExpectSame(mark: "fitted", tolerance: 0.0),
            ExpectReferenceDeviation(max: {HOOD_TOLERANCE:e}),
            Save("out/fitted.ron"),"#
        ),
    );
    assert_eq!(code, 0, "{out}");
    // what the step measured is the kernel's measure of the same design
    let (max, _) = direct(&dir.join("out/fitted.ron"), &dir.join("refs/hood.step"), 5);
    assert!(max < HOOD_TOLERANCE, "{max}");
    assert!(
        line(&out, 2).contains(&format!("largest distance {max:.2e}")),
        "{out}"
    );
    assert!(
        line(&out, 8).contains(&format!("largest distance {max:.2e}")),
        "{out}"
    );
    // negative controls: the turned tangent is over the tolerance, and the
    // fitted design is not above a bound it is within; each failure says
    // what it measured
    let (code, out) = play(
        &dir,
        "above",
        &format!(
            r#"{FIT},
            ExpectReferenceDeviation(max: 1.0, min: Some({HOOD_TOLERANCE:e})),
            Rotate(row: 4, col: 3, axis: (0.0, 0.0, 1.0), degrees: 8.0),
            ExpectReferenceDeviation(max: {HOOD_TOLERANCE:e}),"#
        ),
    );
    assert_eq!(code, 1, "{out}");
    assert!(
        line(&out, 2).contains(&format!("FAIL the design is at most {max:.3e} from")),
        "{out}"
    );
    let turned = line(&out, 4);
    assert!(turned.contains("FAIL the design is up to "), "{out}");
    let figure: f64 = turned
        .split("up to ")
        .nth(1)
        .and_then(|r| r.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    assert!(figure > 5e-4, "{turned}");
}

#[test]
fn bad_fits_are_the_steps_located_errors() {
    let dir = folder("errors");
    // each refused, the design kept, each expected
    let (code, out) = play(
        &dir,
        "expected",
        r#"Mark("car"),
            Fit(path: "refs/hood.step", face: 5),
            ExpectError("there is no face 5: the file has 1 face (0)"),
            Fit(path: "refs/gone.step"),
            ExpectError("gone.step: cannot read the file"),
            Fit(path: "refs/hood.step", tolerance: Absolute(1e-9), max_net: Some((4, 4))),
            ExpectError("not within the tolerance 1.000e-9"),
            Fit(path: "refs/hood.step", depth: 9),
            ExpectError("depth"),
            ExpectSame(mark: "car", tolerance: 0.0),
            ExpectScene(can_undo: Some(false)),
            ExpectReferenceDeviation(max: 1.0),
            ExpectError("has no reference"),"#,
    );
    assert_eq!(code, 0, "{out}");
    // not expected: each fails the script, at its step, naming the file
    let hood = dir.join("refs/hood.step");
    for (steps, n, says) in [
        (
            r#"Mark("m"), Fit(path: "refs/hood.step", face: 5),"#,
            2,
            format!("{}: there is no face 5", hood.display()),
        ),
        (
            r#"Mark("m"), Fit(path: "refs/gone.step"),"#,
            2,
            format!(
                "{}: cannot read the file",
                dir.join("refs/gone.step").display()
            ),
        ),
        (
            r#"Mark("m"), ExpectReferenceDeviation(max: 1.0),"#,
            2,
            "the design has no reference".to_string(),
        ),
    ] {
        let (code, out) = play(&dir, "unexpected", steps);
        assert_eq!(code, 1, "{out}");
        assert!(line(&out, n).contains(&format!("error {says}")), "{out}");
        assert!(
            out.contains(&format!("step {n:>3}: FAIL unexpected error: {says}")),
            "{out}"
        );
    }
    // saved and opened again, the design is measured against the same
    // file; its bytes copied where `../refs/hood.step` names no file,
    // measuring it is the step's error
    let (code, out) = play(
        &dir,
        "moved",
        &format!(
            r#"{FIT},
            Save("out/fitted.ron"),
            NewDesign(rows: 4, cols: 5, length: 2.0, template: Flat(width: 1.0)),
            Load("out/fitted.ron"),
            ExpectReferenceDeviation(max: {HOOD_TOLERANCE:e}),"#
        ),
    );
    assert_eq!(code, 0, "{out}");
    let far = dir.join("far/away");
    std::fs::create_dir_all(&far).unwrap();
    std::fs::copy(dir.join("out/fitted.ron"), far.join("fitted.ron")).unwrap();
    let (code, out) = play(
        &far,
        "measure",
        r#"Load("fitted.ron"),
            ExpectReferenceDeviation(max: 1.0),
            ExpectError("hood.step: cannot read the file"),"#,
    );
    assert_eq!(code, 0, "{out}");
}

/// `build`'s report as JSON, and its exit code.
fn build(args: &[&str]) -> (i32, serde_json::Value) {
    let mut all = vec!["build"];
    all.extend_from_slice(args);
    let (code, out, err) = run(&all);
    assert_eq!(code, 0, "{err}");
    (code, serde_json::from_str(&out).unwrap())
}

#[test]
fn build_reports_the_distance_to_the_reference() {
    let dir = folder("build");
    let hood = dir.join("refs/hood.step");
    let design = dir.join("designs/hood.ron");
    std::fs::create_dir_all(dir.join("designs")).unwrap();
    let (code, _, err) = run(&[
        "fit",
        hood.to_str().unwrap(),
        "--out",
        design.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let mut maxima = Vec::new();
    for depth in [None, Some(3)] {
        let d = depth.map(|d| d.to_string());
        let mut args = vec![design.to_str().unwrap()];
        if let Some(d) = &d {
            args.extend(["--depth", d]);
        }
        let (_, json) = build(&args);
        let r = &json["reference"];
        let at = depth.unwrap_or(5);
        assert_eq!(json["depth"], at);
        assert_eq!(r["path"], hood.display().to_string(), "{r}");
        assert_eq!(r["face"], 0);
        assert!(r.get("error").is_none(), "{r}");
        let (max, mean) = direct(&design, &hood, at);
        let got = (
            r["deviation"]["max"].as_f64().unwrap(),
            r["deviation"]["mean"].as_f64().unwrap(),
        );
        assert!((got.0 - max).abs() <= 1e-12, "depth {at}: {got:?} vs {max}");
        assert!(
            (got.1 - mean).abs() <= 1e-12,
            "depth {at}: {got:?} vs {mean}"
        );
        assert!(max <= HOOD_TOLERANCE, "depth {at}: {max}");
        maxima.push(max);
    }
    // negative control: the build depth's own points are measured (depth 3
    // is another figure, which the depth-5 report is not)
    assert!((maxima[0] - maxima[1]).abs() > 1e-7, "{maxima:?}");
    // a design without a reference has no key
    let (_, json) = build(&["car1"]);
    assert!(json.get("reference").is_none());
    // the reference file moved away: the error, and the build still exits 0
    std::fs::rename(&hood, dir.join("refs/moved.step")).unwrap();
    let (code, json) = build(&[design.to_str().unwrap()]);
    assert_eq!(code, 0);
    let r = &json["reference"];
    assert_eq!(r["path"], hood.display().to_string());
    assert_eq!(r["face"], 0);
    assert!(r.get("deviation").is_none(), "{r}");
    let error = r["error"].as_str().unwrap();
    assert!(
        error.contains("hood.step") && error.contains("cannot read the file"),
        "{error}"
    );
    assert!(json["streamlines"].as_u64().unwrap() > 0);
}

/// The editor's File ▸ Run script: a `Fit` step's fit runs off the frame
/// (frames keep coming meanwhile), and the steps after it act on the
/// fitted design.
#[test]
fn the_editor_runs_a_fit_off_the_frame() {
    use std::time::{Duration, Instant};
    use streamline_studio::ecs::runner::{RunState, ScriptRun, ScriptRunPlugin};
    use streamline_studio::ecs::{self, headless_app};
    use streamline_studio::scene::design::builtin;
    let dir = folder("runner");
    let script = dir.join("fit.ron");
    std::fs::write(
        &script,
        format!(
            "(steps: [{FIT}, ExpectReferenceDeviation(max: 1.0), \
             Rotate(row: 4, col: 3, axis: (0.0, 0.0, 1.0), degrees: 8.0)])"
        ),
    )
    .unwrap();
    let mut app = headless_app(builtin::scene("car1").unwrap());
    app.add_plugins(ScriptRunPlugin);
    app.world_mut()
        .resource_mut::<ScriptRun>()
        .start(script.clone());
    let start = Instant::now();
    let mut frames = 0;
    let line = loop {
        app.update();
        frames += 1;
        if let RunState::Done(line) = &app.world().resource::<ScriptRun>().state {
            break line.clone();
        }
        assert!(start.elapsed() < Duration::from_secs(120), "the run hangs");
        std::thread::sleep(Duration::from_millis(2));
    };
    app.update();
    assert!(
        line.contains("ran 3 steps (2 edits; 1 expectations skipped") && !line.contains("refused"),
        "{line}"
    );
    assert!(frames > 3, "frames ran while the fit did: {frames}");
    let scene = ecs::patch::try_scene(app.world()).unwrap();
    assert_eq!(
        scene.reference.as_ref().map(|r| (r.path.clone(), r.face)),
        Some((dir.join("refs/hood.step"), 0))
    );
    assert_eq!(
        (scene.design.net().rows(), scene.design.net().cols()),
        (9, 8)
    );
    // the rotation came after the fit: one undo step on the fitted design
    assert_eq!(app.world().resource::<ecs::History>().undo_len(), 1);
}
