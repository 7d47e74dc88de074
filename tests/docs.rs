//! The documents are tested, so that what README.md, CHANGELOG.md and docs/
//! say stays true of the product:
//!
//! - every command in a ```` ```sh ```` block runs and exits 0 (headless, in a
//!   scratch folder holding copies of `scenes/`, `tests/data/` and
//!   `tests/scripts/`, with the built `streamline-studio` first on `PATH`;
//!   a block that takes a screenshot runs under `xvfb-run`). The blocks of
//!   one page run in order in one folder, so a page may build on what an
//!   earlier block wrote. A command that runs a repository script
//!   (`bash scripts/…`, `python3 scripts/…`) is the project's own machinery
//!   (the two commands, the benchmark tables, the screenshots: minutes to
//!   tens of minutes, or a window): the script must exist and parse;
//! - every link and image points at a file that exists, and every `#anchor`
//!   at a heading of its page;
//! - (every `docs/math.md §n` cited anywhere is a section of docs/math.md:
//!   `crates/kernel/tests/citations.rs`, which scans the whole checkout);
//! - every picture in docs/img is shown by some page;
//! - no page or comment tells the project's history (sessions, issue and
//!   item numbers): that is git's and CHANGELOG.md's;
//! - the benchmark tables are generated from their saved results;
//! - `--help` of `build` names every format the exporter writes.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;
use streamline_studio::scene::export::format::Format;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// README.md, CHANGELOG.md and every page in docs/.
fn pages() -> Vec<PathBuf> {
    let mut v = vec![root().join("README.md"), root().join("CHANGELOG.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    v.extend(docs);
    v
}

fn rel(p: &Path) -> String {
    p.strip_prefix(root()).unwrap_or(p).display().to_string()
}

/// A fenced code block: its info string, its first line (1-based) and text.
struct Block {
    info: String,
    line: usize,
    text: String,
}

/// The page's fenced blocks, and its prose with the blocks blanked out
/// (line numbers kept).
fn split(md: &str) -> (Vec<Block>, Vec<String>) {
    let mut blocks = Vec::new();
    let mut prose = Vec::new();
    let mut open: Option<(String, usize, usize, String, String)> = None;
    for (i, line) in md.lines().enumerate() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        match &mut open {
            None if trimmed.starts_with("```") => {
                let fence = trimmed
                    .chars()
                    .take_while(|&c| c == '`')
                    .collect::<String>();
                let info = trimmed[fence.len()..].trim().to_string();
                open = Some((info, i + 2, indent, String::new(), fence));
                prose.push(String::new());
            }
            None => prose.push(line.to_string()),
            Some((info, start, ind, text, fence)) => {
                prose.push(String::new());
                if trimmed.starts_with(fence.as_str()) && trimmed.trim_end() == fence.as_str() {
                    blocks.push(Block {
                        info: std::mem::take(info),
                        line: *start,
                        text: std::mem::take(text),
                    });
                    open = None;
                } else {
                    let cut = line
                        .char_indices()
                        .take_while(|&(k, c)| k < *ind && c == ' ')
                        .count();
                    text.push_str(&line[cut..]);
                    text.push('\n');
                }
            }
        }
    }
    assert!(open.is_none(), "a code block is never closed");
    (blocks, prose)
}

/// A prose line without its inline code spans.
fn without_code(line: &str) -> String {
    let mut out = String::new();
    let mut inside = false;
    for c in line.chars() {
        if c == '`' {
            inside = !inside;
        } else if !inside {
            out.push(c);
        }
    }
    out
}

/// The targets of `[text](target)` and `![alt](target)` in a prose line.
fn link_targets(line: &str) -> Vec<String> {
    let line = without_code(line);
    let mut v = Vec::new();
    let mut rest = line.as_str();
    while let Some(k) = rest.find("](") {
        let after = &rest[k + 2..];
        let Some(end) = after.find(')') else { break };
        let target = after[..end].split_whitespace().next().unwrap_or("");
        if !target.is_empty() {
            v.push(target.to_string());
        }
        rest = &after[end..];
    }
    v
}

/// GitHub's anchor of a heading: lower case, letters, digits, `-` and `_`
/// kept, spaces made `-`, everything else dropped.
fn slug(heading: &str) -> String {
    let mut s = String::new();
    for c in heading.chars() {
        if c.is_alphanumeric() || c == '-' || c == '_' {
            s.extend(c.to_lowercase());
        } else if c == ' ' {
            s.push('-');
        }
    }
    s
}

/// The anchors of a page's headings (repeats numbered as GitHub does).
fn anchors(md: &str) -> BTreeSet<String> {
    let (_, prose) = split(md);
    let mut seen = BTreeSet::new();
    for line in prose {
        let t = line.trim_start();
        if t.starts_with('#') {
            let heading = t.trim_start_matches('#').trim();
            let base = slug(heading);
            let mut a = base.clone();
            let mut n = 0;
            while seen.contains(&a) {
                n += 1;
                a = format!("{base}-{n}");
            }
            seen.insert(a);
        }
    }
    seen
}

#[test]
fn every_link_and_image_exists_and_every_anchor_is_a_heading() {
    let mut bad = Vec::new();
    for page in pages() {
        let md = std::fs::read_to_string(&page).unwrap();
        let (_, prose) = split(&md);
        for (i, line) in prose.iter().enumerate() {
            for target in link_targets(line) {
                if target.starts_with("http://")
                    || target.starts_with("https://")
                    || target.starts_with("mailto:")
                {
                    continue;
                }
                let (file, anchor) = match target.split_once('#') {
                    Some((f, a)) => (f, Some(a)),
                    None => (target.as_str(), None),
                };
                let path = match file.is_empty() {
                    true => page.clone(),
                    false => page.parent().unwrap().join(file),
                };
                let at = format!("{}:{}: {target}", rel(&page), i + 1);
                if !path.exists() {
                    bad.push(format!("{at}: no such file"));
                    continue;
                }
                if let Some(a) = anchor
                    && path.extension().is_some_and(|e| e == "md")
                    && !anchors(&std::fs::read_to_string(&path).unwrap()).contains(a)
                {
                    bad.push(format!("{at}: no heading with this anchor"));
                }
            }
        }
    }
    assert!(bad.is_empty(), "broken links:\n{}", bad.join("\n"));
}

#[test]
fn every_picture_is_shown_by_a_page() {
    let text: String = pages()
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    let mut orphans = Vec::new();
    for e in std::fs::read_dir(root().join("docs/img")).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().to_string();
        if !text.contains(&format!("img/{name}")) {
            orphans.push(name);
        }
    }
    assert!(orphans.is_empty(), "pictures no page shows: {orphans:?}");
}

/// Every file under `dir` whose extension is one of `exts`.
fn files(dir: &Path, exts: &[&str], out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    for e in rd {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy();
        if p.is_dir() {
            if !matches!(name.as_ref(), "target" | ".git" | "node_modules") {
                files(&p, exts, out);
            }
        } else if p
            .extension()
            .is_some_and(|e| exts.contains(&e.to_string_lossy().as_ref()))
        {
            out.push(p);
        }
    }
}

/// The docs, the code and the scripts: what may tell history.
fn sources() -> Vec<PathBuf> {
    let mut v = pages();
    for dir in ["src", "crates", "tests", "benches", "fuzz", "scripts"] {
        files(
            &root().join(dir),
            &["rs", "sh", "py", "ron", "cpp", "mjs", "js"],
            &mut v,
        );
    }
    v
}

/// Whether `text` names a session, an issue or an item by number
/// (`session 12`, `issue 26`, `issue #26`, `item 7`, `Issue 5`).
fn tells_history(text: &str) -> Option<String> {
    let lower = text.to_lowercase();
    for word in ["session", "issue", "item"] {
        let mut rest = lower.as_str();
        while let Some(k) = rest.find(word) {
            let before = rest[..k].chars().next_back();
            let after = &rest[k + word.len()..];
            rest = after;
            if before.is_some_and(char::is_alphanumeric) {
                continue;
            }
            let after = after.strip_prefix('s').unwrap_or(after);
            let after = after.strip_prefix(' ').unwrap_or(after);
            let after = after.strip_prefix('#').unwrap_or(after);
            if after.starts_with(|c: char| c.is_ascii_digit()) {
                let n: String = after.chars().take_while(char::is_ascii_digit).collect();
                return Some(format!("{word} {n}"));
            }
        }
    }
    None
}

#[test]
fn no_page_or_comment_tells_history() {
    assert_eq!(tells_history("as in Session 12"), Some("session 12".into()));
    assert_eq!(
        tells_history("(issue #26, item 7)"),
        Some("issue 26".into())
    );
    assert_eq!(tells_history("an item list of 3 issues"), None);
    let mut bad = Vec::new();
    for f in sources() {
        if f.ends_with("tests/docs.rs") {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap_or_default();
        for (i, line) in text.lines().enumerate() {
            if let Some(w) = tells_history(line) {
                bad.push(format!("{}:{}: `{w}`: {}", rel(&f), i + 1, line.trim()));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "history belongs in git and CHANGELOG.md; state the fact, or cite docs/math.md § or the test:\n{}",
        bad.join("\n")
    );
}

#[test]
fn build_help_names_every_export_format() {
    let out = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
        .args(["build", "--help"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).unwrap();
    let top = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
        .arg("--help")
        .output()
        .unwrap();
    let top = String::from_utf8(top.stdout).unwrap();
    let line = top
        .lines()
        .find(|l| l.trim_start().starts_with("build "))
        .expect("the top-level help lists build");
    for f in Format::ALL {
        assert!(line.contains(f.name()), "`--help` on build: {line}");
        for e in f.extensions() {
            assert!(
                help.contains(&format!(".{e}")),
                "build --help lacks .{e}:\n{help}"
            );
        }
    }
}

/// Copies `from` into `to`, folders and all.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let dest = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy_tree(&p, &dest);
        } else {
            std::fs::copy(&p, &dest).unwrap();
        }
    }
}

/// A block's logical lines (continuations joined): the repository scripts
/// it runs, and the rest of its text to execute.
fn commands(block: &str) -> (Vec<String>, String) {
    let mut scripts = Vec::new();
    let mut run = String::new();
    let mut logical = String::new();
    for line in block.lines() {
        logical.push_str(line);
        logical.push('\n');
        if line.trim_end().ends_with('\\') {
            continue;
        }
        let words: Vec<&str> = logical.split_whitespace().collect();
        let script = match words.as_slice() {
            ["bash" | "python3", s, ..] if s.starts_with("scripts/") => Some(s.to_string()),
            _ => None,
        };
        match script {
            Some(s) => scripts.push(s),
            None => run.push_str(&logical),
        }
        logical.clear();
    }
    run.push_str(&logical);
    (scripts, run)
}

fn runs_anything(script: &str) -> bool {
    script
        .lines()
        .any(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
}

#[test]
fn every_shell_block_runs() {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_streamline-studio"));
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let scratch_root = std::env::temp_dir().join(format!("ss-docs-{}", std::process::id()));
    let mut failures = Vec::new();
    let mut ran = 0;
    for page in pages() {
        let md = std::fs::read_to_string(&page).unwrap();
        let (blocks, _) = split(&md);
        let sh: Vec<&Block> = blocks.iter().filter(|b| b.info == "sh").collect();
        if sh.is_empty() {
            continue;
        }
        let name = page.file_stem().unwrap().to_string_lossy().to_string();
        let dir = scratch_root.join(&name);
        copy_tree(&root().join("scenes"), &dir.join("scenes"));
        copy_tree(&root().join("tests/data"), &dir.join("tests/data"));
        copy_tree(&root().join("tests/scripts"), &dir.join("tests/scripts"));
        for b in sh {
            let at = format!("{}:{}", rel(&page), b.line);
            let (scripts, run) = commands(&b.text);
            for s in scripts {
                let file = root().join(&s);
                let check = match s.ends_with(".py") {
                    true => Command::new("python3")
                        .args(["-c", "import ast,sys; ast.parse(open(sys.argv[1]).read())"])
                        .arg(&file)
                        .output(),
                    false => Command::new("bash").arg("-n").arg(&file).output(),
                };
                if !file.is_file() || !check.is_ok_and(|o| o.status.success()) {
                    failures.push(format!("{at}: {s} is missing or does not parse"));
                }
            }
            if !runs_anything(&run) {
                continue;
            }
            let script = format!("set -euo pipefail\n{run}");
            let mut cmd = match run.contains("streamline-studio screenshot") {
                true => {
                    let mut c = Command::new("xvfb-run");
                    c.args([
                        "-a",
                        "-s",
                        "-screen 0 1280x800x24",
                        "timeout",
                        "600",
                        "bash",
                        "-c",
                    ]);
                    c
                }
                false => {
                    let mut c = Command::new("timeout");
                    c.args(["600", "bash", "-c"]);
                    c
                }
            };
            let out = cmd
                .arg(&script)
                .current_dir(&dir)
                .env("PATH", &path)
                .output()
                .expect("bash, timeout and xvfb-run are installed (scripts/setup.sh)");
            ran += 1;
            if !out.status.success() {
                failures.push(format!(
                    "{at}: exit {:?}\n--- block ---\n{run}--- stderr ---\n{}",
                    out.status.code(),
                    String::from_utf8_lossy(&out.stderr)
                ));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&scratch_root);
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(ran >= 3, "only {ran} blocks ran");
}

#[test]
fn the_readme_test_command_is_what_ci_runs() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let ci = std::fs::read_to_string(root().join(".ci/run")).unwrap();
    let (blocks, _) = split(&readme);
    let first = blocks
        .iter()
        .find(|b| b.info == "sh")
        .expect("the README opens with its two commands in a sh block");
    let lines: Vec<&str> = first
        .text
        .lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .collect();
    assert_eq!(
        lines,
        ["bash scripts/editor.sh", "bash scripts/test.sh"],
        "the README's first block is its two commands"
    );
    assert!(
        ci.lines().any(|l| l.trim() == "bash scripts/test.sh"),
        ".ci/run runs the README's test command"
    );
}

#[test]
fn help_names_every_built_in_scene() {
    let out = Command::new(env!("CARGO_BIN_EXE_streamline-studio"))
        .arg("--help")
        .output()
        .unwrap();
    let help = String::from_utf8(out.stdout).unwrap();
    for (name, _) in streamline_studio::scene::design::builtin::SCENES {
        assert!(
            help.contains(name),
            "--help lacks the built-in scene {name}:\n{help}"
        );
    }
}

/// The tables of docs/benchmarks.md are what `scripts/bench_tables.py`
/// makes of the saved results in docs/bench/: no figure typed by hand.
#[test]
fn the_benchmark_tables_are_generated_from_the_saved_results() {
    let out = Command::new("python3")
        .args(["scripts/bench_tables.py", "--check"])
        .current_dir(root())
        .output()
        .expect("python3 is on the machine");
    assert!(
        out.status.success(),
        "docs/benchmarks.md differs from its saved results; run `python3 scripts/bench_tables.py --from docs/bench`:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `screenshot --help` lists the panel sections the option takes: every
/// one it names opens, and a wrong name is refused with the same list.
#[test]
fn screenshot_help_names_every_panel_section() {
    let bin = env!("CARGO_BIN_EXE_streamline-studio");
    let help = Command::new(bin)
        .args(["screenshot", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8(help.stdout).unwrap();
    let line = help
        .lines()
        .find(|l| l.contains("Open only this panel section:"))
        .expect("--panel is described");
    let listed: Vec<&str> = line
        .split_once(':')
        .unwrap()
        .1
        .trim()
        .trim_end_matches('.')
        .split(", ")
        .collect();
    let out = Command::new(bin)
        .args(["screenshot", "--panel", "no-such", "--out", "x.png"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    let refused: Vec<&str> = err
        .split_once("choose one of ")
        .expect("the refusal lists the sections")
        .1
        .trim()
        .split(", ")
        .collect();
    let (mut a, mut b) = (listed.clone(), refused.clone());
    a.sort_unstable();
    b.sort_unstable();
    assert_eq!(
        a, b,
        "--help lists {listed:?}, the parser takes {refused:?}"
    );
}
