//! What the GUI tests (`tests/editor_gui.rs`, `tests/editor_gui_files.rs`)
//! share: the binary, one GUI run at a time, scratch folders, and the report
//! the scripts in `tests/gui/` write.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

pub const BIN: &str = env!("CARGO_BIN_EXE_streamline-studio");

/// The editor renders in software (llvmpipe): one GUI run at a time keeps the
/// frame rate, and so the pointer and key timings, sane on a 2-core machine.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

pub fn gui_lock() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

pub fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("streamline-gui-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[derive(serde::Deserialize, Debug)]
pub struct Report {
    #[serde(default)]
    pub path: Option<PathBuf>,
    pub undo: usize,
    pub last_edit: String,
    pub selection: Option<(usize, usize)>,
    pub net: Vec<[f64; 3]>,
    pub cols: usize,
    pub shown_gap: Option<f64>,
}

/// Runs `screenshot` with `args` at 800×600 and returns the decoded RGB pixels.
pub fn shot(dir: &Path, name: &str, args: &[&str]) -> (u32, u32, Vec<[u8; 3]>) {
    shot_sized(dir, name, "800x600", args)
}

/// [`shot`] at `size` (`WxH`).
pub fn shot_sized(dir: &Path, name: &str, size: &str, args: &[&str]) -> (u32, u32, Vec<[u8; 3]>) {
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
pub fn share(w: u32, h: u32, px: &[[u8; 3]], f: impl Fn([u8; 3]) -> bool) -> f64 {
    let (mut n, mut hit) = (0usize, 0usize);
    for y in (h / 10)..(h * 9 / 10) {
        for x in (w * 2 / 5)..(w * 7 / 10) {
            n += 1;
            hit += f(px[(y * w + x) as usize]) as usize;
        }
    }
    hit as f64 / n as f64
}
