//! Mesh export: Wavefront OBJ with normals (text) and binary STL. Both are
//! written atomically ([`super::io::write_atomic`]).

use super::error::SceneError;
use super::io::write_atomic;
use std::fmt::Write as _;
use std::path::Path;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;

/// The formats [`export`] writes, chosen by the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `.obj`
    Obj,
    /// `.stl` (binary)
    Stl,
}

impl Format {
    /// From a path's extension.
    pub fn of(path: &Path) -> Result<Self, SceneError> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("obj") => Ok(Format::Obj),
            Some("stl") => Ok(Format::Stl),
            _ => Err(SceneError::file(
                path,
                "unknown export format; name the file .obj or .stl",
            )),
        }
    }
}

/// OBJ text: `v`, `vn` and `f a//a b//b c//c` lines.
pub fn obj_text(mesh: &SurfaceMesh, name: &str) -> String {
    let mut s = String::with_capacity(mesh.positions.len() * 80 + mesh.indices.len() * 12);
    let _ = writeln!(s, "# Streamline Studio surface\no {}", sanitize(name));
    for p in &mesh.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for n in &mesh.normals {
        let _ = writeln!(s, "vn {} {} {}", n.x, n.y, n.z);
    }
    for t in mesh.indices.chunks_exact(3) {
        let (a, b, c) = (t[0] + 1, t[1] + 1, t[2] + 1);
        let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
    }
    s
}

fn sanitize(name: &str) -> String {
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

/// Writes `mesh` to `path` in the format its extension names.
pub fn export(mesh: &SurfaceMesh, name: &str, path: &Path) -> Result<Format, SceneError> {
    let format = Format::of(path)?;
    if mesh.positions.iter().any(|p| !p.is_finite()) {
        return Err(SceneError::file(
            path,
            "the mesh has a non-finite point; nothing was written",
        ));
    }
    let bytes = match format {
        Format::Obj => obj_text(mesh, name).into_bytes(),
        Format::Stl => stl_bytes(mesh),
    };
    write_atomic(path, &bytes, |_| Ok(()))?;
    Ok(format)
}
