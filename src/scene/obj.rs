//! Triangle meshes from and to OBJ files (paper 002's input and output).
//!
//! Reading goes through the tobj crate (`use_f64`), with its polygon
//! triangulation: a polygon of `k` corners becomes a fan of `k − 2`
//! triangles from its first corner. tobj renumbers vertices in order of first
//! use and drops unused ones; to keep the file's vertex order (the
//! interpolated control mesh is written with the same numbering) and to
//! report unused vertices, each `v` line is tagged with its number as a vertex
//! colour before tobj reads it, and the numbers are read back from the colours.
//! Then the kernel validates the mesh ([`TriMesh::new`]): every error names
//! the file, the element and the fix.

use super::error::SceneError;
use super::io::{read_text, write_atomic};
use std::fmt::Write as _;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_kernel::trimesh::{Topology, TriMesh};

/// The largest OBJ file read (bytes).
pub const MAX_OBJ_BYTES: u64 = 2 << 30;

/// Reads, triangulates and validates an OBJ file.
pub fn read(path: &Path) -> Result<(TriMesh, Topology), SceneError> {
    let text = read_text(path, MAX_OBJ_BYTES)?;
    parse(&text, path)
}

/// [`read`] on text already in memory (`path` names it in errors).
pub fn parse(text: &str, path: &Path) -> Result<(TriMesh, Topology), SceneError> {
    // tag every vertex with its number (as its colour), dropping `w` and colours
    let mut tagged = String::with_capacity(text.len() + text.len() / 4);
    let mut count = 0usize;
    for (line_no, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if let Some(rest) = t.strip_prefix("v ").or_else(|| t.strip_prefix("v\t")) {
            let xyz: Vec<&str> = rest.split_whitespace().take(3).collect();
            if xyz.len() < 3 || xyz.iter().any(|s| s.parse::<f64>().is_err()) {
                return Err(SceneError::at(
                    path,
                    line_no + 1,
                    line.len() - t.len() + 1,
                    format!(
                        "vertex {} needs three numbers (`v x y z`), got `{}`; fix the line",
                        count + 1,
                        rest.trim()
                    ),
                ));
            }
            let _ = writeln!(tagged, "v {} {} {} {} 0 0", xyz[0], xyz[1], xyz[2], count);
            count += 1;
        } else {
            tagged.push_str(line);
            tagged.push('\n');
        }
    }
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut tagged.as_bytes(), &opts, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| {
        SceneError::file(
            path,
            format!("is not a readable OBJ file ({e}); check its `v` and `f` lines"),
        )
    })?;
    let mut positions = vec![DVec3::ZERO; count];
    let mut faces = Vec::new();
    for m in &models {
        let mesh = &m.mesh;
        let nv = mesh.positions.len() / 3;
        if mesh.vertex_color.len() != 3 * nv {
            return Err(SceneError::file(
                path,
                "vertex numbering was lost while reading; write plain `v x y z` lines",
            ));
        }
        let original: Vec<u32> = (0..nv).map(|i| mesh.vertex_color[3 * i] as u32).collect();
        for (i, &o) in original.iter().enumerate() {
            positions[o as usize] = DVec3::new(
                mesh.positions[3 * i],
                mesh.positions[3 * i + 1],
                mesh.positions[3 * i + 2],
            );
        }
        for t in mesh.indices.chunks_exact(3) {
            faces.push([
                original[t[0] as usize],
                original[t[1] as usize],
                original[t[2] as usize],
            ]);
        }
    }
    TriMesh::new(positions, faces).map_err(|e| SceneError::file(path, e.to_string()))
}

/// Writes `positions` with `faces` as OBJ (full precision, 1-based), atomically.
pub fn write(
    path: &Path,
    positions: &[DVec3],
    faces: &[[u32; 3]],
    comment: &str,
) -> Result<(), SceneError> {
    let mut s = String::with_capacity(positions.len() * 64 + faces.len() * 24);
    for line in comment.lines() {
        let _ = writeln!(s, "# {line}");
    }
    for p in positions {
        let _ = writeln!(s, "v {:?} {:?} {:?}", p.x, p.y, p.z);
    }
    for f in faces {
        let _ = writeln!(s, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    write_atomic(path, s.as_bytes(), |_| Ok(()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obj_keeps_vertex_order_and_triangulates_quads() {
        let text = "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 5 3\n";
        let (m, t) = parse(text, Path::new("q.obj")).unwrap();
        assert_eq!(m.positions[4], DVec3::new(2.0, 0.0, 0.0), "file order kept");
        assert_eq!(m.faces.len(), 3, "the quad is a fan of two triangles");
        assert_eq!(t.loops.len(), 1);
        let e = parse(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n",
            Path::new("u.obj"),
        )
        .unwrap_err()
        .to_string();
        assert_eq!(e, "u.obj: vertex 4 is used by no face; remove it");
        let e = parse("v 0 0\nf 1 2 3\n", Path::new("b.obj"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("b.obj:1:1: vertex 1 needs three numbers"),
            "{e}"
        );
    }
}
