//! STL of a design (docs/cad.md, "Several patches"): for several patches,
//! ASCII STL with one `solid <patch name>` per patch in one file
//! ([`stl_solids_text`]); for one, binary STL ([`stl_bytes`]: binary STL
//! has no solids and no names). Each facet's normal is its triangle's, its
//! corners as the mesh winds them.

use super::obj_shell::sanitize;
use std::fmt::Write as _;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;

/// The ASCII STL text of `patches` (name, mesh), one solid each.
pub fn stl_solids_text(patches: &[(&str, &SurfaceMesh)]) -> String {
    let mut s = String::new();
    for (name, mesh) in patches {
        let name = sanitize(name);
        let _ = writeln!(s, "solid {name}");
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|i| mesh.positions[t[i] as usize]);
            let n = (b - a).cross(c - a).try_normalize().unwrap_or_default();
            let _ = writeln!(s, "  facet normal {:e} {:e} {:e}", n.x, n.y, n.z);
            s.push_str("    outer loop\n");
            for v in [a, b, c] {
                let _ = writeln!(s, "      vertex {:e} {:e} {:e}", v.x, v.y, v.z);
            }
            s.push_str("    endloop\n  endfacet\n");
        }
        let _ = writeln!(s, "endsolid {name}");
    }
    s
}

/// Binary STL bytes: an 80-byte header, the triangle count, then per triangle
/// its face normal and three corners (little-endian `f32`) and a zero `u16`.
pub fn stl_bytes(mesh: &SurfaceMesh) -> Vec<u8> {
    let tris = mesh.indices.len() / 3;
    let mut out = Vec::with_capacity(84 + tris * 50);
    let mut header = [b' '; 80];
    let title = b"Streamline Studio binary STL";
    header[..title.len()].copy_from_slice(title);
    out.extend_from_slice(&header);
    out.extend_from_slice(&(tris as u32).to_le_bytes());
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|i| mesh.positions[t[i] as usize]);
        let n = (b - a).cross(c - a).try_normalize().unwrap_or_default();
        for v in [n, a, b, c] {
            for x in [v.x, v.y, v.z] {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// A check of what was written: `solids` solids, each closed, and every
/// facet with three vertices.
pub fn verify(bytes: &[u8], solids: usize) -> Result<(), String> {
    let text = std::str::from_utf8(bytes).map_err(|_| "not UTF-8".to_string())?;
    let (mut open, mut count, mut facets, mut vertices) = (false, 0, 0, 0);
    for line in text.lines().map(str::trim) {
        if line.starts_with("solid ") {
            if open {
                return Err("a solid inside a solid".into());
            }
            (open, count) = (true, count + 1);
        } else if line.starts_with("endsolid") {
            if !open {
                return Err("endsolid without solid".into());
            }
            open = false;
        } else if line.starts_with("facet normal") {
            facets += 1;
        } else if line.starts_with("vertex") {
            vertices += 1;
        }
    }
    if open || count != solids || vertices != 3 * facets {
        return Err(format!(
            "{count} solids (want {solids}), {facets} facets, {vertices} vertices"
        ));
    }
    Ok(())
}
