//! The editor as a user sees it, on a virtual X display with Mesa's software
//! Vulkan (installed by scripts/setup.sh): screenshots are decoded and checked
//! for the surface and the panel; a real pointer (xdotool) drags an arrow, and
//! Esc cancels a drag.

use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_streamline-studio");

/// The editor renders in software (llvmpipe): one GUI run at a time keeps the
/// frame rate, and so the pointer and key timings, sane on a 2-core machine.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn gui_lock() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("streamline-gui-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `screenshot` with `args` at 800×600 and returns the decoded RGB pixels.
fn shot(dir: &Path, name: &str, args: &[&str]) -> (u32, u32, Vec<[u8; 3]>) {
    shot_sized(dir, name, "800x600", args)
}

/// [`shot`] at `size` (`WxH`).
fn shot_sized(dir: &Path, name: &str, size: &str, args: &[&str]) -> (u32, u32, Vec<[u8; 3]>) {
    let out = dir.join(format!("{name}.png"));
    let run = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", BIN, "screenshot"])
        .args(args)
        .args(["--size", size, "--out"])
        .arg(&out)
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run is installed by scripts/setup.sh");
    assert!(
        run.status.success(),
        "screenshot failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&out).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    assert!(channels >= 3, "{:?}", info.color_type);
    let px = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    (info.width, info.height, px)
}

/// Share of pixels in the 3D view (right of the panel, below the toolbar,
/// left of the sphere inset) that satisfy `f`.
fn share(w: u32, h: u32, px: &[[u8; 3]], f: impl Fn([u8; 3]) -> bool) -> f64 {
    let (mut n, mut hit) = (0usize, 0usize);
    for y in (h / 10)..(h * 9 / 10) {
        for x in (w * 2 / 5)..(w * 7 / 10) {
            n += 1;
            hit += f(px[(y * w + x) as usize]) as usize;
        }
    }
    hit as f64 / n as f64
}

#[test]
fn screenshots_show_the_surface_panels_and_curvature() {
    let _gui = gui_lock();
    let dir = temp_dir("shots");
    // shaded: the light blue-grey surface covers a good part of the view
    let (w, h, px) = shot(&dir, "shaded", &["car1"]);
    let surface = share(w, h, &px, |[r, g, b]| r.min(g).min(b) > 120 && b >= r);
    assert!(surface > 0.08, "surface covers {surface:.3} of the view");
    // the panel (left 200 px) has text: light pixels on the dark panel
    let text = (0..h * w)
        .filter(|i| i % w < 200)
        .filter(|&i| px[i as usize].iter().all(|&c| c > 150))
        .count();
    assert!(text > 300, "{text} text pixels in the panel");
    // a sample count the adapter may not offer (llvmpipe offers 1 and 4 only;
    // asking 8 of it once broke every render pass): the nearest offered one
    let (w, h, px) = shot(&dir, "msaa8", &["car1", "--msaa", "8"]);
    let surface = share(w, h, &px, |[r, g, b]| r.min(g).min(b) > 120 && b >= r);
    assert!(
        surface > 0.08,
        "with --msaa 8 the surface covers {surface:.3}"
    );
    // Gaussian curvature: the car has domes (red) and saddles (blue)
    let (w, h, px) = shot(
        &dir,
        "gauss",
        &["car1", "--analysis", "gaussian", "--panel", "analysis"],
    );
    let red = share(w, h, &px, |[r, g, b]| {
        r as i32 > b as i32 + 60 && r as i32 > g as i32 + 40
    });
    let blue = share(w, h, &px, |[r, _, b]| b as i32 > r as i32 + 60);
    assert!(red > 0.0008 && blue > 0.002, "red {red:.4}, blue {blue:.4}");
    // zebra: black and white stripes on the surface
    let (w, h, px) = shot(&dir, "zebra", &["car1", "--analysis", "zebra"]);
    let black = share(w, h, &px, |p| p.iter().all(|&c| c < 35));
    let white = share(w, h, &px, |p| p.iter().all(|&c| c > 180));
    assert!(
        black > 0.02 && white > 0.02,
        "black {black:.3}, white {white:.3}"
    );
    // deviation map: car1 fits within the tolerance, so the surface is green
    let (w, h, px) = shot(&dir, "deviation", &["car1", "--analysis", "deviation"]);
    let green = share(w, h, &px, |[r, g, b]| {
        g as i32 > r as i32 + 60 && g as i32 > b as i32 + 50
    });
    let red = share(w, h, &px, |[r, g, b]| {
        r as i32 > g as i32 + 80 && r as i32 > b as i32 + 80
    });
    assert!(
        green > 0.05 && red < 0.001,
        "green {green:.3}, red {red:.4}"
    );
    // fine tuning: the panel's sliders and labels, and the plot of α in yellow
    // (the panel is 300 px wide: count only inside it; 680 px high, so that
    // the plot fits under the menu bar, the toolbar and the sliders)
    let (w, h, px) = shot_sized(
        &dir,
        "tuning",
        "800x680",
        &["car1-tuned", "--panel", "tuning"],
    );
    let in_panel = |f: &dyn Fn([u8; 3]) -> bool| {
        (0..h * w)
            .filter(|i| i % w < 280)
            .filter(|&i| f(px[i as usize]))
            .count()
    };
    let text = in_panel(&|p| p.iter().all(|&c| c > 150));
    let plot = in_panel(&|[r, g, b]| r > 200 && g > 150 && b < 110);
    assert!(text > 300, "{text} text pixels in the fine-tuning panel");
    assert!(plot > 40, "{plot} yellow pixels of the α plot");
    // mesh mode (paper 002): the interpolating Loop surface (tan) under the
    // given mesh's edges (blue), and the panel's figures
    let knight = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/meshes/knight.obj");
    let (w, h, px) = shot(&dir, "mesh", &["--mesh", knight, "--panel", "mesh"]);
    let tan = share(w, h, &px, |[r, g, b]| {
        r > 150 && (r as i32) > b as i32 + 40 && g as i32 > b as i32 + 10
    });
    let edges = share(w, h, &px, |[r, _, b]| b as i32 > r as i32 + 80);
    assert!(tan > 0.02, "Loop surface covers {tan:.3} of the view");
    assert!(
        edges > 0.002,
        "given mesh edges cover {edges:.4} of the view"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[derive(serde::Deserialize, Debug)]
struct Report {
    #[serde(default)]
    path: Option<PathBuf>,
    undo: usize,
    last_edit: String,
    selection: Option<(usize, usize)>,
    net: Vec<[f64; 3]>,
    cols: usize,
    shown_gap: Option<f64>,
}

fn drag(dir: &Path, mode: &str) -> Report {
    let report = dir.join(format!("{mode}.json"));
    let run = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", "bash"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gui/drag.sh"))
        .arg(BIN)
        .arg(dir.join("drag.png"))
        .arg(&report)
        .arg(mode)
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run and xdotool are installed by scripts/setup.sh");
    assert!(
        run.status.success(),
        "drag run failed: {}{}",
        String::from_utf8_lossy(&run.stderr),
        std::fs::read_to_string(report.with_extension("json.log")).unwrap_or_default()
    );
    serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap()
}

/// A left drag on the arrow of control tangent (0, 8) turns it (one undo step);
/// the same drag with Esc pressed before release leaves it exactly as it was;
/// dragging its point on the sphere view turns it too.
#[test]
fn pointer_drag_turns_an_arrow_and_esc_cancels() {
    let _gui = gui_lock();
    let dir = temp_dir("drag");
    let start = streamline_studio::scene::builtin::default_scene()
        .design
        .net()
        .get(0, 8)
        .to_array();
    let moved = drag(&dir, "arrow");
    let d = moved.net[8];
    assert_eq!(moved.cols, 9);
    let turn =
        ((d[0] - start[0]).powi(2) + (d[1] - start[1]).powi(2) + (d[2] - start[2]).powi(2)).sqrt();
    assert!(turn > 0.05, "the arrow turned by {turn}: {moved:?}");
    assert_eq!(moved.undo, 1, "a drag is one undo step");
    // the rows and columns rewritten in place, frame by frame, in the
    // surface mesh and the sphere view's points are all there is to change
    assert_eq!(moved.shown_gap, Some(0.0), "the views show the model");
    let cancelled = drag(&dir, "esc");
    assert_eq!(cancelled.shown_gap, Some(0.0), "the views show the model");
    assert_eq!(cancelled.net[8], start, "Esc restores the direction");
    assert_eq!(cancelled.undo, 0, "a cancelled drag leaves no undo step");
    assert!(
        cancelled.last_edit.contains("cancel"),
        "{}",
        cancelled.last_edit
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn editor_without_display_says_what_to_do() {
    let out = Command::new(BIN)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no display found") && err.contains("xvfb-run"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    // a scene file is read (and checked) before the window opens
    let run = |arg: &str| {
        let out = Command::new(BIN)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .arg(arg)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).to_string(),
        )
    };
    let (code, err) = run("scenes/car2.ron");
    assert_eq!(code, Some(2));
    assert!(err.contains("no display found"), "{err}");
    let (code, err) = run("tests/bad/scenes/zero-tangent.ron");
    assert_eq!(code, Some(2));
    assert!(
        err.contains("zero-tangent.ron:5:24") && err.contains("non-zero direction"),
        "{err}"
    );
}

/// A display but no graphics adapter (Vulkan pointed at nothing): a message
/// that says what to do, exit code 2, no panic report.
#[test]
fn editor_without_adapter_says_what_to_do() {
    let _gui = gui_lock();
    let dir = temp_dir("noadapter");
    let out = Command::new("xvfb-run")
        .args([
            "-a",
            "-s",
            "-screen 0 1280x800x24",
            BIN,
            "screenshot",
            "--out",
        ])
        .arg(dir.join("x.png"))
        .env("VK_ICD_FILENAMES", dir.join("none.json"))
        .env("WGPU_BACKEND", "vulkan")
        .env_remove("DISPLAY")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("no usable graphics adapter") && err.contains("mesa-vulkan-drivers"),
        "{err}"
    );
    assert!(!err.contains("panicked at"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The File dialogs with the keyboard: Ctrl+O, a typed path and Enter open a
/// scene; Ctrl+Shift+S, Ctrl+A, a typed path and Enter save it there (atomic,
/// verified); the saved file loads back as the opened scene.
#[test]
fn file_dialogs_open_and_save_as() {
    let _gui = gui_lock();
    let dir = temp_dir("files");
    let open = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/car2.ron");
    let save = dir.join("saved.ron");
    let report = dir.join("files.json");
    let run = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", "bash"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gui/files.sh"))
        .arg(BIN)
        .arg(dir.join("files.png"))
        .arg(&report)
        .arg(&open)
        .arg(&save)
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run and xdotool are installed by scripts/setup.sh");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let r: Report = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let car2 = streamline_studio::scene::io::load(&open).unwrap();
    assert_eq!(r.cols, car2.design.net().cols(), "car2 was opened: {r:?}");
    assert!(r.last_edit.contains("save"), "{r:?}");
    let saved = streamline_studio::scene::io::load(&save).expect("saved and valid");
    assert_eq!(saved.to_file(), car2.to_file());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The interactive editor rests when nobody touches it (a software renderer
/// drawing the scene again and again kept both cores busy: 36 CPU seconds in
/// 20 idle ones) and wakes on input: with the keyboard, Save As writes the
/// scene while the same idle stretch took next to no CPU.
#[test]
fn the_idle_editor_rests_and_wakes_on_input() {
    let _gui = gui_lock();
    let dir = temp_dir("idle");
    let scene = dir.join("minimal.ron");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/minimal.ron"),
        &scene,
    )
    .unwrap();
    let save = dir.join("saved.ron");
    let run = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", "bash"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gui/idle.sh"))
        .arg(BIN)
        .arg(&scene)
        .arg(&save)
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run and xdotool are installed by scripts/setup.sh");
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{out}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let figure = |k: &str| -> u64 {
        out.lines()
            .find_map(|l| l.strip_prefix(k)?.trim().parse().ok())
            .unwrap_or_else(|| panic!("no {k} in {out}"))
    };
    let (idle, busy) = (figure("idle "), figure("busy "));
    // drawing every frame took 845 ticks in these 5 s here; resting took 0-11
    // (a wake-up every 5 s draws one frame, about 0.1 s of llvmpipe's CPU)
    assert!(idle <= 60, "5 idle seconds took {idle} ticks of CPU: {out}");
    let saved = streamline_studio::scene::io::load(&save).expect("saved on input, and valid");
    let opened = streamline_studio::scene::io::load(&scene).unwrap();
    assert_eq!(saved.to_file(), opened.to_file());
    assert!(busy > idle, "input woke the editor: {out}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A 1 GiB OBJ does not hang the editor (issue 7, item 3): it is read off the
/// frame while frames keep coming, refused at the memory cap with the line
/// where that happened, and the streamline surface stays on screen.
#[test]
fn a_1gib_obj_is_opened_off_the_frame_and_refused() {
    use std::io::Write;
    let _gui = gui_lock();
    let dir = temp_dir("huge-obj");
    let obj = dir.join("huge.obj");
    {
        let mut w =
            std::io::BufWriter::with_capacity(1 << 22, std::fs::File::create(&obj).unwrap());
        let mut written = 0usize;
        let mut i = 0u64;
        while written < 1 << 30 {
            let line = format!("v {}.5 {}.5 0.25\n", i % 20_000, i / 20_000);
            w.write_all(line.as_bytes()).unwrap();
            written += line.len();
            i += 1;
        }
        w.flush().unwrap();
    }
    let report = dir.join("report.json");
    let (w, h, px) = shot(
        &dir,
        "huge",
        &[
            "--mesh",
            obj.to_str().unwrap(),
            "--panel",
            "mesh",
            "--report",
            report.to_str().unwrap(),
        ],
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let busy = r["busy_frames"].as_u64().unwrap();
    assert!(
        busy >= 2,
        "frames were drawn while the mesh was read: {busy}"
    );
    let e = r["mesh_error"].as_str().unwrap_or_default();
    assert!(
        e.contains("over the memory cap of 2048 MB") && e.contains("nothing was opened"),
        "{e}"
    );
    // the car is still shown (its blue-white shading), not a mesh
    let surface = share(w, h, &px, |[r, g, b]| b > 150 && b >= r && g > 100);
    assert!(surface > 0.05, "the streamline surface stays: {surface:.3}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs `tests/gui/authoring.sh` in `mode` on `file` and returns the report.
fn authoring(dir: &Path, mode: &str, file: &Path) -> Report {
    let report = dir.join(format!("{mode}.json"));
    let run = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", "bash"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gui/authoring.sh"))
        .arg(BIN)
        .arg(dir.join(format!("{mode}.png")))
        .arg(&report)
        .arg(mode)
        .arg(file)
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run and xdotool are installed by scripts/setup.sh");
    assert!(
        run.status.success(),
        "authoring run ({mode}) failed: {}{}",
        String::from_utf8_lossy(&run.stderr),
        std::fs::read_to_string(report.with_extension("json.log")).unwrap_or_default()
    );
    serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap()
}

/// Issue 20: with a real pointer, File ▸ New ▸ New design… with rows 4,
/// columns 7 and a Flat width of 3 makes exactly that net (the rectangle
/// `[0, 4] × [0, 3]`), saved under a typed path; then a right click on arrow
/// (1, 3) and "Insert row after" from its menu give a fifth row at index 2
/// (one undo step, the new row selected), saved with Ctrl+S.
#[test]
fn new_design_dialog_and_right_click_insert() {
    let _gui = gui_lock();
    let dir = temp_dir("authoring");
    let file = dir.join("design.ron");
    let made = authoring(&dir, "new", &file);
    assert!(made.last_edit.contains("save"), "{made:?}");
    let s = streamline_studio::scene::io::load(&file).expect("the new design was saved");
    assert_eq!(
        (s.design.net().rows(), s.design.net().cols()),
        (4, 7),
        "{made:?}"
    );
    assert_eq!(s.design.initial().length(), 3.0, "the typed width");
    assert_eq!(
        s.design.streamline_length(0),
        Some(4.0),
        "the default length"
    );
    assert!(!s.mirror);
    let flat = s.design.build(s.display_depth).unwrap();
    assert!(
        flat.mesh.positions.iter().all(|p| p.z.abs() < 1e-12
            && (-1e-9..=4.0 + 1e-9).contains(&p.x)
            && (-1e-9..=3.0 + 1e-9).contains(&p.y)),
        "Flat lies in the rectangle [0, 4] × [0, 3] of z = 0"
    );
    let inserted = authoring(&dir, "insert", &file);
    assert_eq!(inserted.undo, 1, "an insert is one undo step: {inserted:?}");
    assert!(inserted.last_edit.contains("save"), "{inserted:?}");
    let t = streamline_studio::scene::io::load(&file).expect("saved after the insert");
    assert_eq!((t.design.net().rows(), t.design.net().cols()), (5, 7));
    assert_eq!(inserted.selection, Some((2, 3)), "the new row is selected");
    // the new row got index 2, between the old rows 1 and 2; the others kept theirs
    let (old, new) = (&s.design.params().t, &t.design.params().t);
    assert_eq!(
        [new[0], new[1], new[3], new[4]],
        [old[0], old[1], old[2], old[3]]
    );
    assert!(old[1] < new[2] && new[2] < old[2], "{old:?} → {new:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A glTF export from the editor carries the colours of the analysis map
/// shown (`COLOR_0`, linear RGBA, one per vertex): the Gaussian map of the
/// car has red domes and blue saddles; the shaded surface exports none.
#[test]
fn a_glb_exported_with_a_map_shown_has_its_colours() {
    let _gui = gui_lock();
    let dir = temp_dir("glb-colours");
    std::fs::write(
        dir.join("export.ron"),
        "(steps: [\n    Export(\"car.glb\"),\n])\n",
    )
    .unwrap();
    let script = dir.join("export.ron");
    let script = script.to_str().unwrap();
    for (analysis, coloured) in [("gaussian", true), ("shaded", false)] {
        let glb = dir.join("car.glb");
        let _ = std::fs::remove_file(&glb);
        shot(
            &dir,
            analysis,
            &["car1", "--analysis", analysis, "--script", script],
        );
        let doc = gltf::Gltf::open(&glb).expect("the export wrote a .glb");
        let blob = doc.blob.as_deref();
        let prim = doc.meshes().next().unwrap().primitives().next().unwrap();
        let reader = prim.reader(|_| blob);
        let n = reader.read_positions().unwrap().count();
        match reader.read_colors(0) {
            Some(c) => {
                assert!(coloured, "{analysis}: no colours expected");
                let c: Vec<[f32; 4]> = c.into_rgba_f32().collect();
                assert_eq!(c.len(), n, "one colour per vertex");
                let red = c.iter().filter(|p| p[0] > p[2] + 0.2).count();
                let blue = c.iter().filter(|p| p[2] > p[0] + 0.2).count();
                assert!(
                    red > n / 1000 && blue > n / 1000,
                    "{analysis}: {red} red and {blue} blue of {n} vertices"
                );
            }
            None => assert!(!coloured, "{analysis}: COLOR_0 missing"),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs `tests/gui/browser.sh` in `mode` from `cwd` (the editor's working
/// folder) with the scene folder `folder`; returns the report.
fn browser(dir: &Path, cwd: &Path, mode: &str, folder: &Path, name: &str) -> Report {
    let report = dir.join(format!("{mode}.json"));
    let run = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", "bash"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gui/browser.sh"))
        .arg(BIN)
        .arg(dir.join(format!("{mode}.png")))
        .arg(&report)
        .arg(mode)
        .arg(folder)
        .arg(name)
        .current_dir(cwd)
        .env("STREAMLINE_STUDIO_HOME", dir.join("home"))
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run and xdotool are installed by scripts/setup.sh");
    assert!(
        run.status.success(),
        "browser run ({mode}) failed: {}{}",
        String::from_utf8_lossy(&run.stderr),
        std::fs::read_to_string(report.with_extension("json.log")).unwrap_or_default()
    );
    serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap()
}

/// Issue 27: with a real pointer, File ▸ Open… in the menu bar opens the file
/// browser in the working folder; a typed folder elsewhere, a click on the
/// scene listed there and on Open load it (its path, its net). Then File ▸
/// Export ▸ OBJ mesh… opens the browser in that scene's folder: a typed name
/// and a click on Save write a valid OBJ of the scene's surface there.
#[test]
fn menu_bar_and_file_browser_open_and_export() {
    let _gui = gui_lock();
    let dir = temp_dir("browser");
    let (cwd, folder) = (dir.join("work"), dir.join("elsewhere"));
    std::fs::create_dir_all(&cwd).unwrap();
    std::fs::create_dir_all(&folder).unwrap();
    let scene = folder.join("car2.ron");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/car2.ron"),
        &scene,
    )
    .unwrap();
    // not a scene: the browser's filter hides it
    std::fs::write(folder.join("notes.txt"), "not a scene\n").unwrap();
    let r = browser(&dir, &cwd, "run", &folder, "through-browser.obj");
    let car2 = streamline_studio::scene::io::load(&scene).unwrap();
    let opened = r.path.as_deref().map(std::fs::canonicalize);
    assert_eq!(
        opened.map(Result::unwrap),
        Some(std::fs::canonicalize(&scene).unwrap()),
        "the scene from the other folder was opened: {r:?}"
    );
    assert_eq!(r.cols, car2.design.net().cols(), "{r:?}");
    assert_eq!(r.net.len(), car2.design.net().data().len(), "{r:?}");
    let obj = folder.join("through-browser.obj");
    let text = std::fs::read_to_string(&obj).unwrap_or_else(|e| {
        panic!(
            "no OBJ in the scene's folder ({e}): {r:?}; {:?}",
            std::fs::read_dir(&folder).unwrap().collect::<Vec<_>>()
        )
    });
    let mesh = car2.design.build(car2.display_depth).unwrap().mesh;
    let count = |p: &str| text.lines().filter(|l| l.starts_with(p)).count();
    assert_eq!(
        count("v "),
        mesh.positions.len(),
        "one vertex per mesh point"
    );
    assert_eq!(count("f "), mesh.indices.len() / 3, "every triangle");
    for l in text.lines().filter(|l| l.starts_with("v ")) {
        let xyz: Vec<f64> = l[2..]
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        assert!(xyz.len() == 3 && xyz.iter().all(|v| v.is_finite()), "{l}");
    }
    assert!(r.last_edit.contains("export"), "{r:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
