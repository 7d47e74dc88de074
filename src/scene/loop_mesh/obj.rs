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

use crate::scene::files::error::SceneError;
use crate::scene::files::io::write_atomic;
use crate::scene::job::Progress;
use std::fmt::Write as _;
use std::io::BufRead;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_kernel::limits::{MEMORY_CAP_BYTES, mesh_bytes};
use streamline_kernel::loop_subdiv::trimesh::{MeshError, Topology, TriMesh};

/// The largest OBJ file read (bytes).
pub const MAX_OBJ_BYTES: u64 = 2 << 30;

/// Lines between two looks at the progress (cancel, memory estimate).
const CHECK_EVERY: usize = 4096;

/// Reads, triangulates and validates an OBJ file.
pub fn read(path: &Path) -> Result<(TriMesh, Topology), SceneError> {
    read_with(path, &Progress::default())
}

/// [`read`], reporting bytes read to `progress` and stopping when it is
/// cancelled. The file is read line by line (never whole into memory) and
/// refused as soon as the mesh it describes would need more than the
/// memory cap ([`MEMORY_CAP_BYTES`]).
pub fn read_with(path: &Path, progress: &Progress) -> Result<(TriMesh, Topology), SceneError> {
    let len = crate::scene::files::io::file_size(
        path,
        MAX_OBJ_BYTES,
        "an .obj file",
        "simplify the mesh first",
    )?;
    let f = std::fs::File::open(path)
        .map_err(|e| SceneError::file(path, format!("cannot read: {e}; check the permissions")))?;
    progress.stage("reading", len);
    let mut reader = std::io::BufReader::with_capacity(1 << 20, f);
    let mut tagger = Tagger::new(path, progress);
    let mut line = Vec::new();
    let mut read = 0u64;
    loop {
        line.clear();
        let n = reader
            .read_until(b'\n', &mut line)
            .map_err(|e| SceneError::file(path, format!("cannot read: {e}; check the file")))?;
        if n == 0 {
            break;
        }
        read += n as u64;
        let text = match std::str::from_utf8(&line) {
            Ok(t) => t,
            Err(e) => {
                let col = String::from_utf8_lossy(&line[..e.valid_up_to()])
                    .chars()
                    .count();
                return Err(SceneError::at(
                    path,
                    tagger.line + 1,
                    col + 1,
                    "this byte is not UTF-8 text (OBJ files are text); save the file as UTF-8 or check it is the right file",
                ));
            }
        };
        tagger.line(text.trim_end_matches(['\n', '\r']))?;
        if tagger.line.is_multiple_of(CHECK_EVERY) {
            progress.set(read);
        }
    }
    progress.set(read);
    tagger.finish()
}

/// [`read`] on text already in memory (`path` names it in errors).
pub fn parse(text: &str, path: &Path) -> Result<(TriMesh, Topology), SceneError> {
    let progress = Progress::default();
    let mut tagger = Tagger::new(path, &progress);
    for line in text.lines() {
        tagger.line(line)?;
    }
    tagger.finish()
}

/// The first pass over the lines: checks `v` and `f` lines where they are
/// (so errors name the line and column), tags every vertex with its number,
/// counts what the mesh will need, and remembers the line of every vertex
/// and triangle for the errors found later.
struct Tagger<'a> {
    path: &'a Path,
    progress: &'a Progress,
    tagged: String,
    /// Lines seen.
    line: usize,
    vertex_lines: Vec<usize>,
    triangle_lines: Vec<usize>,
    /// Positive face indices, checked against the vertex count at the end:
    /// (line, column, index).
    forward: Vec<(usize, usize, u64)>,
}

impl<'a> Tagger<'a> {
    fn new(path: &'a Path, progress: &'a Progress) -> Self {
        Tagger {
            path,
            progress,
            tagged: String::new(),
            line: 0,
            vertex_lines: Vec::new(),
            triangle_lines: Vec::new(),
            forward: Vec::new(),
        }
    }

    fn at(&self, col: usize, msg: String) -> SceneError {
        SceneError::at(self.path, self.line, col, msg)
    }

    fn line(&mut self, line: &str) -> Result<(), SceneError> {
        self.line += 1;
        if self.line.is_multiple_of(CHECK_EVERY) {
            self.check_size()?;
        }
        let t = line.trim_start();
        let indent = line.len() - t.len();
        if let Some(rest) = t.strip_prefix("v ").or_else(|| t.strip_prefix("v\t")) {
            self.vertex(rest, indent)
        } else if let Some(rest) = t.strip_prefix("f ").or_else(|| t.strip_prefix("f\t")) {
            self.face(rest, indent)?;
            self.tagged.push_str(line);
            self.tagged.push('\n');
            Ok(())
        } else {
            self.tagged.push_str(line);
            self.tagged.push('\n');
            Ok(())
        }
    }

    fn vertex(&mut self, rest: &str, indent: usize) -> Result<(), SceneError> {
        let n = self.vertex_lines.len() + 1;
        let xyz: Vec<&str> = rest.split_whitespace().take(3).collect();
        let nums: Vec<Option<f64>> = xyz.iter().map(|s| s.parse::<f64>().ok()).collect();
        if xyz.len() < 3 || nums.iter().any(|x| x.is_none()) {
            return Err(self.at(
                indent + 1,
                format!(
                    "vertex {n} needs three numbers (`v x y z`), got `{}`; fix the line",
                    rest.trim()
                ),
            ));
        }
        if nums.iter().any(|x| !x.is_some_and(f64::is_finite)) {
            return Err(self.at(
                indent + 1,
                format!(
                    "vertex {n} has a NaN or infinite coordinate (`{}`); give finite coordinates",
                    rest.trim()
                ),
            ));
        }
        let _ = writeln!(
            self.tagged,
            "v {} {} {} {} 0 0",
            xyz[0],
            xyz[1],
            xyz[2],
            n - 1
        );
        self.vertex_lines.push(self.line);
        Ok(())
    }

    fn face(&mut self, rest: &str, indent: usize) -> Result<(), SceneError> {
        let mut corners = 0usize;
        let base = indent + 2;
        let mut from = 0;
        for word in rest.split_whitespace() {
            let off = rest[from..].find(word).map_or(from, |p| from + p);
            from = off + word.len();
            let col = base + rest[..off].chars().count() + 1;
            let idx = word.split('/').next().unwrap_or("");
            let known = self.vertex_lines.len() as i64;
            match idx.parse::<i64>() {
                Ok(0) => {
                    return Err(self.at(
                        col,
                        "vertex index 0 does not exist (OBJ counts vertices from 1); fix the face"
                            .into(),
                    ));
                }
                Ok(i) if i < 0 && known + i < 0 => {
                    return Err(self.at(
                        col,
                        format!(
                            "relative vertex index {i} reaches before the first vertex (only {known} vertices so far); fix the face"
                        ),
                    ));
                }
                Ok(i) if i > 0 => self.forward.push((self.line, col, i as u64)),
                Ok(_) => {}
                Err(_) => {
                    return Err(self.at(
                        col,
                        format!(
                            "`{word}` is not a vertex index (`f a b c`, or `a/t/n` with texture and normal indices); fix the face"
                        ),
                    ));
                }
            }
            corners += 1;
        }
        if corners < 3 {
            return Err(self.at(
                indent + 1,
                format!("a face needs at least three corners, this one has {corners}; fix or remove the line"),
            ));
        }
        for _ in 2..corners {
            self.triangle_lines.push(self.line);
        }
        Ok(())
    }

    /// Refuses the mesh as soon as it would need more than the memory cap;
    /// stops when cancelled.
    fn check_size(&self) -> Result<(), SceneError> {
        if self.progress.cancelled() {
            return Err(SceneError::file(self.path, "cancelled; nothing was opened"));
        }
        let need = mesh_bytes(self.vertex_lines.len(), self.triangle_lines.len());
        if need > MEMORY_CAP_BYTES {
            return Err(SceneError::at(
                self.path,
                self.line,
                1,
                format!(
                    "by this line the mesh has {} vertices and {} triangles, which would need about {:.1} MB, over the memory cap of {} MB; simplify the mesh (fewer triangles) first",
                    self.vertex_lines.len(),
                    self.triangle_lines.len(),
                    need as f64 / (1u64 << 20) as f64,
                    MEMORY_CAP_BYTES >> 20
                ),
            ));
        }
        Ok(())
    }

    fn finish(self) -> Result<(TriMesh, Topology), SceneError> {
        self.check_size()?;
        let count = self.vertex_lines.len();
        if let Some(&(line, col, i)) = self.forward.iter().find(|f| f.2 > count as u64) {
            return Err(SceneError::at(
                self.path,
                line,
                col,
                format!(
                    "vertex index {i} does not exist: the file has {count} vertices; fix the face"
                ),
            ));
        }
        self.progress.stage("triangulating", 0);
        let opts = tobj::LoadOptions {
            triangulate: true,
            single_index: false,
            ignore_points: true,
            ignore_lines: true,
        };
        let (models, _) = tobj::load_obj_buf(&mut self.tagged.as_bytes(), &opts, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(|e| {
            SceneError::file(
                self.path,
                format!("is not a readable OBJ file ({e}); check its `v` and `f` lines"),
            )
        })?;
        drop(self.tagged);
        let mut positions = vec![DVec3::ZERO; count];
        let mut faces = Vec::with_capacity(self.triangle_lines.len());
        for m in &models {
            let mesh = &m.mesh;
            let nv = mesh.positions.len() / 3;
            if mesh.vertex_color.len() != 3 * nv {
                return Err(SceneError::file(
                    self.path,
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
        if self.progress.cancelled() {
            return Err(SceneError::file(self.path, "cancelled; nothing was opened"));
        }
        self.progress.stage("checking the mesh", 0);
        let same_faces = faces.len() == self.triangle_lines.len();
        TriMesh::new(positions, faces.clone()).map_err(|e| {
            locate_mesh_error(
                self.path,
                &e,
                &self.vertex_lines,
                same_faces.then_some(&self.triangle_lines[..]),
                &faces,
            )
        })
    }
}

/// A mesh error at the line of the vertex or face it is about.
fn locate_mesh_error(
    path: &Path,
    e: &MeshError,
    vertex_lines: &[usize],
    triangle_lines: Option<&[usize]>,
    faces: &[[u32; 3]],
) -> SceneError {
    use MeshError::*;
    let vline = |v: usize| vertex_lines.get(v).copied();
    let fline = |f: usize| triangle_lines.and_then(|t| t.get(f).copied());
    let line = match e {
        IndexOutOfRange { face, .. } | DegenerateFace { face } => fline(*face),
        InconsistentWinding { face2, .. } => fline(*face2),
        NonManifoldEdge { a, b, .. } => faces
            .iter()
            .position(|f| f.contains(a) && f.contains(b))
            .and_then(fline),
        NonFiniteVertex { vertex }
        | VertexTooFar { vertex }
        | NonManifoldVertex { vertex }
        | UnreferencedVertex { vertex } => vline(*vertex),
        Empty | TooLarge { .. } => None,
        _ => None,
    };
    match line {
        Some(l) => SceneError::at(path, l, 1, e.to_string()),
        None => SceneError::file(path, e.to_string()),
    }
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
        assert_eq!(e, "u.obj:4:1: vertex 4 is used by no face; remove it");
        let e = parse("v 0 0\nf 1 2 3\n", Path::new("b.obj"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("b.obj:1:1: vertex 1 needs three numbers"),
            "{e}"
        );
    }
}
