//! What a face's description measures: the area and box of a B-spline
//! surface (evaluated, not from its poles), its corners, and the area of a
//! plane face's bounding polygon.

use streamline_kernel::DVec3;
use streamline_kernel::nurbs::rational::NurbsSurface;

/// An axis-aligned box `[min, max]`.
pub type Bbox = [[f64; 3]; 2];

/// The area `∫∫ |S_u × S_v| du dv` (m²) and the axis-aligned box (m) of the
/// surface, both from evaluated points, within the kernel's work budget
/// ([`NurbsSurface::area`], [`NurbsSurface::bounds`]).
pub fn area_and_bbox(s: &NurbsSurface) -> (f64, Bbox) {
    let [lo, hi] = s.bounds();
    (s.area(), [lo.to_array(), hi.to_array()])
}

/// The surface's four corners `S(u0, v0)`, `S(u1, v0)`, `S(u0, v1)`,
/// `S(u1, v1)`.
pub fn corners(s: &NurbsSurface) -> [DVec3; 4] {
    let ([u0, u1], [v0, v1]) = s.domain();
    [
        s.point(u0, v0),
        s.point(u1, v0),
        s.point(u0, v1),
        s.point(u1, v1),
    ]
}

/// How far a vertex may lie from a corner and still be on it: 1e-6 of the
/// box's diagonal (1e-12 m at least).
pub fn corner_tolerance(bbox: Bbox) -> f64 {
    let d = DVec3::from_array(bbox[1]) - DVec3::from_array(bbox[0]);
    let d = d.length();
    if d.is_finite() {
        (d * 1e-6).max(1e-12)
    } else {
        1e-12
    }
}

/// The area of a closed polygon in space (Newell's normal: half the length
/// of `Σ p_i × p_{i+1}`); exact for a planar polygon.
pub fn polygon_area(points: &[DVec3]) -> f64 {
    if points.len() < 3 {
        return 0.0;
    }
    let o = points[0];
    let mut n = DVec3::ZERO;
    for i in 0..points.len() {
        let a = points[i] - o;
        let b = points[(i + 1) % points.len()] - o;
        n += a.cross(b);
    }
    n.length() / 2.0
}

/// The axis-aligned box of some points, `None` when there are none.
pub fn points_bbox(points: impl IntoIterator<Item = DVec3>) -> Option<Bbox> {
    let mut it = points.into_iter();
    let first = it.next()?;
    let (mut lo, mut hi) = (first, first);
    for p in it {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    Some([lo.to_array(), hi.to_array()])
}
