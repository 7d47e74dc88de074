//! The files of `src/editor`, `src/ecs`, `src/scene` and `src/cli` import each other
//! without a circle. Each folder is checked on its own: its nodes are its
//! files and sub-folders (a sub-folder is one node, checked in turn); a
//! file's use of its folder's `mod.rs` items, and `mod.rs`'s use of its
//! children, are the tree itself and not edges. Code under `#[cfg(test)]`
//! (the files' own tests, at their end) is not counted.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The source of a file with its tests and comments taken out.
fn code(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let text = match text.find("#[cfg(test)]") {
        Some(i) => &text[..i],
        None => &text[..],
    };
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The first path segment after each occurrence of `prefix` (`prefix{a::x, b}`
/// gives `a` and `b`).
fn segments_after(code: &str, prefix: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find(prefix) {
        // a match inside a longer path (`super::super::`) counts from its start only
        let before = rest[..i].chars().last();
        rest = &rest[i + prefix.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
            continue;
        }
        if let Some(inner) = rest.strip_prefix('{') {
            // a group: the first segment of each top-level item
            let mut depth = 0;
            let mut item = String::new();
            let mut items = Vec::new();
            for c in inner.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => items.push(std::mem::take(&mut item)),
                    _ if depth == 0 => item.push(c),
                    _ => {}
                }
            }
            items.push(item);
            for it in items {
                let first: String = it
                    .trim()
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !first.is_empty() {
                    out.push(first);
                }
            }
        } else {
            let first: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !first.is_empty() {
                out.push(first);
            }
        }
    }
    out
}

/// The modules of folder `dir`: name → the files that make it up.
fn children(dir: &Path) -> BTreeMap<String, Vec<PathBuf>> {
    let mut out = BTreeMap::new();
    for e in std::fs::read_dir(dir).expect("a source folder") {
        let p = e.expect("an entry").path();
        let name = p.file_stem().unwrap().to_string_lossy().to_string();
        if p.is_dir() {
            let mut files = Vec::new();
            collect(&p, &mut files);
            out.insert(name, files);
        } else if p.extension().is_some_and(|x| x == "rs") && name != "mod" {
            out.insert(name, vec![p]);
        }
    }
    out
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("a source folder") {
        let p = e.expect("an entry").path();
        if p.is_dir() {
            collect(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The edges between the modules of folder `dir` (whose path from the crate
/// root is `crate_path`, such as `crate::editor`), and the sub-folders.
fn edges(dir: &Path, crate_path: &str) -> (BTreeMap<String, BTreeSet<String>>, Vec<PathBuf>) {
    let kids = children(dir);
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut folders = Vec::new();
    for (name, files) in &kids {
        let node = graph.entry(name.clone()).or_default();
        let sub = dir.join(name);
        if sub.is_dir() {
            folders.push(sub.clone());
        }
        for f in files {
            let c = code(f);
            // how `super::` reaches this folder from the file
            let depth = f
                .parent()
                .unwrap()
                .strip_prefix(dir)
                .map(|p| p.components().count())
                .unwrap_or(0);
            let is_mod = f.file_name().is_some_and(|n| n == "mod.rs");
            let up = if is_mod { depth } else { depth + 1 };
            let mut refs = segments_after(&c, &format!("{crate_path}::"));
            if up >= 1 {
                refs.extend(segments_after(&c, &"super::".repeat(up)));
            }
            for r in refs {
                if r != *name && kids.contains_key(&r) {
                    node.insert(r);
                }
            }
        }
    }
    (graph, folders)
}

/// A circle in `graph`, if there is one.
fn cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        n: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(n.to_string(), 1);
        path.push(n.to_string());
        for m in graph.get(n).into_iter().flatten() {
            match state.get(m.as_str()).copied().unwrap_or(0) {
                1 => {
                    let at = path.iter().position(|p| p == m).unwrap();
                    let mut c = path[at..].to_vec();
                    c.push(m.clone());
                    return Some(c);
                }
                0 => {
                    if let Some(c) = visit(m, graph, state, path) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        path.pop();
        state.insert(n.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in graph.keys() {
        if state.get(n.as_str()).copied().unwrap_or(0) == 0
            && let Some(c) = visit(n, graph, &mut state, &mut Vec::new())
        {
            return Some(c);
        }
    }
    None
}

/// Checks `dir` and its sub-folders; returns the folders checked and the edges seen.
fn check(dir: &Path, crate_path: &str) -> (usize, usize) {
    let (graph, folders) = edges(dir, crate_path);
    if let Some(c) = cycle(&graph) {
        panic!("{}: a circle of imports: {}", dir.display(), c.join(" → "));
    }
    let mut counts = (1, graph.values().map(BTreeSet::len).sum());
    for f in folders {
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        let (a, b) = check(&f, &format!("{crate_path}::{name}"));
        counts.0 += a;
        counts.1 += b;
    }
    counts
}

fn src(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join(p)
}

#[test]
fn editor_files_import_each_other_without_a_circle() {
    let (folders, edges) = check(&src("editor"), "crate::editor");
    // the check sees the editor's imports (not an empty graph)
    assert!(
        folders >= 2 && edges >= 20,
        "{folders} folders, {edges} edges"
    );
}

#[test]
fn ecs_files_import_each_other_without_a_circle() {
    let (_, edges) = check(&src("ecs"), "crate::ecs");
    assert!(edges >= 10, "{edges} edges");
}

#[test]
fn scene_files_import_each_other_without_a_circle() {
    let (_, edges) = check(&src("scene"), "crate::scene");
    assert!(edges >= 20, "{edges} edges");
}

#[test]
fn cli_files_import_each_other_without_a_circle() {
    let (_, edges) = check(&src("cli"), "crate::cli");
    assert!(edges >= 3, "{edges} edges");
}

/// The checker finds a circle where there is one, through `use` groups,
/// inline paths and `super::super::` alike.
#[test]
fn the_checker_sees_circles() {
    let dir = std::env::temp_dir().join(format!("module_graph_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let w = |p: &str, t: &str| std::fs::write(dir.join(p), t).unwrap();
    w("mod.rs", "mod a; mod b; mod sub;");
    w("a.rs", "use super::{b::X, c};\n");
    w("b.rs", "fn f() { super::c::g() } // super::a::h()\n");
    w(
        "c.rs",
        "use crate::m::d::Y;\n#[cfg(test)]\nmod tests { use super::a::Z; }\n",
    );
    w("d.rs", "fn h() {}");
    w("sub/mod.rs", "mod s;");
    w("sub/s.rs", "use super::super::d::Q;");
    let (graph, _) = edges(&dir, "crate::m");
    let set = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<BTreeSet<_>>();
    assert_eq!(graph["a"], set(&["b", "c"]));
    assert_eq!(graph["b"], set(&["c"]));
    assert_eq!(graph["c"], set(&["d"]));
    assert_eq!(graph["sub"], set(&["d"]));
    assert!(cycle(&graph).is_none());
    w("d.rs", "fn h() { crate::m::a::f() }");
    let (graph, _) = edges(&dir, "crate::m");
    let c = cycle(&graph).expect("a → c → d → a");
    assert_eq!(c.first(), c.last());
    std::fs::remove_dir_all(&dir).unwrap();
}
