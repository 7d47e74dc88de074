//! Analysis ▸ to reference as a designer uses it, on a virtual X display
//! with Mesa's software Vulkan (as `tests/editor_gui_import.rs`): File ▸
//! Import surface… fits `scenes/references/hood.step`, the Analysis
//! section's map is switched to "to reference" with a real pointer (green:
//! the fitted design is within the tolerance), a handle's arrow is dragged
//! (the map turns red where the surface left the face, measured when the
//! drag ends, in the window of points the drag moved), and Ctrl+Z brings
//! the green back, the largest distance that of the fit.
//! `tests/gui/reference.sh` drives it; the pictures of
//! docs/fit.md's walk-through are those of its steps.

use std::path::{Path, PathBuf};
use std::process::Command;
use streamline_kernel::fit::ReferenceFitOptions;
use streamline_studio::scene::files::reference_link::ReferenceLink;
use streamline_studio::scene::fit::reference::fit_file;

#[path = "gui/harness.rs"]
mod harness;

use harness::{BIN, gui_lock, share, temp_dir};

/// The hood's shown points at depth 5 (257 × 226).
const HOOD_POINTS: u64 = 257 * 226;

/// Runs `tests/gui/reference.sh` to `step`; its report and picture.
fn run(dir: &Path, step: &str) -> (serde_json::Value, PathBuf) {
    let hood = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.step");
    let out = dir.join(format!("{step}.png"));
    let report = dir.join(format!("{step}.json"));
    let run = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", "bash"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gui/reference.sh"))
        .arg(BIN)
        .arg(&out)
        .arg(&report)
        .arg(step)
        .arg(&hood)
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run and xdotool are installed by scripts/setup.sh");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let r = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    (r, out)
}

/// The share of the 3D view's pixels that are the map's red (at or beyond
/// the tolerance).
fn red_share(png_path: &Path) -> f64 {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(png_path).unwrap(),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let px: Vec<[u8; 3]> = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    share(info.width, info.height, &px, |[r, g, b]| {
        r > 150 && g < 90 && b < 90
    })
}

/// The map in a report: largest distance, tolerance, points measured last.
fn map(r: &serde_json::Value) -> (f64, f64, u64) {
    let m = &r["reference"];
    assert!(m.is_object(), "the map was measured: {r}");
    (
        m["max"].as_f64().unwrap(),
        m["tolerance"].as_f64().unwrap(),
        m["measured"].as_u64().unwrap(),
    )
}

#[test]
fn a_dragged_handle_turns_the_map_red_and_undo_brings_green_back() {
    let _gui = gui_lock();
    let dir = temp_dir("reference");
    // the drag
    let (r, picture) = run(&dir, "dragged");
    assert_eq!(r["scene"], "hood", "the fitted design was opened: {r}");
    assert!(
        r["last_edit"]
            .as_str()
            .unwrap_or_default()
            .contains("(0, 0)"),
        "the handle was dragged: {r}"
    );
    let (max, tolerance, measured) = map(&r);
    assert!((1.7e-4..1.9e-4).contains(&tolerance), "{tolerance}");
    assert!(
        max > tolerance,
        "the surface left the face: {max} > {tolerance}"
    );
    // measured where the drag moved the surface, and when it ended: the
    // window is more than a frame measures
    assert!(
        measured < HOOD_POINTS,
        "the drag's window, not every point: {measured}"
    );
    assert_eq!(r["reference"]["live"], false, "{r}");
    let red = red_share(&picture);
    eprintln!(
        "dragged: largest {max:.3e} m (tolerance {tolerance:.3e}), {measured} points measured, {:.1} % of the view red",
        red * 100.0
    );
    assert!(red > 0.01, "the map shows red: {red}");
    // the same, then Ctrl+Z
    let (u, picture) = run(&dir, "undone");
    assert_eq!(u["last_edit"], "undo", "{u}");
    assert_eq!(u["redo"].as_u64(), Some(1), "{u}");
    let (back, tolerance, _) = map(&u);
    assert!(back <= tolerance, "green again: {back} within {tolerance}");
    // the fitted design's largest distance: the same fit without a window
    let link = ReferenceLink {
        path: Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.step"),
        face: 0,
    };
    let (_, fit) = fit_file(&link, &ReferenceFitOptions::default()).unwrap();
    let fitted = fit.to_reference.max;
    assert!(
        (back - fitted).abs() <= 1e-9 * fitted,
        "undone: {back}, fitted: {fitted}"
    );
    let red = red_share(&picture);
    eprintln!(
        "undone: largest {back:.3e} m, {:.2} % of the view red",
        red * 100.0
    );
    assert!(red < 0.001, "no red left: {red}");
    let _ = std::fs::remove_dir_all(&dir);
}
