//! Where a script writes: only inside its own folder ([`output_path`],
//! [`confine`]).

use std::path::{Path, PathBuf};

/// Where a script's `Save` or `Export` of `p` writes, for a script in `dir`.
/// Scripts are data: they write only inside their own folder, so `p` must be
/// a relative path that never climbs above it (checked on the words of the
/// path; [`confine`] checks the folder on disk, links resolved).
pub fn output_path(dir: &Path, p: &str) -> Result<PathBuf, String> {
    use std::path::Component;
    let refuse = || {
        format!(
            "`{p}` would write outside the script's folder ({}); scripts write only there: give a relative path such as \"out/scene.ron\"",
            dir.display()
        )
    };
    let mut depth = 0i32;
    for c in Path::new(p).components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir => depth -= 1,
            Component::RootDir | Component::Prefix(_) => depth = -1,
        }
        if depth < 0 {
            return Err(refuse());
        }
    }
    if depth == 0 {
        return Err(format!(
            "`{p}` names the script's folder itself, not a file; give a file name such as \"out/scene.ron\""
        ));
    }
    Ok(dir.join(p))
}

/// Creates the folder of `path` (from [`output_path`]) and checks that, with
/// symbolic links resolved, it still lies inside `dir`: a link inside the
/// script's folder cannot lead a write elsewhere.
pub fn confine(dir: &Path, path: &Path) -> Result<(), String> {
    let parent = path.parent().unwrap_or(dir);
    std::fs::create_dir_all(parent)
        .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
    let real_dir = dir
        .canonicalize()
        .map_err(|e| format!("cannot resolve {}: {e}", dir.display()))?;
    let real_parent = parent
        .canonicalize()
        .map_err(|e| format!("cannot resolve {}: {e}", parent.display()))?;
    let link_out = |p: &Path| {
        format!(
            "`{}` leads outside the script's folder ({}) through a symbolic link; scripts write only there",
            p.display(),
            real_dir.display()
        )
    };
    if !real_parent.starts_with(&real_dir) {
        return Err(link_out(path));
    }
    // the file itself may be a link to elsewhere
    if let Ok(meta) = std::fs::symlink_metadata(path)
        && meta.file_type().is_symlink()
    {
        return Err(link_out(path));
    }
    Ok(())
}
