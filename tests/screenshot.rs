//! The editor as a user sees it: under a virtual X display with Mesa's software
//! Vulkan (installed by scripts/setup.sh), `screenshot` renders the car scene and
//! writes a PNG that is not blank.

use std::process::Command;

#[test]
fn screenshot_renders_the_car() {
    let dir = std::env::temp_dir().join(format!("streamline-shot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("car1.png");
    let status = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24"])
        .arg(env!("CARGO_BIN_EXE_streamline-studio"))
        .args([
            "screenshot",
            "--scene",
            "car1",
            "--size",
            "800x600",
            "--out",
        ])
        .arg(&out)
        .env_remove("DISPLAY")
        .output()
        .expect("xvfb-run is installed by scripts/setup.sh");
    assert!(
        status.status.success(),
        "screenshot failed: {}",
        String::from_utf8_lossy(&status.stderr)
    );
    let bytes = std::fs::read(&out).expect("PNG written");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "a PNG file");
    // A blank 800x600 frame compresses to a few kB; the shaded surface, streamlines
    // and panel text make it far larger.
    assert!(
        bytes.len() > 40_000,
        "PNG of {} bytes looks blank",
        bytes.len()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn editor_without_display_says_what_to_do() {
    let out = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
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
}
