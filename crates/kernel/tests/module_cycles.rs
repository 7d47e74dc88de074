//! The kernel's top-level modules and folders import each other without a
//! circle: every `crate::a::…` path written in a file of module `b` (outside
//! comments) is an edge `b → a`, and the graph of those edges must be acyclic,
//! so the folders can be read bottom-up (sphere → curve → streamline → levels).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

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
