//! A regular grid of points as a reference (docs/math.md §12, docs/fit.md):
//! an OBJ of quadrilaterals forming one `rows × cols` grid is read, whatever
//! the order of its vertices, of its faces and of each face's corners, as
//! one B-spline surface through every point; anything that is not one grid
//! is read as a triangle mesh, which a fit refuses at the face's line.

use proptest::prelude::*;
use std::path::PathBuf;
use streamline_kernel::DVec3;
use streamline_kernel::fit::ReferenceSurface;
use streamline_reference::{SurfaceKind, read};

fn height(x: f64, y: f64) -> f64 {
    0.08 * (1.3 * x).sin() * (0.9 * y).cos() + 0.02 * x * y
}

/// The points of a `rows × cols` grid over `[0, 1.2] × [0, 0.8]`.
fn points(rows: usize, cols: usize) -> Vec<DVec3> {
    let mut v = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            let (x, y) = (
                1.2 * c as f64 / (cols - 1) as f64,
                0.8 * r as f64 / (rows - 1) as f64,
            );
            v.push(DVec3::new(x, y, height(x, y)));
        }
    }
    v
}

/// OBJ text of the grid: vertex `i` of `points` written at place `perm[i]`,
/// faces in the order `faces_order`, each face's corners turned by `turn`.
fn obj(rows: usize, cols: usize, perm: &[usize], faces_order: &[usize], turn: &[usize]) -> String {
    let pts = points(rows, cols);
    let mut placed = vec![DVec3::ZERO; pts.len()];
    for (i, p) in pts.iter().enumerate() {
        placed[perm[i]] = *p;
    }
    let mut s = String::from("# a grid of points\no grid\n");
    for p in &placed {
        s += &format!("v {:.17e} {:.17e} {:.17e}\n", p.x, p.y, p.z);
    }
    let cells: Vec<[usize; 4]> = (0..rows - 1)
        .flat_map(|r| {
            (0..cols - 1).map(move |c| {
                [
                    r * cols + c,
                    r * cols + c + 1,
                    (r + 1) * cols + c + 1,
                    (r + 1) * cols + c,
                ]
            })
        })
        .collect();
    for (k, &f) in faces_order.iter().enumerate() {
        let cell = cells[f];
        let t = turn.get(k).copied().unwrap_or(0) % 4;
        let idx: Vec<String> = (0..4)
            .map(|i| (perm[cell[(i + t) % 4]] + 1).to_string())
            .collect();
        s += &format!("f {}\n", idx.join(" "));
    }
    s
}

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join("streamline-reference-grid");
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The largest distance from the grid's points to the surface, each point
/// compared with the nearest of a dense sample refined by a few Newton steps.
fn through(surface: &dyn ReferenceSurface, pts: &[DVec3]) -> f64 {
    streamline_kernel::fit::distances_to_reference(surface, pts)
        .unwrap()
        .into_iter()
        .fold(0.0, f64::max)
}

#[test]
fn a_grid_reads_as_one_surface_through_its_points() {
    let (rows, cols) = (7, 9);
    let n = rows * cols;
    let ident: Vec<usize> = (0..n).collect();
    let order: Vec<usize> = (0..(rows - 1) * (cols - 1)).collect();
    let path = write("plain.obj", &obj(rows, cols, &ident, &order, &[]));
    let file = read(&path).unwrap();
    assert_eq!(file.faces.len(), 1);
    let info = &file.faces[0].info;
    assert_eq!(info.kind, SurfaceKind::Grid);
    assert_eq!(info.entity, "a grid of 7 × 9 points");
    assert!(!info.trimmed && info.closed == [false, false]);
    let s = file.surface(0).unwrap();
    let d = through(s, &points(rows, cols));
    let diag = DVec3::new(1.2, 0.8, 0.2).length();
    eprintln!("through the points within {d:.3e} (diagonal {diag:.3})");
    assert!(d <= 1e-6 * diag, "{d}");
    // the area of a gently curved 1.2 × 0.8 sheet is a little over 0.96
    assert!(info.area > 0.96 && info.area < 0.99, "{}", info.area);
    // negative control: another grid's points are not on it
    let other: Vec<DVec3> = points(rows, cols)
        .iter()
        .map(|p| *p + DVec3::Z * 0.01)
        .collect();
    assert!(through(s, &other) > 1e-3);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Any numbering of the vertices, any order of the faces, any first
    /// corner of each face: the same surface through the same points.
    #[test]
    fn any_order_of_vertices_and_faces_reads_the_same_grid(
        rows in 4usize..9,
        cols in 4usize..9,
        seed in any::<u64>(),
    ) {
        let n = rows * cols;
        let cells = (rows - 1) * (cols - 1);
        let mut rng = seed | 1;
        let mut next = || { rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17; rng };
        let mut perm: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() { let j = (next() % (i as u64 + 1)) as usize; perm.swap(i, j); }
        let mut order: Vec<usize> = (0..cells).collect();
        for i in (1..cells).rev() { let j = (next() % (i as u64 + 1)) as usize; order.swap(i, j); }
        let turn: Vec<usize> = (0..cells).map(|_| (next() % 4) as usize).collect();
        let path = write(&format!("shuffled-{seed}.obj"), &obj(rows, cols, &perm, &order, &turn));
        let file = read(&path).unwrap();
        let s = file.surface(0).unwrap();
        let g = &file.faces[0].info.entity;
        let a = format!("a grid of {rows} × {cols} points");
        let b = format!("a grid of {cols} × {rows} points");
        prop_assert!(g == &a || g == &b, "{g}");
        let d = through(s, &points(rows, cols));
        prop_assert!(d <= 1e-6 * 1.5, "{d}");
        let _ = std::fs::remove_file(&path);
    }
}

/// A grid whose points are finite but so large that its surface's area
/// overflows is refused at its line, never read with an infinite area (the
/// `reference_obj` fuzz target found one): at every scale from 1e140 to
/// 1e160 the file reads with a finite area or is refused with its name.
#[test]
fn a_grid_too_large_to_measure_is_refused() {
    let (rows, cols) = (4, 4);
    let n = rows * cols;
    let good = obj(
        rows,
        cols,
        &(0..n).collect::<Vec<_>>(),
        &(0..9).collect::<Vec<_>>(),
        &[],
    );
    let mut refused = Vec::new();
    for e in 140..=160 {
        let k = 10f64.powi(e);
        let scaled: String = good
            .lines()
            .map(|l| match l.strip_prefix("v ") {
                Some(xyz) => {
                    let v: Vec<f64> = xyz
                        .split(' ')
                        .map(|x| x.parse::<f64>().unwrap() * k)
                        .collect();
                    format!("v {:e} {:e} {:e}\n", v[0], v[1], v[2])
                }
                None => format!("{l}\n"),
            })
            .collect();
        match read(&write("huge.obj", &scaled)) {
            Ok(f) => assert!(
                f.faces[0].info.area.is_finite(),
                "1e{e}: area {}",
                f.faces[0].info.area
            ),
            Err(err) => {
                let msg = err.to_string();
                assert!(msg.contains("huge.obj:"), "{msg}");
                if msg.contains("too large to measure") {
                    refused.push(e);
                }
            }
        }
    }
    assert!(
        !refused.is_empty(),
        "some scale reaches the overflow this refuses"
    );
    // control: the same grid at its own size reads, with a finite area
    let f = read(&write("fine.obj", &good)).unwrap();
    assert!(f.faces[0].info.area.is_finite() && f.faces[0].info.area > 0.0);
}

#[test]
fn what_is_not_one_grid_is_refused_at_its_line() {
    // what is not one grid reads as a triangle mesh (for measuring, tests/mesh.rs),
    // which a fit refuses, saying why it is not a grid
    let not_grid = |name: &str, text: &str| -> String {
        let f = read(&write(name, text)).unwrap();
        assert_eq!(
            f.faces[0].info.kind,
            streamline_reference::SurfaceKind::Mesh
        );
        f.surface(0).unwrap_err().to_string()
    };
    let (rows, cols) = (5, 6);
    let n = rows * cols;
    let ident: Vec<usize> = (0..n).collect();
    let order: Vec<usize> = (0..(rows - 1) * (cols - 1)).collect();
    let good = obj(rows, cols, &ident, &order, &[]);
    // a triangle among the quads: refused at its own line
    let tri = good.replacen("f 1 2 8 7\n", "f 1 2 8\n", 1);
    let e = not_grid("triangle.obj", &tri);
    let line = tri.lines().position(|l| l == "f 1 2 8").unwrap() + 1;
    assert!(
        e.contains(&format!("triangle.obj:{line}:1: face 0 is a triangle mesh"))
            && e.contains("face 1 has 3 corners"),
        "{e}"
    );
    assert!(e.contains("; "), "{e}");
    // a missing face: a hole, not one grid
    let holed: String = good
        .lines()
        .filter(|l| *l != "f 9 10 16 15")
        .map(|l| format!("{l}\n"))
        .collect();
    let e = not_grid("holed.obj", &holed);
    assert!(e.contains("holed.obj") && e.contains("grid"), "{e}");
    // two grids side by side: eight corners
    let mut two = good.clone();
    for p in points(rows, cols) {
        two += &format!("v {} {} {}\n", p.x + 5.0, p.y, p.z);
    }
    for f in good.lines().filter(|l| l.starts_with("f ")) {
        let idx: Vec<String> = f[2..]
            .split(' ')
            .map(|i| (i.parse::<usize>().unwrap() + n).to_string())
            .collect();
        two += &format!("f {}\n", idx.join(" "));
    }
    let e = not_grid("two.obj", &two);
    assert!(e.contains("8 corners"), "{e}");
    // too few points to fit through
    let small = obj(
        3,
        6,
        &(0..18).collect::<Vec<_>>(),
        &(0..10).collect::<Vec<_>>(),
        &[],
    );
    let e = not_grid("small.obj", &small);
    assert!(e.contains("at least 4 × 4"), "{e}");
    // no faces at all
    let e = read(&write("points.obj", "v 0 0 0\nv 1 0 0\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no faces"), "{e}");
    // negative control: the good grid reads
    assert!(read(&write("good.obj", &good)).is_ok());
}
