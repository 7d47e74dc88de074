//! Every reference in the repository points into the repository: no file
//! cites a contract or design note that lives outside it (the old names of
//! the math contract and the design notes, or a path into a shared folder),
//! and every `docs/math.md §n` names a section that docs/math.md has. The
//! math document keeps its sections `§1`–`§10` under fixed numbers
//! (docs/math.md, introduction), so that is checked too.
//!
//! The whole checkout is scanned (every UTF-8 file outside `.git`, build
//! output and fuzzing output), not only the kernel: this crate's tests run in
//! seconds, so the check runs wherever the kernel's tests do.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

/// Directories that hold no sources: version control, build and fuzzing
/// output, and the inputs fuzzing found (`fuzz/regressions`: arbitrary bytes,
/// which may spell anything).
const SKIP_DIRS: &[&str] = &[
    ".git",
    "target",
    "corpus",
    "artifacts",
    "coverage",
    "regressions",
];

/// Hidden directories that do hold sources (CI scripts).
const HIDDEN_KEPT: &[&str] = &[".ci", ".github"];

fn repo_root() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    assert!(
        root.join("docs/math.md").is_file(),
        "docs/math.md not found under {}: the kernel's tests expect the whole workspace",
        root.display()
    );
    root
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let Ok(meta) = fs::symlink_metadata(&path) else {
            continue;
        };
        if meta.is_dir() {
            let hidden = name.starts_with('.') && !HIDDEN_KEPT.contains(&name.as_str());
            if !hidden && !SKIP_DIRS.contains(&name.as_str()) {
                collect(&path, out);
            }
        } else if meta.is_file() {
            out.push(path);
        }
    }
}

/// The section numbers of docs/math.md: headings `## 3. …` or `### 7.2 …`.
fn sections(math: &str) -> BTreeSet<String> {
    math.lines()
        .filter_map(|line| {
            let rest = line.strip_prefix("##")?.trim_start_matches('#');
            let rest = rest.strip_prefix(' ')?;
            let number: String = rest
                .chars()
                .take_while(|c| c.is_ascii_digit() || *c == '.')
                .collect();
            let number = number.trim_end_matches('.');
            (!number.is_empty()).then(|| number.to_string())
        })
        .collect()
}

fn is_word_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Whether `word` occurs in `line` as a whole word (so an identifier that
/// merely contains it, such as `NAME_BYTES`, does not count).
fn has_word(line: &str, word: &str) -> bool {
    line.match_indices(word).any(|(i, _)| {
        let before = line[..i].chars().next_back();
        let after = line[i + word.len()..].chars().next();
        !before.is_some_and(is_word_char) && !after.is_some_and(is_word_char)
    })
}

/// The section numbers cited in `line` as `math.md §n`, `math.md §n–m`
/// (every number of the range) or `math.md §n.m`.
fn cited_sections(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (i, m) in line.match_indices("math.md") {
        let rest = line[i + m.len()..].trim_start_matches(['`', ')', ']', ' ']);
        let Some(rest) = rest.strip_prefix('§') else {
            continue;
        };
        let first: String = rest
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '.')
            .collect();
        let first = first.trim_end_matches('.').to_string();
        if first.is_empty() {
            continue; // a placeholder such as `§n`
        }
        let after = &rest[first.len()..];
        let range_end = after
            .strip_prefix('–')
            .or_else(|| after.strip_prefix('-'))
            .map(|r| r.trim_start_matches('§'))
            .map(|r| {
                r.chars()
                    .take_while(char::is_ascii_digit)
                    .collect::<String>()
            })
            .filter(|r| !r.is_empty());
        match (first.parse::<u32>(), range_end.map(|r| r.parse::<u32>())) {
            (Ok(a), Some(Ok(b))) if a <= b => out.extend((a..=b).map(|n| n.to_string())),
            _ => out.push(first),
        }
    }
    out
}

/// The known sections in reading order (`2` before `10`).
fn listed(known: &BTreeSet<String>) -> String {
    let key = |n: &String| -> Vec<u32> { n.split('.').filter_map(|x| x.parse().ok()).collect() };
    let mut v: Vec<&String> = known.iter().collect();
    v.sort_by_key(|n| key(n));
    v.iter().map(|n| n.as_str()).collect::<Vec<_>>().join(", ")
}

/// What is wrong with one line, if anything.
fn problems(line: &str, known: &BTreeSet<String>) -> Vec<String> {
    // Built from pieces so that this file does not cite them itself.
    let spec = ["SP", "EC"].concat();
    let design = ["DES", "IGN"].concat();
    let shared = ["shared", "/"].concat();
    let up_shared = ["../", "shared"].concat();
    let mut out = Vec::new();
    if has_word(line, &spec) {
        out.push(format!(
            "cites `{spec}`: cite `docs/math.md §n` (sections 1–10) instead"
        ));
    }
    if has_word(line, &design) {
        out.push(format!(
            "cites `{design}`: cite docs/architecture.md or the README's Architecture section instead"
        ));
    }
    if line.contains(&shared) || line.contains(&up_shared) {
        out.push(format!(
            "points into a shared folder (`{shared}`) outside the repository: cite docs/math.md or docs/ instead"
        ));
    }
    for n in cited_sections(line) {
        if !known.contains(&n) {
            out.push(format!(
                "cites docs/math.md §{n}, which docs/math.md does not have (its sections: {})",
                listed(known)
            ));
        }
    }
    out
}

#[test]
fn math_doc_keeps_sections_1_to_10() {
    let math = fs::read_to_string(repo_root().join("docs/math.md")).expect("docs/math.md");
    let known = sections(&math);
    for n in 1..=10 {
        assert!(
            known.contains(&n.to_string()),
            "docs/math.md has no section {n} (a heading `## {n}. …`); code and docs cite §1–§10 by number, so keep them: found {known:?}"
        );
    }
}

#[test]
fn every_citation_points_into_the_repository() {
    let root = repo_root();
    let math = fs::read_to_string(root.join("docs/math.md")).expect("docs/math.md");
    let known = sections(&math);
    let mut files = Vec::new();
    collect(&root, &mut files);
    let mut scanned = 0;
    let mut found = Vec::new();
    for path in &files {
        let Ok(text) = fs::read_to_string(path) else {
            continue; // not UTF-8: a mesh, an image, a fuzz input
        };
        scanned += 1;
        let shown = path
            .strip_prefix(&root)
            .unwrap_or(path)
            .display()
            .to_string();
        for (i, line) in text.lines().enumerate() {
            for p in problems(line, &known) {
                found.push(format!("{shown}:{}: {p}", i + 1));
            }
        }
    }
    assert!(
        scanned > 100,
        "only {scanned} text files scanned under {}: is this the workspace root?",
        root.display()
    );
    assert!(
        found.is_empty(),
        "{} reference(s) point outside the repository or to a missing section:\n{}",
        found.len(),
        found.join("\n")
    );
}

#[test]
fn the_scanner_catches_what_it_must() {
    let known: BTreeSet<String> = (1..=10).map(|n| n.to_string()).collect();
    let spec = ["SP", "EC"].concat();
    let design = ["DES", "IGN"].concat();
    let bad = [
        format!("//! Blending ({spec} §1)."),
        format!("see `{spec}.md`"),
        format!("/// ({design}, incremental rebuild)"),
        format!("see {design}.md"),
        ["../shar", "ed/seeds/README.md"].concat(),
        // Split so that this file does not cite missing sections itself.
        ["(docs/math.md", " §11)"].concat(),
        ["(docs/math.md", " §7.3)"].concat(),
        ["(docs/math.md", " §9–12)"].concat(),
        ["[math.md", " §0](math.md)"].concat(),
    ];
    for line in &bad {
        assert!(!problems(line, &known).is_empty(), "not flagged: {line:?}");
    }
    let good = [
        "(docs/math.md §1)",
        "(docs/math.md §2–4)",
        "[math.md §10](math.md)",
        "`docs/math.md` §6",
        "cite it as `docs/math.md §n`",
        "pub const DESIGN_BYTES_PER_TANGENT: u64 = 400;",
        "SchemeSpec::Kobbelt, a spec of the scheme",
        "paper 002, §2 and §4; docs/math.md §7",
    ];
    for line in good {
        assert_eq!(
            problems(line, &known),
            Vec::<String>::new(),
            "flagged: {line:?}"
        );
    }
    assert_eq!(cited_sections("docs/math.md §2–4"), ["2", "3", "4"]);
}
