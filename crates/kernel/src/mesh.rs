//! The surface as a triangle mesh (SPEC §4): point `k` of row `j` is joined to
//! point `k` of row `j+1`; each quad becomes two triangles wound so that their
//! normal is `∂/∂s × ∂/∂t`; vertex normals come from the grid's cross
//! derivatives (central differences, one-sided at the border).

use crate::grid::Grid;
use glam::DVec3;

/// A plain output buffer: positions, unit normals and triangle indices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceMesh {
    /// Vertex positions, row-major over the point grid.
    pub positions: Vec<DVec3>,
    /// Unit vertex normals (never NaN: a degenerate point takes its neighbour's).
    pub normals: Vec<DVec3>,
    /// Triangles, three indices each, counter-clockwise about the normal.
    pub indices: Vec<u32>,
}

impl SurfaceMesh {
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Meshes a grid of streamline points (`rows ≥ 1`, `cols ≥ 2`).
    pub fn from_points(points: &Grid<DVec3>) -> Self {
        let mut m = SurfaceMesh::default();
        m.rebuild(points);
        m
    }

    /// Rewrites this mesh from `points`, reusing its buffers.
    pub fn rebuild(&mut self, points: &Grid<DVec3>) {
        self.positions.clear();
        self.positions.extend_from_slice(points.data());
        self.normals.clear();
        self.normals.resize(points.data().len(), DVec3::Z);
        self.update_normals_rows(points, 0, points.rows().saturating_sub(1));
        self.indices.clear();
        write_indices(points.rows(), points.cols(), &mut self.indices);
    }

    /// Recomputes the normals of rows `lo ..= hi`; at least
    /// [`PARALLEL_MIN_POINTS`] of them are split over two threads (same
    /// operations per point, so the same bits).
    pub fn update_normals_rows(&mut self, points: &Grid<DVec3>, lo: usize, hi: usize) {
        let cols = points.cols();
        if cols == 0 || points.rows() == 0 || hi < lo {
            return;
        }
        let region = &mut self.normals[lo * cols..(hi + 1) * cols];
        let n = hi - lo + 1;
        if n * cols < PARALLEL_MIN_POINTS || n < 2 {
            for (i, out) in region.chunks_mut(cols).enumerate() {
                normals_row(points, lo + i, out);
            }
            return;
        }
        let (top, bottom) = region.split_at_mut((n / 2) * cols);
        crate::parallel::join(
            || {
                for (i, out) in top.chunks_mut(cols).enumerate() {
                    normals_row(points, lo + i, out);
                }
            },
            || {
                for (i, out) in bottom.chunks_mut(cols).enumerate() {
                    normals_row(points, lo + n / 2 + i, out);
                }
            },
        );
    }

    /// Recomputes the normals of row `r` (after its points, or a neighbour's, changed).
    pub fn update_normals_row(&mut self, points: &Grid<DVec3>, r: usize) {
        self.update_normals_rows(points, r, r);
    }
}

/// Mesh updates of at least this many points run on two threads.
pub const PARALLEL_MIN_POINTS: usize = 16_384;

/// The normals of row `r` of `points` into `out`.
fn normals_row(points: &Grid<DVec3>, r: usize, out: &mut [DVec3]) {
    let (rows, cols) = (points.rows(), points.cols());
    let (r0, r1) = (r.saturating_sub(1), (r + 1).min(rows - 1));
    let (above, here, below) = (points.row(r0), points.row(r), points.row(r1));
    let mut last = DVec3::Z;
    for c in 0..cols {
        let (c0, c1) = (c.saturating_sub(1), (c + 1).min(cols - 1));
        let ds = here[c1] - here[c0];
        let dt = below[c] - above[c];
        let n = ds.cross(dt);
        let len2 = n.length_squared();
        // a degenerate point takes its neighbour's normal (never NaN)
        let n = if len2 > 0.0 && len2.is_finite() {
            n * (1.0 / len2.sqrt())
        } else {
            last
        };
        last = n;
        out[c] = n;
    }
}

/// Triangle indices of a `rows × cols` point grid.
pub fn write_indices(rows: usize, cols: usize, out: &mut Vec<u32>) {
    out.reserve(rows.saturating_sub(1) * cols.saturating_sub(1) * 6);
    for r in 0..rows.saturating_sub(1) {
        for c in 0..cols.saturating_sub(1) {
            let a = (r * cols + c) as u32;
            let b = a + 1;
            let d = a + cols as u32;
            let e = d + 1;
            out.extend_from_slice(&[a, b, d, b, e, d]);
        }
    }
}
