//! The reference a design keeps (docs/math.md §12, "Starting from what
//! exists: references and fitted designs"): the STEP, IGES, OBJ or STL file
//! it was fitted to or is measured against, and the face in it. One design,
//! one reference: the top-level `reference` of a version-2 or version-3
//! scene file, absent when there is none.
//!
//! ```ron
//! reference: Some((path: "panel.step", face: 2)),   // 0 for a mesh
//! ```
//!
//! The file holds the path **relative to the scene file's folder**
//! ([`ReferenceSpec`]); in memory it is resolved, that folder joined with it
//! ([`ReferenceLink`], an absolute path kept as written). Saving to a path
//! `P` writes it relative to `P`'s folder again ([`ReferenceLink::to_spec_for`]),
//! so a design saved into another folder still points at the same file.
//! Paths are compared and made relative by their components (`.` dropped,
//! `..` folded into the name before it), not through the file system: the
//! reference need not exist when the design is read or saved.

use super::error::SceneError;
use serde::{Deserialize, Serialize};
use std::path::{Component, Path, PathBuf};

/// The largest face index a reference may name.
pub const MAX_REFERENCE_FACE: usize = 1_000_000;

/// The reference as written in a scene file: its path relative to the scene
/// file's folder (or absolute), with `/` between folders, and the face.
///
/// ```ron
/// reference: Some((path: "../references/panel.step", face: 2)),
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSpec {
    /// The STEP, IGES, OBJ or STL file, relative to the scene file's folder.
    pub path: String,
    /// The index of the face in that file (0 for a mesh).
    pub face: usize,
}

impl ReferenceSpec {
    /// What is wrong with it (an empty path, a NUL in it, a path that names
    /// no file, a face over [`MAX_REFERENCE_FACE`]) and how to fix it; `None`
    /// when it is good.
    pub fn problem(&self) -> Option<String> {
        let example = "such as `path: \"panel.step\"`";
        if self.path.is_empty() {
            return Some(format!(
                "the reference's `path` is empty; give the STEP, IGES, OBJ or STL file the design was fitted to, relative to this file's folder, {example}, or remove `reference`"
            ));
        }
        if self.path.contains('\0') {
            return Some(format!(
                "the reference's `path` contains a NUL character, which no file name may hold; give the file's path relative to this file's folder, {example}"
            ));
        }
        if !matches!(
            Path::new(&self.path).components().next_back(),
            Some(Component::Normal(_))
        ) {
            return Some(format!(
                "the reference's `path` \"{}\" names a folder, not a file; give the path of the STEP, IGES, OBJ or STL file, {example}",
                self.path
            ));
        }
        if self.face > MAX_REFERENCE_FACE {
            return Some(format!(
                "the reference's `face` is {}, over the limit of {MAX_REFERENCE_FACE}; give the index of the face in the file (0 for a mesh)",
                self.face
            ));
        }
        None
    }
}

/// The reference in memory: the file, resolved against the folder of the
/// scene file it was read from, and the face.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReferenceLink {
    /// The file: the scene file's folder joined with the written path
    /// (`.` and `..` folded), or the absolute path as written.
    pub path: PathBuf,
    /// The index of the face in that file (0 for a mesh).
    pub face: usize,
}

impl ReferenceLink {
    /// Resolves `spec`, read from the scene file `file`, against `file`'s
    /// folder; the problem ([`ReferenceSpec::problem`]) when it is bad.
    pub fn resolve(spec: &ReferenceSpec, file: &Path) -> Result<Self, String> {
        if let Some(p) = spec.problem() {
            return Err(p);
        }
        let written = Path::new(&spec.path);
        let path = if written.is_absolute() {
            written.to_path_buf()
        } else {
            normalised(&folder_of(file).join(written))
        };
        Ok(ReferenceLink {
            path,
            face: spec.face,
        })
    }

    /// The file form of the path as held (relative to the working folder,
    /// or absolute), with `/` between folders: what a scene file in the
    /// working folder would hold.
    pub fn to_spec(&self) -> ReferenceSpec {
        ReferenceSpec {
            path: slashed(&self.path),
            face: self.face,
        }
    }

    /// The file form as saved to the scene file `file`: the path relative
    /// to `file`'s folder (with `..` where it leads up), or absolute when
    /// there is no relative path ([`relative_to`]).
    pub fn to_spec_for(&self, file: &Path) -> ReferenceSpec {
        ReferenceSpec {
            path: slashed(&relative_to(folder_of(file), &self.path)),
            face: self.face,
        }
    }
}

/// The optional `reference` read from `file`, resolved; a bad one is an
/// error at `place` (the line and column of the `reference` key).
pub fn resolve_in(
    spec: Option<&ReferenceSpec>,
    file: &Path,
    place: impl FnOnce() -> (usize, usize),
) -> Result<Option<ReferenceLink>, SceneError> {
    spec.map(|s| {
        ReferenceLink::resolve(s, file).map_err(|m| {
            let (line, col) = place();
            SceneError::at(file, line, col, m)
        })
    })
    .transpose()
}

/// The folder of the scene file `file` (empty for a bare file name: the
/// working folder).
pub fn folder_of(file: &Path) -> &Path {
    file.parent().unwrap_or(Path::new(""))
}

/// `path` with `.` dropped and each `..` folded into the name before it
/// (`a/b/../c` is `a/c`; a leading `..` of a relative path stays, one after
/// the root goes); `.` when nothing is left.
pub fn normalised(path: &Path) -> PathBuf {
    let parts = folded(path);
    if parts.is_empty() {
        return PathBuf::from(".");
    }
    parts.iter().collect()
}

/// The components of `path`, folded as [`normalised`] says.
fn folded(path: &Path) -> Vec<Component<'_>> {
    let mut out: Vec<Component> = Vec::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => match out.last() {
                Some(Component::Normal(_)) => {
                    out.pop();
                }
                Some(Component::RootDir | Component::Prefix(_)) => {}
                _ => out.push(c),
            },
            _ => out.push(c),
        }
    }
    out
}

/// `target` relative to the folder `dir` when both are relative to the
/// working folder or both absolute (`..` for each of `dir`'s folders not
/// shared); otherwise, or when `dir` climbs above the working folder where
/// `target` does not, both are first made absolute from the working folder
/// and compared again; when there is still no relative path (another drive),
/// `target` absolute.
pub fn relative_to(dir: &Path, target: &Path) -> PathBuf {
    if let Some(r) = relative_path(dir, target) {
        return r;
    }
    let absolute = |p: &Path| {
        let p = if p.as_os_str().is_empty() {
            Path::new(".")
        } else {
            p
        };
        std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
    };
    let (dir, target) = (absolute(dir), absolute(target));
    relative_path(&dir, &target).unwrap_or_else(|| normalised(&target))
}

/// `target` relative to `dir`, by their folded components, when both are
/// relative or both absolute on the same root, and `dir` does not climb
/// (`..`) past what they share; else `None`.
pub fn relative_path(dir: &Path, target: &Path) -> Option<PathBuf> {
    if dir.is_absolute() != target.is_absolute() || dir.has_root() != target.has_root() {
        return None;
    }
    let (d, t) = (folded(dir), folded(target));
    let shared = d.iter().zip(&t).take_while(|(a, b)| a == b).count();
    let rooted = |c: &Component| matches!(c, Component::RootDir | Component::Prefix(_));
    if d[shared..]
        .iter()
        .any(|c| *c == Component::ParentDir || rooted(c))
        || t[shared..].iter().any(rooted)
    {
        return None;
    }
    let mut out = PathBuf::new();
    for _ in shared..d.len() {
        out.push("..");
    }
    for c in &t[shared..] {
        out.push(c.as_os_str());
    }
    if out.as_os_str().is_empty() {
        out.push(".");
    }
    Some(out)
}

/// `path` written with `/` between its components (a root stays a leading
/// `/`, a Windows prefix its own text).
pub fn slashed(path: &Path) -> String {
    let mut out = String::new();
    let mut sep = false;
    for c in path.components() {
        match c {
            Component::Prefix(p) => out.push_str(&p.as_os_str().to_string_lossy()),
            Component::RootDir => out.push('/'),
            other => {
                if sep {
                    out.push('/');
                }
                out.push_str(&other.as_os_str().to_string_lossy());
                sep = true;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(dir: &str, target: &str) -> Option<String> {
        relative_path(Path::new(dir), Path::new(target)).map(|p| slashed(&p))
    }

    #[test]
    fn relative_paths_climb_with_dots() {
        assert_eq!(rel("/a/b", "/a/b/c.step").as_deref(), Some("c.step"));
        assert_eq!(rel("/a/b", "/a/c/d.step").as_deref(), Some("../c/d.step"));
        assert_eq!(rel("/a/b/c", "/x.step").as_deref(), Some("../../../x.step"));
        assert_eq!(rel("", "r/p.step").as_deref(), Some("r/p.step"));
        assert_eq!(rel("s", "r/p.step").as_deref(), Some("../r/p.step"));
        assert_eq!(rel("s/./t/..", "s/p.step").as_deref(), Some("p.step"));
        assert_eq!(
            rel("..", "p.step"),
            None,
            "the working folder's name is unknown"
        );
        assert_eq!(rel("../s", "../p.step").as_deref(), Some("../p.step"));
        assert_eq!(rel("/a", "b.step"), None, "one absolute, one relative");
        assert_eq!(rel("a", "/b.step"), None);
    }

    #[test]
    fn relative_to_falls_back_to_absolute_paths() {
        let cwd = std::env::current_dir().unwrap();
        let back = relative_to(&cwd.join("x"), Path::new("r/p.step"));
        assert_eq!(slashed(&back), "../r/p.step");
        let up = relative_to(Path::new(".."), Path::new("p.step"));
        let name = cwd.file_name().unwrap().to_string_lossy();
        assert_eq!(slashed(&up), format!("{name}/p.step"));
        // a file in the working folder, an absolute reference under it
        let here = relative_to(Path::new(""), &cwd.join("r/p.step"));
        assert_eq!(slashed(&here), "r/p.step");
    }

    #[test]
    fn folding_and_slashes() {
        assert_eq!(normalised(Path::new("a/./b/../c")), PathBuf::from("a/c"));
        assert_eq!(normalised(Path::new("../a/..")), PathBuf::from(".."));
        assert_eq!(normalised(Path::new("/../a")), PathBuf::from("/a"));
        assert_eq!(normalised(Path::new("a/..")), PathBuf::from("."));
        assert_eq!(slashed(Path::new("/a/b")), "/a/b");
        assert_eq!(slashed(Path::new("../a/b.step")), "../a/b.step");
    }

    #[test]
    fn resolving_joins_the_folder() {
        let spec = |p: &str| ReferenceSpec {
            path: p.into(),
            face: 1,
        };
        let at = |p: &str, file: &str| ReferenceLink::resolve(&spec(p), Path::new(file));
        assert_eq!(
            at("panel.step", "/d/s.ron").unwrap().path,
            PathBuf::from("/d/panel.step")
        );
        assert_eq!(
            at("../r/panel.step", "d/s.ron").unwrap().path,
            PathBuf::from("r/panel.step")
        );
        assert_eq!(
            at("/abs/p.stl", "d/s.ron").unwrap().path,
            PathBuf::from("/abs/p.stl")
        );
        assert_eq!(at("p.obj", "s.ron").unwrap().path, PathBuf::from("p.obj"));
        for bad in ["", "a\0b", "..", "a/.."] {
            assert!(at(bad, "s.ron").is_err(), "{bad:?}");
        }
        let link = at("../r/panel.step", "/d/e/s.ron").unwrap();
        assert_eq!(
            link.to_spec_for(Path::new("/d/e/s.ron")).path,
            "../r/panel.step"
        );
        assert_eq!(link.to_spec_for(Path::new("/d/r/s.ron")).path, "panel.step");
        assert_eq!(link.to_spec().path, "/d/r/panel.step");
    }
}
