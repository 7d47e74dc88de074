//! Reading files with a size cap and as UTF-8 text, and writing them
//! atomically and verified ([`write_atomic`]: scene files, exports, meshes).
//! Reading a scene file into a scene or a document is
//! [`crate::scene::design::document_io`].
//!
//! Writing writes a temporary file in the same directory, flushes it to disk,
//! reads it back and validates it, then renames it over the target (atomic on
//! POSIX file systems) and syncs the directory: a crash at any point leaves
//! either the old file or the new one, never a broken one.

use super::error::SceneError;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The largest scene file read (bytes); larger files are refused before reading.
pub const MAX_SCENE_BYTES: u64 = 64 << 20;

/// The size of the file at `path`, refused with what to do when it cannot be
/// opened, is a folder (`wanted` names what should be there), or is over
/// `cap` bytes (`too_big` says what to do).
pub fn file_size(path: &Path, cap: u64, wanted: &str, too_big: &str) -> Result<u64, SceneError> {
    let meta = fs::metadata(path)
        .map_err(|e| SceneError::file(path, format!("cannot open: {e}; check the path")))?;
    if meta.is_dir() {
        return Err(SceneError::file(
            path,
            format!("is a folder, not a file; give the path of {wanted}"),
        ));
    }
    if meta.len() > cap {
        return Err(SceneError::file(
            path,
            format!(
                "the file is {} bytes, over the limit of {cap}; {too_big}",
                meta.len()
            ),
        ));
    }
    Ok(meta.len())
}

/// Reads a text file, refusing one over `cap` bytes or not UTF-8.
pub fn read_text(path: &Path, cap: u64) -> Result<String, SceneError> {
    file_size(path, cap, "a file", "this is not a scene or script file")?;
    let bytes = fs::read(path)
        .map_err(|e| SceneError::file(path, format!("cannot read: {e}; check the permissions")))?;
    utf8(path, bytes, "scene and script files are RON text")
}

/// `bytes` as text, or an error at the line and column of the first byte
/// that is not UTF-8; `kind` says what the file should be.
pub fn utf8(path: &Path, bytes: Vec<u8>, kind: &str) -> Result<String, SceneError> {
    String::from_utf8(bytes).map_err(|e| {
        let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
        let start = good.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        let col = String::from_utf8_lossy(&good[start..]).chars().count() + 1;
        SceneError::at(
            path,
            line,
            col,
            format!(
                "this byte is not UTF-8 text ({kind}); save the file as UTF-8 or check it is the right file"
            ),
        )
    })
}

/// Writes `bytes`; with `STREAMLINE_STUDIO_SLOW_SAVE=MS` set (a test hook),
/// in 64 KiB pieces with a pause of MS milliseconds after each, so that a
/// test killing the process lands inside the write.
fn write_slowly_if_asked(f: &mut fs::File, bytes: &[u8]) -> std::io::Result<()> {
    let pause = std::env::var("STREAMLINE_STUDIO_SLOW_SAVE")
        .ok()
        .and_then(|v| v.parse::<u64>().ok());
    let Some(ms) = pause else {
        return f.write_all(bytes);
    };
    for piece in bytes.chunks(64 << 10) {
        f.write_all(piece)?;
        std::thread::sleep(std::time::Duration::from_millis(ms));
    }
    Ok(())
}

/// Writes `bytes` to `path` through a verified temporary file and a rename.
pub fn write_atomic(
    path: &Path,
    bytes: &[u8],
    verify: impl FnOnce(&[u8]) -> Result<(), String>,
) -> Result<(), SceneError> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path.file_name().ok_or_else(|| {
        SceneError::file(path, "not a file name; give a path ending in a file name")
    })?;
    let tmp = dir.join(format!(
        ".{}.tmp-{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let fail = |what: &str, e: std::io::Error| {
        let _ = fs::remove_file(&tmp);
        SceneError::file(path, format!("{what}: {e}; the previous file is unchanged"))
    };
    {
        let mut f =
            fs::File::create(&tmp).map_err(|e| fail("cannot create a temporary file", e))?;
        write_slowly_if_asked(&mut f, bytes).map_err(|e| fail("cannot write", e))?;
        f.sync_all().map_err(|e| fail("cannot flush to disk", e))?;
    }
    let back = fs::read(&tmp).map_err(|e| fail("cannot read back", e))?;
    if back != bytes {
        let _ = fs::remove_file(&tmp);
        return Err(SceneError::file(
            path,
            "the written file differs from what was meant; the previous file is unchanged",
        ));
    }
    if let Err(m) = verify(&back) {
        let _ = fs::remove_file(&tmp);
        return Err(SceneError::file(
            path,
            format!("verification failed ({m}); the previous file is unchanged"),
        ));
    }
    fs::rename(&tmp, path).map_err(|e| fail("cannot replace the file", e))?;
    if let Ok(d) = fs::File::open(&dir) {
        let _ = d.sync_all();
    }
    Ok(())
}
