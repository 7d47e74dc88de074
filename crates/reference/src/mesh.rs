//! A triangle mesh as a reference (`docs/math.md §12`): an OBJ whose faces
//! are not one grid of quadrilaterals, or an STL file (binary or ASCII),
//! for display and measuring only: it has no parameters for the
//! streamlines to follow, so a design is measured against it (the closest
//! point of its triangles, the kernel's
//! [`MeshIndex`](streamline_kernel::fit::MeshIndex)) but not fitted to it.
//!
//! OBJ text is read by `tobj` (in [`crate::grid`], which decides between a
//! grid and a mesh); its polygons are split into triangles as fans from
//! their first corner. Binary STL is read by the `stl_io` crate, triangle
//! by triangle, so an error names the triangle's number and bytes; ASCII
//! STL by a short reader here (`read_ascii` says why), an error naming its
//! line. Neither format states a unit: lengths are metres. A vertex that is not finite, an index past the end, no triangle
//! at all or triangles that are all degenerate (no area) are refused with
//! the place and the fix.

use crate::error::{MAX_POINTS, MAX_TRIANGLES, ReferenceError};
use crate::{FaceData, SurfaceKind};
use std::collections::HashMap;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_kernel::fit::{MeshError, TriangleMesh};

/// How a mesh face is described: "a mesh of 12 triangles, 9 vertices".
fn entity(mesh: &TriangleMesh) -> String {
    let (t, v) = (mesh.triangles().len(), mesh.positions().len());
    format!(
        "a mesh of {t} triangle{}, {v} vertices",
        if t == 1 { "" } else { "s" }
    )
}

/// The face of a checked mesh: its area (the triangles' sum), its box and,
/// for an OBJ whose faces are not one grid, why not.
fn face(
    path: &Path,
    mesh: TriangleMesh,
    line: usize,
    not_grid: Option<(usize, String)>,
) -> Result<FaceData, ReferenceError> {
    let area = mesh.area();
    if area.is_nan() || area <= 0.0 || area.is_infinite() {
        return Err(ReferenceError::at(
            path,
            line,
            1,
            format!(
                "{} has no area (every triangle is degenerate, its corners on one line){}; export the surface itself, not its edges or points",
                entity(&mesh),
                if area.is_finite() {
                    ""
                } else {
                    " or an infinite one"
                }
            ),
        ));
    }
    let [lo, hi] = mesh.bbox();
    Ok(FaceData {
        kind: SurfaceKind::Mesh,
        entity: entity(&mesh),
        line,
        surface: None,
        mesh: Some(mesh),
        not_grid,
        closed: [false; 2],
        trimmed: false,
        area,
        bbox: Some([lo.to_array(), hi.to_array()]),
    })
}

/// The mesh of an OBJ's `positions` and `polygons` (vertex indices, 0-based,
/// each with its `f` line): polygons split into fans of triangles.
/// `not_grid` says why the faces are not one grid (the face's line, why).
pub(crate) fn from_obj(
    path: &Path,
    positions: Vec<DVec3>,
    polygons: &[(Vec<usize>, usize)],
    not_grid: Option<(usize, String)>,
) -> Result<FaceData, ReferenceError> {
    let first_line = polygons.first().map_or(1, |p| p.1);
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    for (k, (poly, line)) in polygons.iter().enumerate() {
        if let Some(&i) = poly.iter().find(|&&i| i >= positions.len()) {
            return Err(ReferenceError::at(
                path,
                *line,
                1,
                format!(
                    "face {} names vertex {}, but the file has {} vertices; fix the `f` line",
                    k + 1,
                    i + 1,
                    positions.len()
                ),
            ));
        }
        if poly.len() < 3 {
            continue;
        }
        if triangles.len() + poly.len() - 2 > MAX_TRIANGLES {
            return Err(too_many(path, *line));
        }
        for j in 1..poly.len() - 1 {
            triangles.push([poly[0], poly[j], poly[j + 1]].map(|i| i as u32));
        }
    }
    let mesh = TriangleMesh::new(positions, triangles).map_err(|e| match e {
        MeshError::Empty => ReferenceError::whole(
            path,
            "has no faces; a reference mesh is an OBJ of faces (`f a b c`) or an STL of triangles",
        ),
        e => ReferenceError::at(path, first_line, 1, format!("{e}; fix the file")),
    })?;
    face(path, mesh, first_line, not_grid)
}

/// The error for a mesh past [`MAX_TRIANGLES`] or [`MAX_POINTS`].
fn too_many(path: &Path, line: usize) -> ReferenceError {
    let msg = format!(
        "the mesh has more than {MAX_TRIANGLES} triangles or {MAX_POINTS} vertices, more than a reference is read with; decimate it"
    );
    if line > 0 {
        ReferenceError::at(path, line, 1, msg)
    } else {
        ReferenceError::whole(path, msg)
    }
}

/// Adds the triangle of `corners` to the mesh, corners with the same
/// coordinates as one vertex (0.0 and -0.0 alike); `false` when the mesh
/// is past the limits.
struct Builder {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    index: HashMap<[u64; 3], u32>,
}

impl Builder {
    fn new() -> Self {
        Builder {
            positions: Vec::new(),
            triangles: Vec::new(),
            index: HashMap::new(),
        }
    }

    fn vertex(&mut self, p: DVec3) -> Option<u32> {
        let key = (p + DVec3::ZERO).to_array().map(f64::to_bits);
        let n = self.positions.len() as u32;
        let i = *self.index.entry(key).or_insert(n);
        if i == n {
            if self.positions.len() >= MAX_POINTS {
                return None;
            }
            self.positions.push(p);
        }
        Some(i)
    }

    fn triangle(&mut self, corners: [DVec3; 3]) -> bool {
        if self.triangles.len() >= MAX_TRIANGLES {
            return false;
        }
        let mut t = [0u32; 3];
        for (c, p) in corners.into_iter().enumerate() {
            match self.vertex(p) {
                Some(i) => t[c] = i,
                None => return false,
            }
        }
        self.triangles.push(t);
        true
    }

    fn finish(self, path: &Path, line: usize) -> Result<FaceData, ReferenceError> {
        let mesh = TriangleMesh::new(self.positions, self.triangles).map_err(|e| match e {
            MeshError::Empty => ReferenceError::whole(
                path,
                "has no triangles; export the surface as an STL of its triangles",
            ),
            e => ReferenceError::whole(path, format!("{e}; export it again")),
        })?;
        face(path, mesh, line, None)
    }
}

/// Whether `bytes` is a binary STL: an 80-byte header, a triangle count
/// and exactly 50 bytes a triangle after it (also when the header starts
/// with `solid`, as some exporters write it).
fn binary_count(bytes: &[u8]) -> Option<usize> {
    let count = u32::from_le_bytes(bytes.get(80..84)?.try_into().ok()?) as usize;
    (bytes.len() as u64 == 84 + 50 * count as u64).then_some(count)
}

/// Reads an STL file, binary or ASCII.
pub(crate) fn read_stl(path: &Path, bytes: &[u8]) -> Result<FaceData, ReferenceError> {
    match binary_count(bytes) {
        Some(count) => read_binary(path, bytes, count),
        // text holds no zero byte; a binary file almost always does (a
        // coordinate 0.0, the attribute count), also one whose header
        // starts with `solid` and whose length is wrong
        None if bytes.trim_ascii_start().starts_with(b"solid") && !bytes.contains(&0) => {
            read_ascii(path, bytes)
        }
        None => {
            let why = if bytes.len() < 84 {
                format!(
                    "the file has {} bytes, fewer than the 84 of a binary STL's header and triangle count, and is not ASCII STL (text that starts with `solid`)",
                    bytes.len()
                )
            } else {
                let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
                format!(
                    "the header counts {count} triangles, which take {} bytes, but the file has {} (binary STL: an 80-byte header, the count and 50 bytes a triangle), and it is not ASCII STL (text that starts with `solid`)",
                    84 + 50 * count as u64,
                    bytes.len()
                )
            };
            Err(ReferenceError::whole(
                path,
                format!("{why}; the file is truncated or not STL: export it again"),
            ))
        }
    }
}

/// A binary STL of `count` triangles, read by `stl_io`; an error names the
/// triangle and its bytes.
fn read_binary(path: &Path, bytes: &[u8], count: usize) -> Result<FaceData, ReferenceError> {
    if count > MAX_TRIANGLES {
        return Err(too_many(path, 0));
    }
    let place = |k: usize| {
        format!(
            "triangle {} (bytes {} to {})",
            k + 1,
            84 + 50 * k,
            84 + 50 * k + 49
        )
    };
    // `stl_io` takes a header that starts with `solid` for ASCII: the
    // header is free text, so it is blanked for the reader
    let mut data = bytes.to_vec();
    data[..80].fill(b' ');
    let mut cursor = std::io::Cursor::new(data);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| {
        ReferenceError::whole(
            path,
            format!("is not a readable binary STL file ({e}); export it again"),
        )
    })?;
    let mut mesh = Builder::new();
    for (k, t) in reader.enumerate() {
        let t = t.map_err(|e| {
            ReferenceError::whole(
                path,
                format!(
                    "{} cannot be read ({e}); the file is truncated: export it again",
                    place(k)
                ),
            )
        })?;
        let corners = t
            .vertices
            .map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64));
        if let Some(c) = corners.iter().position(|p| !p.is_finite()) {
            return Err(ReferenceError::whole(
                path,
                format!(
                    "{}: corner {} has a coordinate that is not a finite number; the file is damaged: export it again",
                    place(k),
                    c + 1
                ),
            ));
        }
        if !mesh.triangle(corners) {
            return Err(too_many(path, 0));
        }
    }
    mesh.finish(path, 0)
}

/// An ASCII STL: `solid NAME`, facets of `facet normal x y z`, `outer
/// loop`, three `vertex x y z` (or more: a polygon split into a fan),
/// `endloop`, `endfacet`, and `endsolid`; several solids one after the
/// other are one mesh. Read here, not by `stl_io`, which reads the numbers
/// as `f32` and stops at the first `endsolid`: the coordinates are kept as
/// written (`f64`), and an error names its line.
fn read_ascii(path: &Path, bytes: &[u8]) -> Result<FaceData, ReferenceError> {
    let text = String::from_utf8_lossy(bytes);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.split_whitespace().collect::<Vec<&str>>()))
        .filter(|(_, t)| !t.is_empty());
    let last = text.lines().count().max(1);
    let fix = "the file is damaged or truncated: export it again";
    let mut mesh = Builder::new();
    let mut first_facet = 0usize;
    let mut in_solid = false;
    let mut corners: Vec<DVec3> = Vec::new();
    let expect = |line: Option<(usize, Vec<&str>)>, what: &str| -> Result<(), ReferenceError> {
        match line {
            Some((_, t)) if t.join(" ") == what => Ok(()),
            Some((n, t)) => Err(ReferenceError::at(
                path,
                n,
                1,
                format!("expected `{what}`, found `{}`; {fix}", t.join(" ")),
            )),
            None => Err(ReferenceError::at(
                path,
                last,
                1,
                format!("the file ends where `{what}` is expected; {fix}"),
            )),
        }
    };
    let number = |n: usize, t: &str| -> Result<f64, ReferenceError> {
        match t.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(ReferenceError::at(
                path,
                n,
                1,
                format!("`{t}` is not a finite number; {fix}"),
            )),
        }
    };
    while let Some((n, t)) = lines.next() {
        match (in_solid, t[0]) {
            (false, "solid") => in_solid = true,
            (true, "endsolid") => in_solid = false,
            (true, "facet") => {
                if first_facet == 0 {
                    first_facet = n;
                }
                expect(lines.next(), "outer loop")?;
                corners.clear();
                loop {
                    let Some((n, t)) = lines.next() else {
                        return Err(ReferenceError::at(
                            path,
                            last,
                            1,
                            format!("the file ends inside a facet; {fix}"),
                        ));
                    };
                    match t[0] {
                        "vertex" if t.len() == 4 => {
                            if corners.len() >= 1024 {
                                return Err(ReferenceError::at(
                                    path,
                                    n,
                                    1,
                                    format!("a facet with more than 1024 corners; {fix}"),
                                ));
                            }
                            corners.push(DVec3::new(
                                number(n, t[1])?,
                                number(n, t[2])?,
                                number(n, t[3])?,
                            ));
                        }
                        "endloop" if corners.len() >= 3 => break,
                        _ => {
                            return Err(ReferenceError::at(
                                path,
                                n,
                                1,
                                format!(
                                    "expected `vertex x y z`{}, found `{}`; {fix}",
                                    if corners.len() >= 3 {
                                        " or `endloop`"
                                    } else {
                                        ""
                                    },
                                    t.join(" ")
                                ),
                            ));
                        }
                    }
                }
                expect(lines.next(), "endfacet")?;
                for j in 1..corners.len() - 1 {
                    if !mesh.triangle([corners[0], corners[j], corners[j + 1]]) {
                        return Err(too_many(path, n));
                    }
                }
            }
            (true, _) => {
                return Err(ReferenceError::at(
                    path,
                    n,
                    1,
                    format!(
                        "expected `facet normal x y z` or `endsolid`, found `{}`; {fix}",
                        t.join(" ")
                    ),
                ));
            }
            (false, _) => {
                return Err(ReferenceError::at(
                    path,
                    n,
                    1,
                    format!("expected `solid NAME`, found `{}`; {fix}", t.join(" ")),
                ));
            }
        }
    }
    if in_solid {
        return Err(ReferenceError::at(
            path,
            last,
            1,
            format!("the file ends inside a solid, without its `endsolid`; {fix}"),
        ));
    }
    mesh.finish(path, first_facet.max(1))
}
