//! STEP shells of several patches (docs/math.md §10, §11; docs/cad.md,
//! "Several patches") read back by OpenCascade (tests/python/check_shell.py,
//! in the test virtual environment of `scripts/setup.sh --tests`): chains of
//! 2 and 3 copies of the car's net (each copy's first column the one
//! before's last) joined with G1 and G2, and G1 side joins on the car's
//! first and last streamlines. Each: one shell, one face per patch, valid, free edges
//! only on the outer boundary (a chain of N: 2N + 2), every face within its
//! tolerance of its patch's points (by OpenCascade's projection), and across each G1/G2 seam
//! (chains and side joins) the faces' normals within 0.1° at 40 points. The negative control: the
//! same patches fitted alone (no shared edge) leave every seam edge free.

mod common;

use glam::DVec3;
use std::path::{Path, PathBuf};
use streamline_kernel::Design;
use streamline_kernel::grid::Grid;
use streamline_kernel::joins::chain::chain;
use streamline_kernel::joins::edge_curve::EdgeCurve;
use streamline_kernel::joins::merged::g2_run;
use streamline_kernel::joins::{Continuity, Edge, Join, Stack, join};
use streamline_kernel::nurbs::{FitOptions, PatchGrid, SeamSpec, fit_alone};
use streamline_studio::scene::design::builtin;
use streamline_studio::scene::export::step::StepInfo;
use streamline_studio::scene::export::step_shell::{faces_text, write_shell};

const DEPTH: u32 = 5;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("streamline-shell-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn car() -> Design {
    builtin::scene("car1").unwrap().shown_design().unwrap()
}

/// A copy of `a` anchored at its first column, whose first column is `a`'s last.
fn next_copy(a: &Design) -> Design {
    let mut net = a.net().clone();
    let last = net.cols() - 1;
    for r in 0..net.rows() {
        net.set(r, 0, a.net().get(r, last));
    }
    Design::new(
        &net,
        a.params().s.clone(),
        a.params().t.clone(),
        0,
        a.scheme(),
        a.order(),
        a.initial().clone(),
    )
    .unwrap()
}

/// A chain of `n` copies of the car, built to `DEPTH + 1`.
fn chain_of(n: usize, continuity: Continuity) -> Vec<Stack> {
    let mut designs = vec![car()];
    for _ in 1..n {
        designs.push(next_copy(designs.last().unwrap()));
    }
    if continuity == Continuity::G2 {
        let refs: Vec<&Design> = designs.iter().collect();
        return g2_run(&refs, DEPTH + 1).unwrap();
    }
    let jn = Join {
        edge: Edge::End,
        continuity,
    };
    let (sa, sb) = join(&designs[0], &designs[1], jn, DEPTH + 1).unwrap();
    let mut stacks = vec![sa, sb];
    for k in 2..n {
        let s = chain(&designs[k - 1], &stacks[k - 1], &designs[k], continuity).unwrap();
        stacks.push(s);
    }
    stacks
}

/// The car and a patch leaving its first or last streamline outwards (G1),
/// over the middle 60 % of it (its rows along the car's `u`).
fn side_pair(on: Edge) -> Vec<Stack> {
    let a = car();
    let sa = Stack::build(&a, DEPTH + 1).unwrap();
    let edge = EdgeCurve::of(&sa, DEPTH + 1, on).unwrap();
    let (lo, hi) = (edge.start(), edge.length());
    let (lo, hi) = (lo + 0.2 * (hi - lo), hi - 0.2 * (hi - lo));
    let p = &sa.points[0];
    let mid = p.cols() / 2;
    let (r0, r1) = if on == Edge::First {
        (0, 1)
    } else {
        (p.rows() - 1, p.rows() - 2)
    };
    let out = (p.get(r0, mid) - p.get(r1, mid)).normalize();
    let (rows, cols) = (4, 4);
    let net = (0..rows * cols)
        .map(|i| {
            let (r, c) = (i / cols, i % cols);
            (out + DVec3::new(0.0, 0.0, -0.1 * c as f64) + DVec3::X * 0.05 * r as f64).normalize()
        })
        .collect();
    let step = 0.1 * (hi - lo);
    let s = Grid::new(
        rows,
        cols,
        (0..rows * cols).map(|i| step * (i % cols) as f64).collect(),
    )
    .unwrap();
    let t = (0..rows)
        .map(|r| lo + (hi - lo) * r as f64 / (rows - 1) as f64)
        .collect();
    let b = Design::new(
        &Grid::new(rows, cols, net).unwrap(),
        s,
        t,
        0,
        a.scheme(),
        a.order(),
        a.initial().clone(),
    )
    .unwrap();
    let jn = Join {
        edge: on,
        continuity: Continuity::G1,
    };
    let (sa, sb) = join(&a, &b, jn, DEPTH + 1).unwrap();
    vec![sa, sb]
}

fn grids(stacks: &[Stack]) -> Vec<PatchGrid> {
    stacks
        .iter()
        .enumerate()
        .map(|(i, s)| {
            // the car's scheme, Kobbelt's 4-point rule along the rows
            let curve = car().scheme().curve();
            PatchGrid::from_stack(&format!("patch {i}"), s, DEPTH, curve).unwrap()
        })
        .collect()
}

fn point_files(dir: &Path, tag: &str, patches: &[PatchGrid]) -> Vec<String> {
    patches
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let path = dir.join(format!("{tag}-{i}.xyz"));
            let text: String = p
                .data
                .points
                .data()
                .iter()
                .map(|q| format!("{:?} {:?} {:?}\n", q.x, q.y, q.z))
                .collect();
            std::fs::write(&path, text).unwrap();
            path.display().to_string()
        })
        .collect()
}

struct Case {
    tag: String,
    patches: Vec<PatchGrid>,
    seams: Vec<SeamSpec>,
    /// Free edges expected and whether the seams' normals must agree.
    free: usize,
    smooth: bool,
}

fn chain_case(n: usize, continuity: Continuity) -> Case {
    let patches = grids(&chain_of(n, continuity));
    let seams = (1..n)
        .map(|b| SeamSpec {
            a: b - 1,
            b,
            join: Join {
                edge: Edge::End,
                continuity,
            },
        })
        .collect();
    Case {
        tag: format!("chain{n}-{}", continuity.name()),
        patches,
        seams,
        free: 2 * n + 2,
        smooth: true,
    }
}

#[test]
fn opencascade_reads_one_shell_whose_seams_are_shared() {
    let dir = scratch("shared");
    let mut cases = vec![
        chain_case(2, Continuity::G1),
        chain_case(3, Continuity::G1),
        chain_case(2, Continuity::G2),
        chain_case(3, Continuity::G2),
    ];
    for on in [Edge::First, Edge::Last] {
        cases.push(Case {
            tag: format!("side-{}-G1", on.name()),
            patches: grids(&side_pair(on)),
            seams: vec![SeamSpec {
                a: 0,
                b: 1,
                join: Join {
                    edge: on,
                    continuity: Continuity::G1,
                },
            }],
            // A's edge split in three, one of them the seam: 5 + 3 (on
            // `Last`, B's face is written reversed: check_shell.py's normals
            // take each face's orientation, so a wrong one shows as ~180°)
            free: 8,
            smooth: true,
        });
    }
    let mut manifest = Vec::new();
    let mut fits = Vec::new();
    for c in &cases {
        let path = dir.join(format!("{}.step", c.tag));
        let shell = write_shell(&path, &c.tag, &c.patches, &c.seams, &FitOptions::DEFAULT)
            .unwrap_or_else(|e| panic!("{}: {e}", c.tag));
        manifest.push(serde_json::json!({
            "file": path.display().to_string(),
            "points": point_files(&dir, &c.tag, &c.patches),
            "tolerance": shell.faces.iter().map(|f| f.tolerance).fold(f64::INFINITY, f64::min),
            "samples": 40,
        }));
        fits.push(shell);
    }
    // the negative control: the chain of 2 (G1) fitted patch by patch
    let control = &cases[0];
    let alone = fit_alone(&control.patches, &FitOptions::DEFAULT).unwrap();
    let path = dir.join("control-alone.step");
    let info = StepInfo {
        name: "alone",
        file_name: "control-alone.step",
        uncertainty: 1e-7,
        timestamp: "",
    };
    std::fs::write(&path, faces_text(&alone, &[], None, &info)).unwrap();
    manifest.push(serde_json::json!({
        "file": path.display().to_string(),
        "points": point_files(&dir, "control", &control.patches),
        "tolerance": alone.iter().map(|f| f.tolerance).fold(f64::INFINITY, f64::min),
        "samples": 40,
    }));
    let results = common::opencascade_manifest("check_shell.py", &dir, &manifest);
    for ((c, shell), r) in cases.iter().zip(&fits).zip(&results) {
        eprintln!("{}: {r}", c.tag);
        let n = c.patches.len();
        assert_eq!(r["shells"], 1, "{}: {r}", c.tag);
        assert_eq!(r["faces"], n, "{}: {r}", c.tag);
        assert_eq!(r["valid"], true, "{}: {r}", c.tag);
        assert_eq!(r["free_edges"], c.free, "{}: {r}", c.tag);
        assert_eq!(r["shared_edges"], c.seams.len(), "{}: {r}", c.tag);
        for (f, d) in shell.faces.iter().zip(r["deviation"].as_array().unwrap()) {
            let d = d.as_f64().unwrap();
            assert!(
                d <= f.tolerance,
                "{}: a face is {d} from its points, over {}",
                c.tag,
                f.tolerance
            );
        }
        for s in r["seams"].as_array().unwrap() {
            let angle = s["max_angle_deg"].as_f64().unwrap();
            assert!(s["samples"].as_u64().unwrap() >= 32);
            // a side G1 seam's second column of poles is held in the earlier
            // face's tangent plane (docs/math.md §11.5); oriented consistently
            // (a wrong orientation reads about 180°)
            assert!(c.smooth);
            assert!(angle < 0.1, "{}: seam normals {angle}° apart", c.tag);
        }
    }
    let r = results.last().unwrap();
    eprintln!("control: {r}");
    assert_eq!(r["faces"], 2);
    assert_eq!(r["shared_edges"], 0, "fitted alone, a seam is shared? {r}");
    assert_eq!(
        r["free_edges"], 8,
        "fitted alone, both seam edges are free: {r}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
