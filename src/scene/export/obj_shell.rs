//! Wavefront OBJ of a design (docs/cad.md, "Several patches"): one `o <patch
//! name>` object per patch (a design of one patch is one object), each
//! with its vertices row by row over the point grid (streamline by
//! streamline), then its normals (`vn`), then its triangles (`f a//a b//b
//! c//c`), whose indices count on from the patches before (OBJ's indices
//! are global to the file).

use std::fmt::Write as _;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;

/// The OBJ text of `patches` (name, mesh), one object each.
pub fn obj_meshes_text(patches: &[(&str, &SurfaceMesh)]) -> String {
    let mut s = String::from(match patches {
        [_] => "# Streamline Studio surface\n",
        _ => "# Streamline Studio surface: several patches\n",
    });
    let mut offset = 0usize;
    for (name, mesh) in patches {
        let _ = writeln!(s, "o {}", sanitize(name));
        for p in &mesh.positions {
            let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
        }
        for n in &mesh.normals {
            let _ = writeln!(s, "vn {} {} {}", n.x, n.y, n.z);
        }
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize + 1 + offset);
            let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
        }
        offset += mesh.positions.len();
    }
    s
}

/// `name` as an OBJ object or STL solid name: ASCII letters, digits, `-`
/// and `_`, anything else `_`; `surface` when empty.
pub(super) fn sanitize(name: &str) -> String {
    let n: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if n.is_empty() { "surface".into() } else { n }
}

/// A check of what was written: `objects` objects.
pub fn verify(bytes: &[u8], objects: usize) -> Result<(), String> {
    let text = std::str::from_utf8(bytes).map_err(|_| "not UTF-8".to_string())?;
    let found = text.lines().filter(|l| l.starts_with("o ")).count();
    if found != objects {
        return Err(format!("{found} objects, not {objects}"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use streamline_kernel::DVec3;
    use streamline_kernel::grid::Grid;

    #[test]
    fn each_patch_is_one_object_with_its_rows_and_global_indices() {
        let grid = |x0: f64| {
            let data = (0..6)
                .map(|i| DVec3::new(x0 + (i % 3) as f64, (i / 3) as f64, 0.0))
                .collect();
            Grid::new(2, 3, data).unwrap()
        };
        let (a, b) = (grid(0.0), grid(2.0));
        let (ma, mb) = (SurfaceMesh::from_points(&a), SurfaceMesh::from_points(&b));
        let text = obj_meshes_text(&[("hood", &ma), ("screen", &mb)]);
        // read by tobj (an outside reader), each object with its own indices
        let opts = tobj::LoadOptions {
            single_index: true,
            triangulate: true,
            ..Default::default()
        };
        let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &opts, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .expect("tobj reads the file");
        let names: Vec<&str> = models.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["hood", "screen"]);
        // in the file, the second object's vertices are its grid, row by row
        let v: Vec<&str> = text.lines().filter(|l| l.starts_with("v ")).collect();
        assert_eq!(v.len(), 12);
        assert_eq!((v[6], v[8], v[9]), ("v 2 0 0", "v 4 0 0", "v 2 1 0"));
        for (m, g) in models.iter().zip([&a, &b]) {
            // its grid's points, each once (tobj numbers them by first use)
            let key = |q: [f64; 3]| q.map(f64::to_bits);
            let mut read: Vec<_> = m
                .mesh
                .positions
                .chunks(3)
                .map(|q| key([q[0], q[1], q[2]]))
                .collect();
            let mut want: Vec<_> = g.data().iter().map(|q| key(q.to_array())).collect();
            read.sort_unstable();
            want.sort_unstable();
            assert_eq!(read, want, "{}", m.name);
            // two triangles per cell, every index inside the object
            assert_eq!(m.mesh.indices.len(), 3 * 2 * 2);
            assert!(m.mesh.indices.iter().all(|&i| (i as usize) < 6));
        }
    }
}
