//! Documented size limits: work that would need more than the memory cap is
//! refused with a message before anything large is allocated, never by a
//! crash (see docs/reliability.md for the figures behind the estimates).

/// The memory one model (a streamline design, or a triangle mesh with its
/// interpolation and subdivision) may take: 2 GiB.
pub const MEMORY_CAP_BYTES: u64 = 2 << 30;

/// What one tangent of the finest level costs a streamline design, all
/// levels, parameters, streamline points, the mesh and its GPU copy
/// together (estimate; measured ≈ 230 B on the car, see docs/reliability.md).
pub const DESIGN_BYTES_PER_TANGENT: u64 = 400;

/// The most tangents one subdivision level may hold (docs/math.md §8): what the
/// memory cap affords at [`DESIGN_BYTES_PER_TANGENT`], rounded down to 4
/// million (96 MB of `DVec3` per copy of the finest level); beyond that the
/// editor could no longer stay interactive either.
pub const MAX_TANGENTS_PER_LEVEL: usize = 4_000_000;

const _: () = assert!(MAX_TANGENTS_PER_LEVEL as u64 * DESIGN_BYTES_PER_TANGENT <= MEMORY_CAP_BYTES);

/// The deepest subdivision any API accepts, whatever the size (a guard against
/// overflow in the size arithmetic itself).
pub const MAX_DEPTH: u32 = 16;

/// What one vertex of a triangle mesh costs while it is read (the tagged
/// text and tobj's arrays), validated (topology), interpolated (the solver's
/// vectors) and shown (estimate; see docs/reliability.md).
pub const MESH_BYTES_PER_VERTEX: u64 = 600;

/// What one triangle costs on top of its vertices (faces, text, topology).
pub const MESH_BYTES_PER_TRIANGLE: u64 = 120;

/// The memory a mesh of `vertices` and `triangles` needs, by the estimates above.
pub fn mesh_bytes(vertices: usize, triangles: usize) -> u64 {
    (vertices as u64)
        .saturating_mul(MESH_BYTES_PER_VERTEX)
        .saturating_add((triangles as u64).saturating_mul(MESH_BYTES_PER_TRIANGLE))
}

/// The largest magnitude of a coordinate, arc length or parameter accepted
/// (a billion model units). Beyond it sums of points overflow to infinity
/// (found by fuzzing); no design needs it.
pub const MAX_COORDINATE: f64 = 1e9;

/// Whether `x` is finite and within ±[`MAX_COORDINATE`].
pub(crate) fn in_range(x: f64) -> bool {
    x.is_finite() && x.abs() <= MAX_COORDINATE
}

/// The upper bound (exclusive) of ω for the 4-point rule: `2(√5 − 1)`, where the
/// planar scheme stops being C¹ (Dyn–Levin–Gregory, `w = ω/16 < (√5−1)/8`;
/// docs/math.md §2). Also `curve::scheme::OMEGA_MAX`.
pub const OMEGA_MAX: f64 = 2.472_135_954_999_579;

/// QI curves of order up to this are supported (the basis buffer's size;
/// docs/math.md §2). Also `curve::qi::MAX_ORDER`.
pub const MAX_QI_ORDER: usize = 8;
