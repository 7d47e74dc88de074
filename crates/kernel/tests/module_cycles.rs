//! The kernel's top-level modules and folders import each other without a
//! circle: every `crate::a::…` path written in a file of module `b` (outside
//! comments) is an edge `b → a`, and the graph of those edges must be acyclic,
//! so the folders can be read bottom-up (sphere → curve → streamline → levels).
//!
//! The same holds between files: every `crate::a::b::…`
//! path and every `super::…` path (in `use` or inline) in a file of the kernel
//! is an edge from that file's module (`a/b.rs` is `a::b`, `a/mod.rs` is `a`)
//! to the module file the path names (its longest prefix that is a module of
//! the kernel; `use crate::a::{b::X, c}` names `a::b` and `a::c`), and that
//! graph must be acyclic too, so the files of a folder can be read bottom-up.
//!
//! What counts, in both graphs: all code outside `//` comments, the
//! `#[cfg(test)] mod tests` blocks included (a unit test is compiled into its
//! file and reads that file's imports, so a test that needs a file above its
//! own is a circle like any other; put such a test in the file above, or in
//! `tests/`). `lib.rs` is left out (the root declares and re-exports every
//! module), and so are a `mod.rs`'s declarations and bare re-exports of its
//! own children (`pub use child::X`: the folder's table of contents); a
//! `super::` inside an inline `mod` names the file itself (no edge).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Top-level module of a file under `src/`: its folder, or its stem.
fn module_of(rel: &Path) -> String {
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The modules named right after `crate::` in a line of code.
fn crate_paths(line: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = line;
    while let Some(i) = rest.find("crate::") {
        let before = rest[..i].chars().last();
        rest = &rest[i + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        let name: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        if let Some(group) = rest.strip_prefix('{') {
            // `use crate::{a::x, b};`
            let inner = group.split('}').next().unwrap_or("");
            for part in inner.split(',') {
                let m: String = part
                    .trim()
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                if !m.is_empty() {
                    found.push(m);
                }
            }
        } else if !name.is_empty() {
            found.push(name);
        }
    }
    found
}

/// The edges `from → to` between top-level modules of `crates/kernel/src`.
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let modules: BTreeSet<String> = files
        .iter()
        .map(|f| module_of(f.strip_prefix(&src).unwrap()))
        .collect();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let from = module_of(f.strip_prefix(&src).unwrap());
        if from == "lib" {
            continue; // the root declares and re-exports every module
        }
        for line in fs::read_to_string(f).unwrap().lines() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue; // doc links are not imports
            }
            for to in crate_paths(code) {
                if to != from && modules.contains(&to) {
                    edges.entry(from.clone()).or_default().insert(to);
                }
            }
        }
    }
    edges
}

/// A cycle of the graph, if there is one, as the list of its modules.
fn find_cycle(edges: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        n: &str,
        edges: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(n.to_string(), 1);
        stack.push(n.to_string());
        for m in edges.get(n).into_iter().flatten() {
            match state.get(m.as_str()).copied().unwrap_or(0) {
                1 => {
                    let at = stack.iter().position(|s| s == m).unwrap();
                    let mut cycle = stack[at..].to_vec();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(m, edges, state, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(n.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in edges.keys() {
        if state.get(n.as_str()).copied().unwrap_or(0) == 0
            && let Some(c) = visit(n, edges, &mut state, &mut Vec::new())
        {
            return Some(c);
        }
    }
    None
}

#[test]
fn the_parser_sees_paths_and_groups() {
    assert_eq!(crate_paths("use crate::levels::surface::X;"), ["levels"]);
    assert_eq!(
        crate_paths("use crate::{grid::Grid, error};"),
        ["grid", "error"]
    );
    assert_eq!(
        crate_paths("let x = crate::simd::f(a) + $crate::no;"),
        ["simd"]
    );
    assert!(crate_paths("let y = my_crate::x;").is_empty());
}

#[test]
fn the_cycle_finder_finds_a_planted_cycle() {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.entry("a".into()).or_default().insert("b".into());
    g.entry("b".into()).or_default().insert("c".into());
    assert_eq!(find_cycle(&g), None);
    g.entry("c".into()).or_default().insert("a".into());
    assert_eq!(find_cycle(&g).unwrap(), ["a", "b", "c", "a"]);
}

#[test]
fn no_cycle_among_the_kernels_top_level_modules() {
    let edges = graph();
    assert!(
        edges.contains_key("levels") && edges["levels"].contains("curve"),
        "the parser found no edges: {edges:?}"
    );
    if let Some(cycle) = find_cycle(&edges) {
        panic!(
            "the kernel's modules import each other in a circle: {} \
             (move the shared item down, e.g. into limits or grid); all edges: {edges:?}",
            cycle.join(" → ")
        );
    }
}

// ---------------------------------------------------------------- files

/// Module path of a file under `src/` (`levels/surface.rs` → `levels::surface`,
/// `levels/mod.rs` → `levels`), as segments; `None` for `lib.rs`.
fn file_module(rel: &Path) -> Option<Vec<String>> {
    let mut segs: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if segs == ["lib"] {
        return None;
    }
    if segs.last().is_some_and(|s| s == "mod") {
        segs.pop();
    }
    Some(segs)
}

/// The file's text with `//` comments (and doc comments) blanked out, line
/// breaks kept; a `//` inside a string literal is kept.
fn strip_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let mut in_str = false;
        let mut prev = ' ';
        let mut cut = line.len();
        for (i, c) in line.char_indices() {
            if c == '"' && prev != '\\' {
                in_str = !in_str;
            }
            if !in_str && c == '/' && prev == '/' {
                cut = i - 1;
                break;
            }
            prev = c;
        }
        out.push_str(&line[..cut]);
        out.push('\n');
    }
    out
}

fn ident(s: &str) -> (&str, &str) {
    let end = s
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    (&s[..end], &s[end..])
}

/// The paths of a path tail after `prefix::` (`a::b::X`, `a::{b::X, c}`,
/// nested groups, across lines): each as its list of segments, `prefix` first.
fn expand(prefix: Vec<String>, rest: &str, out: &mut Vec<Vec<String>>) {
    let rest = rest.trim_start();
    if let Some(group) = rest.strip_prefix('{') {
        // split the group at its top-level commas
        let (mut depth, mut start) = (0usize, 0usize);
        for (i, c) in group.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    expand(prefix.clone(), &group[start..i], out);
                    return;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    expand(prefix.clone(), &group[start..i], out);
                    start = i + 1;
                }
                _ => {}
            }
        }
        return;
    }
    let (name, tail) = ident(rest);
    if name.is_empty() {
        out.push(prefix);
        return;
    }
    let mut p = prefix;
    p.push(name.to_string());
    match tail.trim_start().strip_prefix("::") {
        Some(more) => expand(p, more, out),
        None => out.push(p),
    }
}

/// Every `crate::…` and `super::…` path in comment-free `code`, as absolute
/// segments, for a file of module `module`; a `super` inside an inline `mod`
/// block counts from that block.
fn file_paths(module: &[String], code: &str) -> Vec<Vec<String>> {
    // inline `mod name {` blocks: byte ranges
    let mut inline: Vec<(usize, usize)> = Vec::new();
    let mut search = 0;
    while let Some(i) = code[search..].find("mod ") {
        let at = search + i;
        search = at + 4;
        if code[..at]
            .chars()
            .last()
            .is_some_and(|c| c.is_alphanumeric() || c == '_')
        {
            continue;
        }
        let (name, tail) = ident(&code[at + 4..]);
        if name.is_empty() || !tail.trim_start().starts_with('{') {
            continue;
        }
        let open = code.len() - tail.trim_start().len();
        let mut depth = 0usize;
        for (j, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        inline.push((open, open + j));
                        break;
                    }
                }
                _ => {}
            }
        }
    }
    let mut found = Vec::new();
    for key in ["crate::", "super::"] {
        let mut search = 0;
        while let Some(i) = code[search..].find(key) {
            let at = search + i;
            search = at + key.len();
            let before = code[..at].chars().last();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$' || c == ':') {
                continue;
            }
            let mut prefix: Vec<String> = Vec::new();
            let mut rest = &code[at + key.len()..];
            if key == "super::" {
                let nested = inline.iter().filter(|(a, b)| *a < at && at < *b).count();
                prefix = module.to_vec();
                prefix.extend((0..nested).map(|_| "<inline>".to_string()));
                prefix.pop();
                while let Some(r) = rest.trim_start().strip_prefix("super::") {
                    prefix.pop();
                    rest = r;
                }
            }
            expand(prefix, rest, &mut found);
        }
    }
    found
}

/// The module a path names: its longest prefix that is a module of the kernel.
fn resolve(path: &[String], modules: &BTreeSet<Vec<String>>) -> Option<Vec<String>> {
    (1..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|p| modules.contains(p))
}

/// The files of `crates/kernel/src` by module path (`lib.rs` left out).
fn kernel_files() -> BTreeMap<Vec<String>, PathBuf> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files
        .into_iter()
        .filter_map(|f| {
            let rel = f.strip_prefix(&src).unwrap().to_path_buf();
            file_module(&rel).map(|m| (m, rel))
        })
        .collect()
}

/// The edges `from → to` between the kernel's files, by module path (`a::b`).
fn file_graph(files: &BTreeMap<Vec<String>, PathBuf>) -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let modules: BTreeSet<Vec<String>> = files.keys().cloned().collect();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (from, rel) in files {
        let code = strip_comments(&fs::read_to_string(src.join(rel)).unwrap());
        for path in file_paths(from, &code) {
            if let Some(to) = resolve(&path, &modules)
                && &to != from
            {
                edges
                    .entry(from.join("::"))
                    .or_default()
                    .insert(to.join("::"));
            }
        }
    }
    edges
}

/// The strongly connected components with more than one node (Tarjan).
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<BTreeSet<String>> {
    struct T<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        out: Vec<BTreeSet<String>>,
    }
    fn go<'a>(t: &mut T<'a>, n: &'a str) {
        let i = t.index.len();
        t.index.insert(n, i);
        t.low.insert(n, i);
        t.stack.push(n);
        t.on.insert(n);
        if let Some(next) = t.edges.get(n) {
            for m in next {
                let m = m.as_str();
                if !t.index.contains_key(m) {
                    go(t, m);
                    let l = t.low[m].min(t.low[n]);
                    t.low.insert(n, l);
                } else if t.on.contains(m) {
                    let l = t.index[m].min(t.low[n]);
                    t.low.insert(n, l);
                }
            }
        }
        if t.low[n] == t.index[n] {
            let mut comp = BTreeSet::new();
            while let Some(m) = t.stack.pop() {
                t.on.remove(m);
                comp.insert(m.to_string());
                if m == n {
                    break;
                }
            }
            if comp.len() > 1 {
                t.out.push(comp);
            }
        }
    }
    let mut t = T {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        out: Vec::new(),
    };
    for n in edges.keys() {
        if !t.index.contains_key(n.as_str()) {
            go(&mut t, n);
        }
    }
    t.out
}

#[test]
fn the_file_parser_sees_crate_super_and_nested_groups() {
    let m: Vec<String> = vec!["levels".into(), "design".into()];
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    let code = "use crate::levels::{surface::{A, B}, params::\n    ParamGrid};\n\
                use super::builder::Builder;\nlet x = my_crate::no + crate::grid::f();\n\
                mod tests { use super::*; }\n";
    let found = file_paths(&m, code);
    assert!(found.contains(&s(&["levels", "surface", "A"])), "{found:?}");
    assert!(
        found.contains(&s(&["levels", "params", "ParamGrid"])),
        "{found:?}"
    );
    assert!(
        found.contains(&s(&["levels", "builder", "Builder"])),
        "{found:?}"
    );
    assert!(found.contains(&s(&["grid", "f"])), "{found:?}");
    // `super` in the inline `mod tests` is the file itself
    assert!(found.contains(&s(&["levels", "design"])), "{found:?}");
    assert_eq!(found.len(), 6, "{found:?}");
    assert_eq!(
        strip_comments("a // crate::x\n\"//\" b\n"),
        "a \n\"//\" b\n"
    );
    let modules: BTreeSet<Vec<String>> = [s(&["levels"]), s(&["levels", "surface"])]
        .into_iter()
        .collect();
    assert_eq!(
        resolve(&s(&["levels", "surface", "refine", "x"]), &modules),
        Some(s(&["levels", "surface"]))
    );
    assert_eq!(
        file_module(Path::new("levels/mod.rs")),
        Some(s(&["levels"]))
    );
    assert_eq!(file_module(Path::new("lib.rs")), None);
}

#[test]
fn the_circle_finder_finds_planted_circles() {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.entry("a".into()).or_default().insert("b".into());
    g.entry("b".into()).or_default().insert("c".into());
    assert!(circles(&g).is_empty());
    g.entry("c".into()).or_default().insert("a".into());
    g.entry("d".into()).or_default().insert("e".into());
    g.entry("e".into()).or_default().insert("d".into());
    assert_eq!(circles(&g).len(), 2);
}

#[test]
fn no_cycle_among_the_kernels_files() {
    let files = kernel_files();
    let edges = file_graph(&files);
    assert!(
        edges
            .get("levels::incremental")
            .is_some_and(|e| e.contains("levels::params") && e.contains("curve::scalar")),
        "the parser found no edges between files: {edges:?}"
    );
    let name = |m: &str| {
        let key: Vec<String> = m.split("::").map(String::from).collect();
        format!("src/{}", files[&key].display())
    };
    let mut report = Vec::new();
    for comp in circles(&edges) {
        let sub: BTreeMap<String, BTreeSet<String>> = comp
            .iter()
            .map(|n| {
                let next = edges[n].intersection(&comp).cloned().collect();
                (n.clone(), next)
            })
            .collect();
        let cycle = find_cycle(&sub).expect("a component of two or more has a circle");
        let files: Vec<String> = cycle.iter().map(|m| name(m)).collect();
        let inner: Vec<String> = sub
            .iter()
            .flat_map(|(a, bs)| bs.iter().map(move |b| format!("{} → {}", name(a), name(b))))
            .collect();
        report.push(format!(
            "  {}\n    (all edges inside: {})",
            files.join(" → "),
            inner.join(", ")
        ));
    }
    assert!(
        report.is_empty(),
        "the kernel's files import each other in a circle (move the shared item \
         into the lower file or a new small one):\n{}",
        report.join("\n")
    );
}
