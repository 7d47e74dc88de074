//! A joined patch's mesh made or updated from its `PatchSurface`
//! (docs/math.md §4, §11): whole from its points and the normals its build
//! kept ([`mesh_of`]), or only the rows a rejoin moved, written in place
//! ([`write_rows`]). Pure: [`super::patches`] calls them.

use crate::ecs::vertex_mirror::write_f32;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::Mesh;
use streamline_kernel::joins::rejoin::RowSpan;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;
use streamline_kernel::{DVec3, Grid};

/// A patch's mesh from its points and the normals its build kept
/// ([`PatchSurface::normals`](crate::ecs::joined::PatchSurface::normals), the whole mesh's, docs/math.md §4), reusing
/// the old mesh's triangles when the grid kept its shape; made whole
/// ([`SurfaceMesh::from_points`]) when the normals are missing.
pub(super) fn mesh_of(
    points: &streamline_kernel::Grid<streamline_kernel::DVec3>,
    normals: &[streamline_kernel::DVec3],
    old: Option<SurfaceMesh>,
    old_shape: Option<(usize, usize)>,
) -> SurfaceMesh {
    match old {
        Some(mut m)
            if normals.len() == points.data().len()
                && old_shape == Some((points.rows(), points.cols())) =>
        {
            m.positions.clear();
            m.positions.extend_from_slice(points.data());
            m.normals.clear();
            m.normals.extend_from_slice(normals);
            m
        }
        _ => SurfaceMesh::from_points(points),
    }
}

/// Writes rows `span` of `points` and `normals` (a rejoin's moved rows ± 1,
/// [`PatchSurface::rows`](crate::ecs::joined::PatchSurface::rows)) into the patch's Bevy mesh, its kernel mesh `m`
/// and its grid `g` in place, as the first patch's mesh takes a window
/// ([`super::shaded`]); `false`, writing nothing, when any of them has
/// another shape (then the mesh is made again).
pub(super) fn write_rows(
    mesh: &mut Mesh,
    m: &mut SurfaceMesh,
    g: &mut Grid<DVec3>,
    points: &Grid<DVec3>,
    normals: &[DVec3],
    span: RowSpan,
) -> bool {
    let (rows, cols) = (points.rows(), points.cols());
    let len = rows * cols;
    if span.hi >= rows
        || span.lo > span.hi
        || (g.rows(), g.cols()) != (rows, cols)
        || normals.len() != len
        || m.positions.len() != len
        || m.normals.len() != len
        || mesh.count_vertices() != len
        || !matches!(
            mesh.attribute(Mesh::ATTRIBUTE_NORMAL),
            Some(VertexAttributeValues::Float32x3(_))
        )
    {
        return false;
    }
    let range = span.lo * cols..(span.hi + 1) * cols;
    let data = &points.data()[range.clone()];
    if let Some(VertexAttributeValues::Float32x3(p)) = mesh.attribute_mut(Mesh::ATTRIBUTE_POSITION)
    {
        write_f32(&mut p[range.clone()], data);
    } else {
        return false;
    }
    if let Some(VertexAttributeValues::Float32x3(n)) = mesh.attribute_mut(Mesh::ATTRIBUTE_NORMAL) {
        write_f32(&mut n[range.clone()], &normals[range.clone()]);
    }
    m.positions[range.clone()].copy_from_slice(data);
    m.normals[range.clone()].copy_from_slice(&normals[range]);
    for r in span.lo..=span.hi {
        g.row_mut(r).copy_from_slice(points.row(r));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mesh remade from the kept normals equals the whole mesh of the
    /// points, bit for bit; a mesh of another shape, or without normals, is
    /// made whole (control: stale normals would show).
    #[test]
    fn a_mesh_from_kept_normals_is_the_whole_mesh() {
        use streamline_kernel::{DVec3, Grid};
        let grid = |k: f64, rows: usize, cols: usize| {
            let data = (0..rows * cols)
                .map(|i| {
                    let (r, c) = ((i / cols) as f64, (i % cols) as f64);
                    DVec3::new(c, r, (k * c).sin() * (0.3 * r).cos())
                })
                .collect();
            Grid::new(rows, cols, data).unwrap()
        };
        let bits = |m: &SurfaceMesh| {
            (m.positions.iter().chain(&m.normals))
                .flat_map(|v| v.to_array().map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        let (a, b) = (grid(0.4, 5, 7), grid(0.9, 5, 7));
        let whole = SurfaceMesh::from_points(&b);
        let old = SurfaceMesh::from_points(&a);
        let m = mesh_of(&b, &whole.normals, Some(old.clone()), Some((5, 7)));
        assert_eq!(bits(&m), bits(&whole));
        assert_eq!(m.indices, whole.indices);
        // stale normals are what the mesh shows (so they must be the build's)
        let stale = mesh_of(&b, &old.normals, Some(old.clone()), Some((5, 7)));
        assert_ne!(bits(&stale), bits(&whole));
        // another shape, or no normals: made whole
        let c = grid(0.9, 4, 7);
        let m = mesh_of(&c, &[], Some(old.clone()), Some((5, 7)));
        assert_eq!(bits(&m), bits(&SurfaceMesh::from_points(&c)));
        let m = mesh_of(
            &c,
            &SurfaceMesh::from_points(&c).normals,
            Some(old),
            Some((5, 7)),
        );
        assert_eq!(m.indices, SurfaceMesh::from_points(&c).indices);
    }
}
