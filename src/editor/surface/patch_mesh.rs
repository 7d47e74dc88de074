//! A joined patch's Bevy mesh made or updated from its `PatchSurface`
//! (docs/math.md §4, §11): whole from its points and the normals its build
//! kept ([`normals_for`]), or only the rows a rejoin moved, written in place
//! ([`write_rows`]). The kernel-side mesh is not copied: its vertices are
//! the stack's finest points, its triangles a function of the grid's shape
//! ([`Triangles`]). Pure: [`super::patches`] calls them.

use crate::ecs::vertex_mirror::{stream_f32, streamed};
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::Mesh;
use std::borrow::Cow;
use streamline_kernel::joins::RowSpan;
use streamline_kernel::streamline::surface_mesh::{SurfaceMesh, write_indices};
use streamline_kernel::{DVec3, Grid};

/// A drawn patch's triangles and the grid shape they are for (docs/math.md
/// §4: a function of the shape alone).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Triangles {
    /// `(rows, cols)` of the point grid.
    pub shape: (usize, usize),
    /// Three indices a triangle, into the grid's row-major points.
    pub indices: Vec<u32>,
}

impl Triangles {
    /// The triangles of a `rows × cols` point grid, `old` kept when it is
    /// for that shape.
    pub fn of(rows: usize, cols: usize, old: Option<Triangles>) -> Triangles {
        match old {
            Some(t) if t.shape == (rows, cols) => t,
            _ => {
                let mut indices = Vec::new();
                write_indices(rows, cols, &mut indices);
                Triangles {
                    shape: (rows, cols),
                    indices,
                }
            }
        }
    }
}

/// The normals a patch's mesh is drawn with: those its build kept
/// ([`PatchSurface::normals`](crate::ecs::joined::PatchSurface::normals),
/// the whole mesh's, docs/math.md §4), or made whole
/// ([`SurfaceMesh::from_points`]) when they are missing.
pub(super) fn normals_for<'a>(points: &Grid<DVec3>, normals: &'a [DVec3]) -> Cow<'a, [DVec3]> {
    if normals.len() == points.data().len() {
        Cow::Borrowed(normals)
    } else {
        Cow::Owned(SurfaceMesh::from_points(points).normals)
    }
}

/// Writes rows `span` of `points` and `normals` (a rejoin's moved rows ± 1,
/// [`PatchSurface::rows`](crate::ecs::joined::PatchSurface::rows)) into the
/// patch's Bevy mesh in place, as the first patch's mesh takes a window
/// ([`super::shaded`]); `false`, writing nothing, when it has another shape
/// or the normals are missing (then the mesh is made again).
pub(super) fn write_rows(
    mesh: &mut Mesh,
    points: &Grid<DVec3>,
    normals: &[DVec3],
    span: RowSpan,
) -> bool {
    let (rows, cols) = (points.rows(), points.cols());
    let len = rows * cols;
    if span.hi >= rows
        || span.lo > span.hi
        || normals.len() != len
        || mesh.count_vertices() != len
        || !matches!(
            mesh.attribute(Mesh::ATTRIBUTE_NORMAL),
            Some(VertexAttributeValues::Float32x3(_))
        )
    {
        return false;
    }
    // streaming stores: the mesh's buffers were last read by the renderer a
    // frame ago, so a plain store would first read every line from memory
    let range = span.lo * cols..(span.hi + 1) * cols;
    if let Some(VertexAttributeValues::Float32x3(p)) = mesh.attribute_mut(Mesh::ATTRIBUTE_POSITION)
    {
        stream_f32(&mut p[range.clone()], &points.data()[range.clone()]);
    } else {
        return false;
    }
    if let Some(VertexAttributeValues::Float32x3(n)) = mesh.attribute_mut(Mesh::ATTRIBUTE_NORMAL) {
        stream_f32(&mut n[range.clone()], &normals[range]);
    }
    streamed();
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(k: f64, rows: usize, cols: usize) -> Grid<DVec3> {
        let data = (0..rows * cols)
            .map(|i| {
                let (r, c) = ((i / cols) as f64, (i % cols) as f64);
                DVec3::new(c, r, (k * c).sin() * (0.3 * r).cos())
            })
            .collect();
        Grid::new(rows, cols, data).unwrap()
    }

    fn f32s(v: &[DVec3]) -> Vec<[f32; 3]> {
        v.iter().map(|p| p.as_vec3().to_array()).collect()
    }

    fn attr(m: &Mesh, a: bevy::mesh::MeshVertexAttribute) -> Vec<[f32; 3]> {
        match m.attribute(a) {
            Some(VertexAttributeValues::Float32x3(v)) => v.clone(),
            _ => panic!("no attribute"),
        }
    }

    /// A Bevy mesh of positions and normals, as the editor makes one.
    fn mesh(points: &Grid<DVec3>, normals: &[DVec3], triangles: &[u32]) -> Mesh {
        use bevy::asset::RenderAssetUsages;
        use bevy::mesh::{Indices, PrimitiveTopology};
        Mesh::new(
            PrimitiveTopology::TriangleList,
            RenderAssetUsages::default(),
        )
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, f32s(points.data()))
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, f32s(normals))
        .with_inserted_indices(Indices::U32(triangles.to_vec()))
    }

    /// The kept normals are the whole mesh's when the build kept them
    /// (`SurfaceMesh::from_points`); without them they are made whole
    /// (control: stale normals would be drawn as they are); the triangles
    /// are kept for the same shape and made again for another, equal to the
    /// whole mesh's.
    #[test]
    fn a_mesh_from_kept_normals_is_the_whole_mesh() {
        let bits = |v: &[DVec3]| {
            v.iter()
                .map(|p| p.to_array().map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        let (a, b) = (grid(0.4, 5, 7), grid(0.9, 5, 7));
        let whole = SurfaceMesh::from_points(&b);
        let old = SurfaceMesh::from_points(&a);
        let t = Triangles::of(5, 7, None);
        assert_eq!(t.indices, whole.indices);
        let kept = normals_for(&b, &whole.normals);
        assert!(matches!(kept, Cow::Borrowed(_)), "not made again");
        assert_eq!(bits(&kept), bits(&whole.normals));
        // stale normals are what is drawn (so they must be the build's)
        assert_ne!(bits(&normals_for(&b, &old.normals)), bits(&whole.normals));
        // no normals: made whole
        assert_eq!(bits(&normals_for(&b, &[])), bits(&whole.normals));
        // triangles: kept for the shape, made again for another
        assert_eq!(Triangles::of(5, 7, Some(t.clone())), t);
        let c = grid(0.9, 4, 7);
        let other = Triangles::of(4, 7, Some(t));
        assert_eq!(other.shape, (4, 7));
        assert_eq!(other.indices, SurfaceMesh::from_points(&c).indices);
    }

    /// Rows written in place equal the whole mesh of the new points in
    /// those rows and leave the others as they were; a span past the grid,
    /// or missing normals, write nothing.
    #[test]
    fn rows_written_in_place_are_the_whole_mesh_s() {
        let (a, b) = (grid(0.4, 6, 5), grid(0.9, 6, 5));
        let (ma, mb) = (SurfaceMesh::from_points(&a), SurfaceMesh::from_points(&b));
        let t = Triangles::of(6, 5, None);
        let mut m = mesh(&a, &ma.normals, &t.indices);
        assert!(write_rows(
            &mut m,
            &b,
            &mb.normals,
            RowSpan { lo: 2, hi: 3 }
        ));
        let (p, n) = (
            attr(&m, Mesh::ATTRIBUTE_POSITION),
            attr(&m, Mesh::ATTRIBUTE_NORMAL),
        );
        for r in 0..6 {
            let (src, nrm) = if (2..=3).contains(&r) {
                (&mb, &mb)
            } else {
                (&ma, &ma)
            };
            let at = r * 5..(r + 1) * 5;
            assert_eq!(p[at.clone()], f32s(&src.positions[at.clone()]), "row {r}");
            assert_eq!(n[at.clone()], f32s(&nrm.normals[at]), "row {r}");
        }
        assert!(!write_rows(
            &mut m,
            &b,
            &mb.normals,
            RowSpan { lo: 5, hi: 6 }
        ));
        assert!(!write_rows(&mut m, &b, &[], RowSpan { lo: 0, hi: 1 }));
        assert_eq!(attr(&m, Mesh::ATTRIBUTE_POSITION), p, "nothing written");
    }
}
