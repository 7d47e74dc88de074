//! The real meshes of `tests/data/meshes` and mesh surgery shared by the Loop
//! tests (`loop_*.rs`, `osd_oracle.rs`).

use streamline_kernel::loop_subdiv::trimesh::{Topology, TriMesh};

/// The test meshes, small to large.
pub const MESHES: [&str; 8] = [
    "knight.obj",
    "snail.obj",
    "teddy.obj",
    "spot.obj",
    "fertility.obj",
    "fairing-cross.obj",
    "max-planck.obj",
    "camelhead.obj",
];

/// The folder of the test meshes.
pub fn meshes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/meshes")
}

/// A test mesh of `tests/data/meshes`, by the shared plain OBJ reader.
pub fn read_mesh(name: &str) -> (TriMesh, Topology) {
    super::read_obj(&meshes_dir().join(name))
}

/// The faces of `m` whose bit in `keep` is set, vertices renumbered (unused dropped).
pub fn sub_mesh(m: &TriMesh, keep: &[bool]) -> TriMesh {
    let mut index = vec![u32::MAX; m.positions.len()];
    let mut positions = Vec::new();
    let faces = m
        .faces
        .iter()
        .zip(keep)
        .filter(|(_, k)| **k)
        .map(|(f, _)| {
            f.map(|v| {
                if index[v as usize] == u32::MAX {
                    index[v as usize] = positions.len() as u32;
                    positions.push(m.positions[v as usize]);
                }
                index[v as usize]
            })
        })
        .collect();
    TriMesh { positions, faces }
}

/// The faces of `m` less holes: every face within `r` vertex-rings of each
/// seed face is dropped.
pub fn with_holes(m: &TriMesh, seeds: &[(usize, usize)]) -> TriMesh {
    let mut keep = vec![true; m.faces.len()];
    for &(seed, r) in seeds {
        let mut near = vec![false; m.positions.len()];
        for &v in &m.faces[seed % m.faces.len()] {
            near[v as usize] = true;
        }
        for _ in 0..r {
            let grow: Vec<[u32; 3]> = m
                .faces
                .iter()
                .filter(|f| f.iter().any(|&v| near[v as usize]))
                .copied()
                .collect();
            for f in grow {
                for v in f {
                    near[v as usize] = true;
                }
            }
        }
        for (k, f) in keep.iter_mut().zip(&m.faces) {
            if f.iter().all(|&v| near[v as usize]) {
                *k = false;
            }
        }
    }
    sub_mesh(m, &keep)
}
