//! File ▸ Import surface… as a user does it, on a virtual X display with
//! Mesa's software Vulkan (as `tests/editor_gui_files.rs`): the menu bar
//! clicked with a real pointer, the file's path typed into the file browser,
//! Fit clicked in the Import surface dialog; the fit runs on its own thread
//! and the design it makes replaces the scene, naming the file it came from.

use std::path::Path;
use std::process::Command;
use streamline_kernel::fit::ReferenceFitOptions;
use streamline_studio::scene::files::reference_link::ReferenceLink;
use streamline_studio::scene::fit::reference::fit_file;

#[path = "gui/harness.rs"]
mod harness;

use harness::{BIN, gui_lock, temp_dir};

#[test]
fn import_surface_fits_the_face_and_opens_the_design() {
    let _gui = gui_lock();
    let dir = temp_dir("import");
    let hood = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/references/hood.step");
    let report = dir.join("import.json");
    let run = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", "bash"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gui/import.sh"))
        .arg(BIN)
        .arg(dir.join("import.png"))
        .arg(&report)
        .arg("fit")
        .arg(&hood)
        // Fit, below the dialog's single face (hood.step has one)
        .env("FIT_BUTTON", "216 400")
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run and xdotool are installed by scripts/setup.sh");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    // the same fit without a window: the design the dialog opened
    let link = ReferenceLink {
        path: hood.clone(),
        face: 0,
    };
    let (_, fit) = fit_file(&link, &ReferenceFitOptions::default()).unwrap();
    assert!(fit.within);
    assert_eq!(r["scene"], "hood", "the fitted design was opened: {r}");
    assert_eq!(r["cols"].as_u64(), Some(fit.net.1 as u64), "{r}");
    assert_eq!(r["depth"].as_u64(), Some(u64::from(fit.depth)), "{r}");
    assert!(
        r["last_edit"].as_str().unwrap_or_default().contains("hood"),
        "{r}"
    );
    // a design of no file, as File ▸ New opens one
    assert!(r["path"].is_null(), "{r}");
    let _ = std::fs::remove_dir_all(&dir);
}
