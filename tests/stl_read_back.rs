//! Our STL files read back by an outside reader, OpenCascade's `RWStl`
//! (`tests/python/check_stl.py`, the test virtual environment of
//! `scripts/setup.sh --tests`): the one-surface export (binary, `f32`) and a
//! document's export (ASCII, one `solid` per patch, shortest round-trip
//! numbers) hold exactly our triangles, each with its corners in our order
//! (so the same facing), bit for bit: the binary file as `f32`, the ASCII
//! file as `f64` (OpenCascade parses the shortest round-trip decimals
//! exactly; the script hands the doubles over as their bits, since
//! `serde_json`'s default float parsing may be one unit in the last place
//! off).

mod common;

use std::path::Path;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;
use streamline_studio::scene::design::builtin;
use streamline_studio::scene::design::document_io::load;
use streamline_studio::scene::export::document::{DocumentExportSettings, export_document};
use streamline_studio::scene::export::format::{Format, write_meshes};
use streamline_studio::scene::export::glb::GlbPart;

/// A triangle's corners.
type Tri = [[f64; 3]; 3];

/// A triangle keyed by its corners' `f32` bits, rotated to start at the
/// smallest corner (the facing kept), with its corners as read or written.
type Keyed = ([[u32; 3]; 3], Tri);

fn keyed(mut t: Tri) -> Keyed {
    let key = |t: &Tri| t.map(|c| c.map(|x| (x as f32).to_bits()));
    let k = (0..3).min_by_key(|&i| key(&t)[i]).unwrap_or(0);
    t.rotate_left(k);
    (key(&t), t)
}

fn sorted(tris: impl IntoIterator<Item = Tri>) -> Vec<Keyed> {
    let mut out: Vec<Keyed> = tris.into_iter().map(keyed).collect();
    out.sort_unstable_by_key(|k| k.0);
    out
}

/// The triangles of `mesh`.
fn ours(mesh: &SurfaceMesh) -> impl Iterator<Item = Tri> + '_ {
    mesh.indices
        .chunks_exact(3)
        .map(|t| [0, 1, 2].map(|k| mesh.positions[t[k] as usize].to_array()))
}

/// What OpenCascade read from each file: its triangles.
fn read_back(files: &[&Path]) -> Vec<Vec<Keyed>> {
    let lines = common::opencascade_lines("check_stl.py", files);
    assert_eq!(lines.len(), files.len());
    lines
        .iter()
        .map(|v| {
            let nodes: Vec<[u64; 3]> = serde_json::from_value(v["nodes"].clone()).unwrap();
            let nodes: Vec<[f64; 3]> = nodes.iter().map(|n| n.map(f64::from_bits)).collect();
            let corners: Vec<[usize; 3]> = serde_json::from_value(v["corners"].clone()).unwrap();
            assert_eq!(v["triangles"].as_u64(), Some(corners.len() as u64));
            sorted(corners.iter().map(|c| c.map(|i| nodes[i])))
        })
        .collect()
}

/// The largest difference between paired corners, in units in the last
/// place of ours (`None` when the triangles do not pair up by key).
fn ulps_apart(read: &[Keyed], ours: &[Keyed]) -> Option<u64> {
    if read.len() != ours.len() || read.iter().zip(ours).any(|(a, b)| a.0 != b.0) {
        return None;
    }
    let ulps = |a: f64, b: f64| (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs();
    Some(
        read.iter()
            .zip(ours)
            .flat_map(|(a, b)| (0..9).map(move |i| ulps(a.1[i / 3][i % 3], b.1[i / 3][i % 3])))
            .max()
            .unwrap_or(0),
    )
}

#[test]
fn opencascade_reads_our_stl_files_triangle_for_triangle() {
    let dir = common::documents::tmpdir("stl");
    // one surface: the car at depth 3, binary STL
    let car = builtin::scene("car1").unwrap();
    let design = car.shown_design().unwrap();
    let level = design.levels(3).unwrap().pop().unwrap();
    let car_mesh = SurfaceMesh::from_points(&design.streamlines(&level));
    let car_stl = dir.join("car.stl");
    let part = GlbPart {
        name: &car.name,
        mesh: &car_mesh,
        colors: None,
    };
    write_meshes(&car_stl, Format::Stl, &[part]).unwrap();
    // a document of three patches (G2 and G1 joins): ASCII, a solid each
    let doc =
        load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron")).unwrap();
    let built = doc.build(doc.display_depth).unwrap();
    let doc_stl = dir.join("hood-screen-wing.stl");
    export_document(&doc, &built, &doc_stl, &DocumentExportSettings::default()).unwrap();
    let meshes: Vec<SurfaceMesh> = (built.patches.iter())
        .map(|s| SurfaceMesh::from_points(s.finest_points()))
        .collect();
    let doc_tris = sorted(meshes.iter().flat_map(ours));
    // the binary file holds f32: ours as f32
    let car_tris = sorted(ours(&car_mesh).map(|t| t.map(|c| c.map(|x| x as f32 as f64))));
    let read = read_back(&[&car_stl, &doc_stl]);
    assert_eq!(car_tris.len(), 2 * 40 * 65);
    assert_eq!(read[0].len(), car_tris.len());
    assert_eq!(
        ulps_apart(&read[0], &car_tris),
        Some(0),
        "the binary file is ours"
    );
    assert!(doc_tris.len() > 20_000, "{}", doc_tris.len());
    assert_eq!(
        read[1].len(),
        doc_tris.len(),
        "every patch's solid was read"
    );
    assert_eq!(
        ulps_apart(&read[1], &doc_tris),
        Some(0),
        "the ASCII file is ours"
    );
    // negative controls: a corner a hair off, a triangle turned over
    let mut off = car_tris.clone();
    off[7].1[1][2] = f64::from((off[7].1[1][2] as f32).next_up());
    assert_ne!(ulps_apart(&read[0], &off), Some(0));
    let mut turned = doc_tris.clone();
    let t = turned[11].1;
    turned[11] = keyed([t[0], t[2], t[1]]);
    turned.sort_unstable_by_key(|k| k.0);
    assert_eq!(ulps_apart(&read[1], &turned), None);
    let _ = std::fs::remove_dir_all(&dir);
}
