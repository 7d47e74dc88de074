//! Loop subdivision beside OpenSubdiv's (docs/loop.md; `bash scripts/loop_vs_osd.sh`
//! runs it): for each mesh (an OBJ, `:k` to subdivide it `k` times first), each
//! boundary rule and levels 1–3, the best of 15 runs (3 rounds of 5, alternating
//! with OpenSubdiv's) of building the topology
//! from the face list and subdividing ([`subdivide_levels`]), one thread,
//! beside the best of 15 of the OpenSubdiv oracle (`tests/oracle/osd_loop.cpp`,
//! given with `--osd PATH`) doing the same in float: building its
//! `TopologyRefiner` from the face list, `RefineUniform`, `Interpolate` per
//! level. 002's rule, which OpenSubdiv lacks, is timed beside its edge-only.
//! Prints a Markdown table.
//!
//! `cargo run -p streamline-kernel --release --example loop_timing -- --osd BIN MESH.obj[:k] …`
#[path = "../tests/common/mod.rs"]
mod common;

use std::fmt::Write as _;
use std::process::Command;
use std::time::Instant;
use streamline_kernel::loop_subdiv::subdivide::{BoundaryRule, subdivide_levels};
use streamline_kernel::loop_subdiv::trimesh::TriMesh;

/// The tests' plain OBJ reader (`tests/common`), the mesh without its topology.
fn read_obj(path: &str) -> TriMesh {
    common::read_obj(std::path::Path::new(path)).0
}

fn write_obj(path: &std::path::Path, m: &TriMesh) {
    let mut s = String::new();
    for p in &m.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for f in &m.faces {
        let _ = writeln!(s, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    std::fs::write(path, s).unwrap();
}

/// OpenSubdiv's best-of-5 seconds for levels 1–3.
fn osd(bin: &str, rule: &str, obj: &std::path::Path) -> Vec<f64> {
    let out = Command::new(bin)
        .args(["bench", rule])
        .arg(obj)
        .args(["3", "5"])
        .output()
        .expect("the oracle runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.split(' ').nth(2).unwrap().parse().unwrap())
        .collect()
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let bin = match args.iter().position(|a| a == "--osd") {
        Some(i) => {
            let b = args.remove(i + 1);
            args.remove(i);
            b
        }
        None => panic!("give --osd PATH (the compiled tests/oracle/osd_loop.cpp)"),
    };
    let dir = std::env::temp_dir().join(format!("loop-timing-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    println!(
        "| mesh | vertices | rule | level | vertices out | ours | OpenSubdiv | ours ÷ OpenSubdiv |"
    );
    println!("|---|---:|---|---:|---:|---:|---:|---:|");
    for arg in args {
        let (path, pre) = match arg.split_once(':') {
            Some((p, n)) => (p.to_string(), n.parse::<u32>().unwrap()),
            None => (arg.clone(), 0),
        };
        let base = read_obj(&path);
        let t = base.topology().unwrap();
        let m = subdivide_levels(&base, &t, BoundaryRule::EdgeAndCorner, pre).unwrap();
        let stem = std::path::Path::new(&path)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let name = if pre > 0 {
            format!("{stem} ×{pre}")
        } else {
            stem.clone()
        };
        let obj = dir.join(format!("{stem}-{pre}.obj"));
        write_obj(&obj, &m);
        for rule in BoundaryRule::ALL {
            let peer = if rule == BoundaryRule::Paper {
                "edge-only"
            } else {
                rule.name()
            };
            // three rounds, ours and theirs alternating (the machine's load shifts)
            let (mut ours, mut theirs, mut outs) = ([f64::INFINITY; 3], [f64::INFINITY; 3], [0; 3]);
            for _ in 0..3 {
                for (k, o) in osd(&bin, peer, &obj).into_iter().enumerate() {
                    theirs[k] = theirs[k].min(o);
                }
                for level in 1..=3u32 {
                    for _ in 0..5 {
                        let t0 = Instant::now();
                        let t = m.topology().unwrap();
                        let s = subdivide_levels(&m, &t, rule, level).unwrap();
                        let k = level as usize - 1;
                        ours[k] = ours[k].min(t0.elapsed().as_secs_f64());
                        outs[k] = s.positions.len();
                        std::hint::black_box(&s);
                    }
                }
            }
            for level in 1..=3u32 {
                let (best, out) = (ours[level as usize - 1], outs[level as usize - 1]);
                let o = theirs[level as usize - 1];
                let label = if rule == BoundaryRule::Paper {
                    "paper (OSD: edge-only)"
                } else {
                    rule.name()
                };
                println!(
                    "| {name} | {} | {label} | {level} | {out} | {:.2} ms | {:.2} ms | {:.2} |",
                    m.positions.len(),
                    best * 1e3,
                    o * 1e3,
                    best / o
                );
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
