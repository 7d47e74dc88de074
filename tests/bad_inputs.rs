//! The bad-input catalogue (docs/math.md §8, docs/reliability.md): every broken
//! scene, script, OBJ, STEP, IGES and STL file in `tests/bad/` and the exact message it must
//! produce, from `tests/bad/catalogue.txt` (blocks of two lines: the file, its
//! message). Each message names the file, the line and column (the whole file
//! only where no line is at fault), what is wrong and, after a `;`, what to do.
//!
//! `BLESS=1 cargo test --release --test bad_inputs` rewrites the catalogue
//! from what the code says now (then read the diff); never in CI.

mod expectations;

use std::path::{Path, PathBuf};
use streamline_studio::scene::{design::document_io, edits::script::Script, loop_mesh::obj};

const CATALOGUE: &str = "tests/bad/catalogue.txt";

/// Messages that may name the whole file rather than a line: the fault is
/// the absence of something, which sits on no line.
const WHOLE_FILE: [&str; 3] = [
    "tests/bad/meshes/empty.obj",
    "tests/bad/meshes/no-faces.obj",
    // a binary file has no lines: the message names the bytes
    "tests/bad/references/truncated-binary.stl",
];

fn inputs() -> Vec<PathBuf> {
    let mut v = Vec::new();
    for dir in ["scenes", "scripts", "meshes", "references"] {
        let d = Path::new("tests/bad").join(dir);
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_file() {
                v.push(p);
            }
        }
    }
    v.sort();
    v
}

fn message(p: &Path) -> String {
    let kind = p.parent().and_then(|d| d.file_name()).unwrap();
    let r = match kind.to_str().unwrap() {
        // every version: 1 and 2 with exactly `io::load`'s messages, 3 by patch
        "scenes" => document_io::load(p).map(|_| ()),
        "scripts" => Script::load(p).map(|_| ()),
        "meshes" => obj::read(p).map(|_| ()),
        // what `fit FILE` reads: the file, then its face 0
        "references" => {
            return match streamline_reference::read(p).and_then(|f| f.surface(0).map(|_| ())) {
                Ok(()) => "(accepted)".into(),
                Err(e) => e.to_string(),
            };
        }
        other => panic!("unknown folder {other}"),
    };
    match r {
        Ok(()) => "(accepted)".into(),
        Err(e) => e.to_string(),
    }
}

fn read_catalogue() -> Vec<(String, String)> {
    let text = std::fs::read_to_string(CATALOGUE).unwrap_or_default();
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    lines
        .split(|l| l.is_empty())
        .filter(|b| !b.is_empty())
        .map(|b| {
            assert_eq!(b.len(), 2, "a catalogue block is two lines: {b:?}");
            (b[0].to_string(), b[1].to_string())
        })
        .collect()
}

#[test]
fn every_bad_file_gives_its_exact_message() {
    let files = inputs();
    assert!(files.len() >= 30, "{} bad files", files.len());
    let got: Vec<(String, String)> = files
        .iter()
        .map(|p| (p.display().to_string(), message(p)))
        .collect();
    if expectations::rewriting("BLESS") {
        let mut out = String::from(
            "# The bad-input catalogue: each file in tests/bad/ and the exact message it\n# must produce (tests/bad_inputs.rs).\n\n",
        );
        for (f, m) in &got {
            out.push_str(&format!("{f}\n{m}\n\n"));
        }
        std::fs::write(CATALOGUE, out).unwrap();
    }
    let want = read_catalogue();
    let mut failures = Vec::new();
    for (f, m) in &got {
        match want.iter().find(|(w, _)| w == f) {
            None => failures.push(format!("{f}: not in the catalogue (got `{m}`)")),
            Some((_, w)) if w != m => failures.push(format!("{f}:\n  want `{w}`\n  got  `{m}`")),
            _ => {}
        }
        // the message's shape: file, place, what, fix
        assert!(m.starts_with(f.as_str()), "{f}: names the file: {m}");
        let rest = &m[f.len()..];
        let located = {
            let parts: Vec<&str> = rest.splitn(4, ':').collect();
            parts.len() == 4
                && parts[0].is_empty()
                && parts[1].parse::<usize>().is_ok_and(|l| l > 0)
                && parts[2].parse::<usize>().is_ok_and(|c| c > 0)
        };
        assert!(
            located || WHOLE_FILE.contains(&f.as_str()),
            "{f}: names the line and column: {m}"
        );
        assert!(m.contains("; "), "{f}: says what to do after a `;`: {m}");
        assert!(m != "(accepted)", "{f} is accepted");
    }
    for (w, _) in &want {
        assert!(
            got.iter().any(|(f, _)| f == w),
            "{w} is in the catalogue but not in tests/bad"
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
