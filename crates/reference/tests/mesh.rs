//! Triangle meshes as references (docs/math.md §12, docs/fit.md "Triangle
//! meshes"): an OBJ whose faces are not one grid of quadrilaterals and an
//! STL file, binary or ASCII, read as triangles for display and measuring
//! only. The fixtures `tent.obj`, `tent-ascii.stl`, `tent-binary.stl` (its
//! header starts with `solid`, as some exporters write it) and `mixed.obj`
//! hold one mesh of 9 vertices and 8 triangles, written by
//! `tests/data/make_meshes.py` (`python3 make_meshes.py` in that folder);
//! its coordinates are exact in `f32`, so every file gives the same
//! triangles. Broken files are refused with the line (ASCII) or the
//! triangle (binary) and the fix, and random truncations and byte changes
//! never make the reader panic.

use proptest::prelude::*;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use streamline_reference::{Format, ReferenceFile, SurfaceKind, parse, read};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn write(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("streamline-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// The triangles of face 0 as corner coordinates, each rotated to start
/// at its smallest corner (the facing kept), as a set.
fn triangles(f: &ReferenceFile) -> BTreeSet<[[u64; 3]; 3]> {
    let m = f.mesh(0).unwrap().expect("a mesh");
    (0..m.triangles().len())
        .map(|k| {
            let c = m.corners(k).map(|p| p.to_array().map(f64::to_bits));
            let i = (0..3).min_by_key(|&i| c[i]).unwrap();
            [c[i], c[(i + 1) % 3], c[(i + 2) % 3]]
        })
        .collect()
}

/// The tent's area from Heron's formula, independent of the reader's cross
/// products.
fn heron(f: &ReferenceFile) -> f64 {
    let m = f.mesh(0).unwrap().unwrap();
    (0..m.triangles().len())
        .map(|k| {
            let [a, b, c] = m.corners(k);
            let (x, y, z) = (a.distance(b), b.distance(c), c.distance(a));
            let s = (x + y + z) / 2.0;
            (s * (s - x) * (s - y) * (s - z)).sqrt()
        })
        .sum()
}

#[test]
fn the_same_mesh_from_obj_and_stl_gives_the_same_triangles() {
    let obj = read(&data("tent.obj")).unwrap();
    let ascii = read(&data("tent-ascii.stl")).unwrap();
    let binary = read(&data("tent-binary.stl")).unwrap();
    let mixed = read(&data("mixed.obj")).unwrap();
    assert_eq!(obj.format, Format::Obj);
    assert_eq!(binary.format, Format::Stl);
    let want = triangles(&obj);
    assert_eq!(want.len(), 8);
    for f in [&ascii, &binary, &mixed] {
        assert_eq!(triangles(f), want, "{}", f.path.display());
        assert_eq!(f.faces.len(), 1);
        let i = &f.faces[0].info;
        assert_eq!(i.kind, SurfaceKind::Mesh);
        assert_eq!((i.triangles, i.vertices), (Some(8), Some(9)));
        assert_eq!(i.entity, "a mesh of 8 triangles, 9 vertices");
        assert_eq!(i.bbox, Some([[0.0, 0.0, 0.0], [1.0, 1.0, 0.75]]));
        assert!(
            (i.area - heron(f)).abs() <= 1e-15,
            "{} {}",
            i.area,
            heron(f)
        );
        assert_eq!(f.unit, "metre");
    }
    // the first `f` line and the first `facet`; a binary file has no line
    assert_eq!(obj.faces[0].info.line, 9 + 3);
    assert_eq!(ascii.faces[0].info.line, 2);
    assert_eq!(binary.faces[0].info.line, 0);
    // the area: four slopes, each two triangles
    assert!((obj.faces[0].info.area - heron(&obj)).abs() <= 1e-15);
    assert!(obj.faces[0].info.area > 1.0 && obj.faces[0].info.area < 1.5);
    // negative control: another mesh has other triangles
    let moved = std::fs::read_to_string(data("tent.obj"))
        .unwrap()
        .replace("v 0.5 0.5 0.75", "v 0.5 0.5 0.5");
    let other = read(&write("moved.obj", moved.as_bytes())).unwrap();
    assert_ne!(triangles(&other), want);
    // the JSON of a mesh's face: kind "mesh", its counts
    let json = serde_json::to_value(binary.infos()).unwrap();
    assert_eq!(json[0]["kind"], "mesh");
    assert_eq!(json[0]["triangles"], 8);
    assert_eq!(json[0]["vertices"], 9);
    // a surface's JSON has no counts
    let grid = serde_json::to_value(read(&data("bicubic.step")).unwrap().infos()).unwrap();
    assert!(grid[0].get("triangles").is_none(), "{grid}");
}

#[test]
fn a_mesh_is_not_a_surface_to_fit() {
    let stl = read(&data("tent-binary.stl")).unwrap();
    let e = stl.surface(0).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!(
            "{}: face 0 is a triangle mesh",
            data("tent-binary.stl").display()
        )),
        "{e}"
    );
    assert!(
        e.contains("for display and measuring only")
            && e.contains("; fit a STEP or IGES face or an OBJ quad grid"),
        "{e}"
    );
    let ascii = read(&data("tent-ascii.stl")).unwrap();
    let e = ascii.surface(0).unwrap_err().to_string();
    assert!(
        e.contains("tent-ascii.stl:2:1: face 0 is a triangle mesh"),
        "{e}"
    );
    // an OBJ says why its faces are not a grid, at the face's line
    let mixed = read(&data("mixed.obj")).unwrap();
    let e = mixed.surface(0).unwrap_err().to_string();
    assert!(
        e.contains("mixed.obj:13:1: face 0 is a triangle mesh")
            && e.contains("not one grid of quadrilaterals (face 3 has 3 corners)"),
        "{e}"
    );
    // quads that are a grid too small to fit through: a mesh, and why
    let mut small = String::new();
    for j in 0..3 {
        for i in 0..3 {
            small += &format!("v {i} {j} 0\n");
        }
    }
    for j in 0..2 {
        for i in 0..2 {
            let a = 3 * j + i + 1;
            small += &format!("f {} {} {} {}\n", a, a + 1, a + 4, a + 3);
        }
    }
    let f = read(&write("small.obj", small.as_bytes())).unwrap();
    assert_eq!(f.faces[0].info.kind, SurfaceKind::Mesh);
    assert_eq!(f.faces[0].info.triangles, Some(8));
    let e = f.surface(0).unwrap_err().to_string();
    assert!(e.contains("the grid has 3 × 3 points"), "{e}");
    // a face past the end
    let e = stl.mesh(1).unwrap_err().to_string();
    assert!(
        e.contains("there is no face 1: the file has 1 face (0)"),
        "{e}"
    );
    // negative control: a grid of quads stays a surface, and no mesh
    let grid = read(&data("../../../../scenes/references/scan.obj")).unwrap();
    assert_eq!(grid.faces[0].info.kind, SurfaceKind::Grid);
    assert!(grid.surface(0).is_ok() && grid.mesh(0).unwrap().is_none());
}

/// `(file name, contents, what the message holds)` for broken meshes.
fn broken() -> Vec<(&'static str, Vec<u8>, &'static str)> {
    let ascii = std::fs::read_to_string(data("tent-ascii.stl")).unwrap();
    let binary = std::fs::read(data("tent-binary.stl")).unwrap();
    let obj = std::fs::read_to_string(data("tent.obj")).unwrap();
    let mut nan_binary = binary.clone();
    // triangle 3's second corner, x
    let at = 84 + 50 * 2 + 24;
    nan_binary[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let mut flat = String::from("solid flat\n");
    for _ in 0..2 {
        flat += "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 1\nvertex 2 2 2\nendloop\nendfacet\n";
    }
    flat += "endsolid flat\n";
    vec![
        (
            "nan.stl",
            ascii
                .replacen("vertex 0.5 0.0 0.25", "vertex 0.5 nan 0.25", 1)
                .into_bytes(),
            "nan.stl:5:1: `nan` is not a finite number; ",
        ),
        (
            "truncated.stl",
            ascii.as_bytes()[..ascii.len() / 2].to_vec(),
            ":1: the file ends",
        ),
        (
            "no-endloop.stl",
            ascii.replacen("endloop", "endloops", 1).into_bytes(),
            "no-endloop.stl:7:1: expected `vertex x y z` or `endloop`, found `endloops`; ",
        ),
        (
            "truncated-binary.stl",
            binary[..binary.len() - 7].to_vec(),
            "the header counts 8 triangles, which take 484 bytes, but the file has 477",
        ),
        (
            "nan-binary.stl",
            nan_binary,
            "triangle 3 (bytes 184 to 233): corner 2 has a coordinate that is not a finite number; ",
        ),
        (
            "empty.stl",
            b"solid empty\nendsolid empty\n".to_vec(),
            "has no triangles; ",
        ),
        (
            "flat.stl",
            flat.into_bytes(),
            "flat.stl:2:1: a mesh of 2 triangles, 3 vertices has no area",
        ),
        ("tiny.stl", b"\x01\x02".to_vec(), "fewer than the 84"),
        (
            "past-end.obj",
            obj.replacen("f 1 2 5", "f 1 2 12", 1).into_bytes(),
            "past-end.obj:",
        ),
        (
            "nan.obj",
            obj.replacen("v 0.5 0.0 0.25", "v 0.5 nan 0.25", 1)
                .into_bytes(),
            "vertex 2 has a coordinate that is not a finite number; ",
        ),
    ]
}

#[test]
fn broken_meshes_are_refused_with_the_place_and_the_fix() {
    for (name, bytes, want) in broken() {
        let p = write(name, &bytes);
        let e = read(&p).expect_err(name).to_string();
        assert!(e.contains(want), "{name}: {e}");
        assert!(e.starts_with(&p.display().to_string()), "{name}: {e}");
        assert!(e.contains("; "), "{name}: says what to do: {e}");
    }
    // negative control: the untouched fixtures read
    for f in ["tent.obj", "tent-ascii.stl", "tent-binary.stl", "mixed.obj"] {
        assert!(read(&data(f)).is_ok(), "{f}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Truncations and byte changes of every mesh fixture are read or
    /// refused, never a panic; what reads is a mesh with finite corners.
    #[test]
    fn random_damage_never_panics(
        which in 0usize..4,
        cut in any::<prop::sample::Index>(),
        flips in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..6),
        truncate in any::<bool>(),
    ) {
        let (name, format) = [
            ("tent.obj", Format::Obj),
            ("tent-ascii.stl", Format::Stl),
            ("tent-binary.stl", Format::Stl),
            ("mixed.obj", Format::Obj),
        ][which];
        let mut bytes = std::fs::read(data(name)).unwrap();
        for (at, b) in &flips {
            let i = at.index(bytes.len());
            bytes[i] = *b;
        }
        if truncate {
            bytes.truncate(cut.index(bytes.len() + 1));
        }
        match parse(Path::new(name), format, bytes) {
            Ok(f) => {
                for face in &f.faces {
                    if let Some(m) = &face.mesh {
                        prop_assert!(m.positions().iter().all(|p| p.is_finite()));
                        prop_assert!(face.info.area > 0.0);
                    }
                }
            }
            Err(e) => prop_assert!(e.message.contains("; "), "{e}"),
        }
    }
}
