//! The surface as a triangle mesh (docs/math.md §4): point `k` of row `j` is joined to
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
        normals_and_indices(points, &mut self.normals, &mut self.indices);
    }
}

/// The normals and triangles of a whole point grid, into buffers kept by the
/// caller (a mesh whose positions are `points` itself).
pub fn normals_and_indices(points: &Grid<DVec3>, normals: &mut Vec<DVec3>, indices: &mut Vec<u32>) {
    normals.clear();
    normals.resize(points.data().len(), DVec3::Z);
    normals_rows(
        points.data(),
        points.cols(),
        0,
        points.rows().saturating_sub(1),
        normals,
    );
    indices.clear();
    write_indices(points.rows(), points.cols(), indices);
}

/// The bounding box `[min, max]` of some points (`[+∞, −∞]` when there are none).
pub fn bounds(points: impl IntoIterator<Item = DVec3>) -> [DVec3; 2] {
    points.into_iter().fold(
        [DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)],
        |[lo, hi], p| [lo.min(p), hi.max(p)],
    )
}

const _: () = assert!(size_of::<DVec3>() == 3 * size_of::<f64>());

/// The `3n` coordinates (x, y, z of each in turn) of `n` points, borrowed.
pub fn coordinates(points: &[DVec3]) -> &[f64] {
    // SAFETY: glam's `DVec3` is `#[repr(C)]` with three `f64` fields and no
    // padding (checked above), so `n` of them are `3n` consecutive `f64`s,
    // borrowed as long as `points` is.
    unsafe { std::slice::from_raw_parts(points.as_ptr().cast::<f64>(), points.len() * 3) }
}

/// [`coordinates`], borrowed mutably.
pub fn coordinates_mut(points: &mut [DVec3]) -> &mut [f64] {
    // SAFETY: as in `coordinates`, for the mutable borrow of `points`.
    unsafe { std::slice::from_raw_parts_mut(points.as_mut_ptr().cast::<f64>(), points.len() * 3) }
}

/// [`bounds`] of a slice, the same box, in one pass that compiles to vector
/// compares: two points' six coordinates at a time (few enough to stay in
/// registers on every x86-64), each kept when it is
/// below (above) its running bound, so a NaN coordinate is passed over as
/// `f64::min` passes it (the integrate stage's row boxes, 4 % of a depth-6
/// drag's frame before).
pub fn slice_bounds(points: &[DVec3]) -> [DVec3; 2] {
    let flat = coordinates(points);
    let mut lo = [f64::INFINITY; 6];
    let mut hi = [f64::NEG_INFINITY; 6];
    let chunks = flat.chunks_exact(6);
    let rest = chunks.remainder();
    for c in chunks {
        for k in 0..6 {
            lo[k] = if c[k] < lo[k] { c[k] } else { lo[k] };
            hi[k] = if c[k] > hi[k] { c[k] } else { hi[k] };
        }
    }
    for (k, &v) in rest.iter().enumerate() {
        lo[k] = if v < lo[k] { v } else { lo[k] };
        hi[k] = if v > hi[k] { v } else { hi[k] };
    }
    let fold = |a: &[f64; 6], pick: fn(f64, f64) -> f64| {
        DVec3::new(pick(a[0], a[3]), pick(a[1], a[4]), pick(a[2], a[5]))
    };
    [fold(&lo, f64::min), fold(&hi, f64::max)]
}

/// Mesh updates of at least this many points run on two threads.
pub(crate) const PARALLEL_MIN_POINTS: usize = 16_384;

/// The normals of rows `lo ..= hi` of the row-major point grid `points`
/// (`cols` wide) into the same entries of `normals`; large ranges on two threads.
pub(crate) fn normals_rows(
    points: &[DVec3],
    cols: usize,
    lo: usize,
    hi: usize,
    normals: &mut [DVec3],
) {
    normals_window(points, cols, lo, hi, 0, normals);
}

/// `normals_rows` for columns `c0 ..` of those rows only (a streamline
/// summed again from a column on moves only its points after it).
pub fn normals_window(
    points: &[DVec3],
    cols: usize,
    lo: usize,
    hi: usize,
    c0: usize,
    normals: &mut [DVec3],
) {
    if cols == 0 || points.is_empty() || hi < lo || c0 >= cols {
        return;
    }
    let region = &mut normals[lo * cols..(hi + 1) * cols];
    let n = hi - lo + 1;
    if n * (cols - c0) < PARALLEL_MIN_POINTS || n < 2 {
        normals_rows_into(points, cols, lo, hi, c0, region);
        return;
    }
    let (top, bottom) = region.split_at_mut((n / 2) * cols);
    let mid = lo + n / 2;
    crate::parallel::join(
        || normals_rows_into(points, cols, lo, mid - 1, c0, top),
        || normals_rows_into(points, cols, mid, hi, c0, bottom),
    );
}

/// The normals of rows `lo ..= hi`, columns `c0 ..`, on this thread, into
/// `out`, which holds those rows only (`(hi − lo + 1) · cols` entries, as a
/// caller's scratch): the same numbers as [`normals_window`] writes there.
/// `out`'s columns before `c0` are kept; a degenerate point at `c0` takes
/// the normal at `c0 − 1`, so the caller puts that one there first.
pub fn normals_rows_into(
    points: &[DVec3],
    cols: usize,
    lo: usize,
    hi: usize,
    c0: usize,
    out: &mut [DVec3],
) {
    if cols == 0 || points.is_empty() || hi < lo || c0 >= cols {
        return;
    }
    crate::simd::normals_rows(points, cols, lo, hi, c0, out);
}

/// Triangle indices of a `rows × cols` point grid (appended to `out`).
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
