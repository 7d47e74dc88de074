//! Checked by OpenSubdiv itself (`docs/math.md §7`, docs/loop.md): a small C++
//! oracle (`tests/oracle/osd_loop.cpp`) is compiled against Debian's
//! `libosd-dev` (OpenSubdiv 3.5; `bash scripts/setup.sh --tests` installs it
//! and g++) and run on every test mesh and on the knight with holes cut (5
//! boundary loops, 2 single-face corners). With the edge-only and the
//! edge-and-corner rules, for the control mesh we interpolate at 1e-7:
//! - OpenSubdiv's own limit positions (`Far::PrimvarRefiner::Limit`) of it are
//!   within 1e-6 of the given vertices (box side 1) computing in float, and
//!   within 1.01e-7 computing in double, boundary vertices included;
//! - our subdivided levels 1 and 2 equal OpenSubdiv's uniformly refined levels
//!   as point sets: to 1e-6 (float) and 1e-11 (double) of the box side.
//!
//! And the check can fail: the control mesh made for 002's boundary rules
//! misses open meshes' boundary vertices in OpenSubdiv by far more.
//!
//! The test fails (never skips) when g++ or OpenSubdiv is missing.

mod common;

use glam::DVec3;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use streamline_kernel::loop_subdiv::mesh_interpolation::{Method, Options, interpolate};
use streamline_kernel::loop_subdiv::subdivide::{BoundaryRule, subdivide};
use streamline_kernel::loop_subdiv::trimesh::{Topology, TriMesh};

const SETUP: &str =
    "run `bash scripts/setup.sh --tests` (installs g++ and Debian's libosd-dev, OpenSubdiv 3.5)";

/// The oracle, compiled once per source change into the test's target dir.
/// The tests run in parallel: the first to get here compiles it (into a
/// temporary name, renamed when done), the others wait for it.
fn oracle() -> PathBuf {
    static ORACLE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    ORACLE.get_or_init(compile_oracle).clone()
}

fn compile_oracle() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let src = root.join("tests/oracle/osd_loop.cpp");
    let bin = Path::new(env!("CARGO_TARGET_TMPDIR")).join("osd_loop");
    let stamp = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    if stamp(&bin).is_none() || stamp(&bin) < stamp(&src) {
        let tmp = bin.with_extension(format!("tmp{}", std::process::id()));
        let out = Command::new("g++")
            .args(["-O2", "-std=c++14"])
            .arg(&src)
            .arg("-o")
            .arg(&tmp)
            .arg("-losdCPU")
            .output()
            .unwrap_or_else(|e| panic!("cannot run g++ ({e}): {SETUP}"));
        assert!(
            out.status.success(),
            "compiling {} against OpenSubdiv failed: {SETUP}\n{}",
            src.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::rename(&tmp, &bin).unwrap_or_else(|e| panic!("{}: {e}", bin.display()));
    }
    bin
}

use common::loop_meshes::{MESHES, read_mesh, with_holes};

/// Writes an OBJ with every coordinate round-tripping exactly.
fn write_obj(path: &Path, p: &[DVec3], faces: &[[u32; 3]]) {
    use std::fmt::Write;
    let mut s = String::new();
    for v in p {
        writeln!(s, "v {} {} {}", v.x, v.y, v.z).unwrap();
    }
    for f in faces {
        writeln!(s, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1).unwrap();
    }
    std::fs::write(path, s).unwrap();
}

fn read_points(path: &Path) -> Vec<DVec3> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .map(|l| {
            let w: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            DVec3::new(w[0], w[1], w[2])
        })
        .collect()
}

/// Whether `a` and `b` are the same point set within `tol` (a one-to-one
/// matching through a grid of cells of side `4 tol`); the worst distance.
fn same_point_set(a: &[DVec3], b: &[DVec3], tol: f64) -> Result<f64, String> {
    if a.len() != b.len() {
        return Err(format!("{} points against {}", a.len(), b.len()));
    }
    let h = 4.0 * tol;
    let key = |p: DVec3| [p.x, p.y, p.z].map(|c| (c / h).floor() as i64);
    let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, &p) in b.iter().enumerate() {
        cells.entry(key(p)).or_default().push(i);
    }
    let mut used = vec![false; b.len()];
    let mut worst = 0.0f64;
    for (i, &p) in a.iter().enumerate() {
        let k = key(p);
        let mut best: Option<(usize, f64)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(c) = cells.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) else {
                        continue;
                    };
                    for &j in c {
                        let d = (b[j] - p).length();
                        if !used[j] && d <= tol && best.is_none_or(|(_, bd)| d < bd) {
                            best = Some((j, d));
                        }
                    }
                }
            }
        }
        match best {
            Some((j, d)) => {
                used[j] = true;
                worst = worst.max(d);
            }
            None => {
                return Err(format!(
                    "our point {i} {p:?} has no OpenSubdiv point within {tol:e}"
                ));
            }
        }
    }
    Ok(worst)
}

/// OpenSubdiv's (double) limit of `ctrl` under `rule`: the worst distance to `m`'s vertices.
fn osd_limit_miss(bin: &Path, dir: &Path, m: &TriMesh, ctrl: &[DVec3], rule: BoundaryRule) -> f64 {
    let obj = dir.join("probe.obj");
    write_obj(&obj, ctrl, &m.faces);
    let out = dir.join("probe");
    let run = Command::new(bin)
        .args(["eval", rule.name(), "double"])
        .arg(&obj)
        .arg("1")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let lim = read_points(&dir.join("probe.limit"));
    lim.iter()
        .zip(&m.positions)
        .map(|(a, b)| (*a - *b).length() / m.scale())
        .fold(0.0, f64::max)
}

#[test]
fn opensubdiv_tells_the_paper_rule_apart() {
    let bin = oracle();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("osd_paper");
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["snail.obj", "camelhead.obj"] {
        let (m, t) = read_mesh(name);
        let mut opts = Options {
            tolerance: 1e-7,
            max_iterations: 5000,
            method: Method::Fast,
            boundary: BoundaryRule::Paper,
        };
        let (paper, _) = interpolate(&m, &t, &opts);
        opts.boundary = BoundaryRule::EdgeAndCorner;
        let (ours, _) = interpolate(&m, &t, &opts);
        let miss_paper = osd_limit_miss(&bin, &dir, &m, &paper, BoundaryRule::EdgeAndCorner);
        let miss_ours = osd_limit_miss(&bin, &dir, &m, &ours, BoundaryRule::EdgeAndCorner);
        println!(
            "{name}: paper's control mesh misses by {miss_paper:.2e}, edge-and-corner's by {miss_ours:.2e}"
        );
        assert!(
            miss_paper > 1e-4 && miss_ours < 1.01e-7,
            "{name}: {miss_paper:e} {miss_ours:e}"
        );
    }
}

/// The knight with seven holes cut (faces all of whose vertices are within a
/// ring of a seed face dropped): five boundary loops (some holes merge) and
/// two single-face corners where a face is left hanging.
fn holed_knight() -> (TriMesh, Topology) {
    let (k, _) = read_mesh("knight.obj");
    let seeds = [3usize, 150, 290, 420, 610, 777, 930].map(|s| (s, 1));
    let holed = with_holes(&k, &seeds);
    TriMesh::new(holed.positions, holed.faces).expect("the holes leave a manifold mesh")
}

#[test]
fn opensubdiv_limit_of_our_control_mesh_hits_the_vertices() {
    let bin = oracle();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("osd_oracle");
    std::fs::create_dir_all(&dir).unwrap();
    let mut boundary_checked = 0;
    let mut meshes: Vec<(String, TriMesh, Topology)> = MESHES
        .iter()
        .map(|name| {
            let (m, t) = read_mesh(name);
            (name.to_string(), m, t)
        })
        .collect();
    let (m, t) = holed_knight();
    let corners = (0..t.vertices())
        .filter(|&v| t.boundary[v] && t.valence(v) == 2)
        .count();
    assert!(
        t.loops.len() >= 5 && corners >= 2,
        "knight with holes: {} loops, {corners} corners",
        t.loops.len()
    );
    meshes.push(("knight with holes".into(), m, t));
    for (name, m, t) in &meshes {
        let (name, m, t) = (name.as_str(), m, t);
        let scale = m.scale();
        for rule in [BoundaryRule::EdgeOnly, BoundaryRule::EdgeAndCorner] {
            let opts = Options {
                tolerance: 1e-7,
                max_iterations: 5000,
                method: Method::Fast,
                boundary: rule,
            };
            let (ctrl, rep) = interpolate(m, t, &opts);
            assert!(rep.converged, "{name} {}: {rep:?}", rule.name());
            let obj = dir.join(format!("{name}.{}.obj", rule.name()));
            write_obj(&obj, &ctrl, &m.faces);
            // our levels 1 and 2 of the control mesh
            let c0 = TriMesh {
                positions: ctrl.clone(),
                faces: m.faces.clone(),
            };
            let c1 = subdivide(&c0, t, rule).unwrap();
            let c2 = subdivide(&c1, &c1.topology().unwrap(), rule).unwrap();
            for (real, lim_tol, level_tol) in [("float", 1e-6, 1e-6), ("double", 1.01e-7, 1e-11)] {
                let out = dir.join(format!("{name}.{}.{real}", rule.name()));
                let run = Command::new(&bin)
                    .args(["eval", rule.name(), real])
                    .arg(&obj)
                    .arg("2")
                    .arg(&out)
                    .output()
                    .unwrap_or_else(|e| panic!("{}: {e}", bin.display()));
                assert!(
                    run.status.success(),
                    "oracle on {name}: {}",
                    String::from_utf8_lossy(&run.stderr)
                );
                let osd_lim = read_points(&out.with_extension(format!("{real}.limit")));
                assert_eq!(osd_lim.len(), m.positions.len());
                let mut worst = (0.0f64, 0usize);
                for (v, (l, p)) in osd_lim.iter().zip(&m.positions).enumerate() {
                    let d = (*l - *p).length() / scale;
                    if d > worst.0 {
                        worst = (d, v);
                    }
                    if t.boundary[v] {
                        boundary_checked += 1;
                    }
                }
                println!(
                    "{name} {} {real}: limit within {:.2e}",
                    rule.name(),
                    worst.0
                );
                assert!(
                    worst.0 < lim_tol,
                    "{name} {} {real}: OpenSubdiv's limit misses vertex {} by {:e} (box side 1)",
                    rule.name(),
                    worst.1 + 1,
                    worst.0
                );
                for (k, ours) in [(1, &c1), (2, &c2)] {
                    let theirs = read_points(&out.with_extension(format!("{real}.{k}")));
                    if let Err(e) = same_point_set(&ours.positions, &theirs, level_tol * scale) {
                        panic!("{name} {} {real} level {k}: {e}", rule.name());
                    }
                }
            }
        }
    }
    assert!(boundary_checked > 0, "open meshes were among the tested");
}
