//! The distance from points to a triangle mesh (`docs/math.md §12`, eq.
//! 12.8): a reference read as triangles (an OBJ or STL scan) has no
//! parameters to follow, so it is only displayed and measured.
//!
//! * [`TriangleMesh`]: vertex positions and triangles, checked (finite
//!   vertices, indices in range, at least one triangle);
//! * [`closest_on_triangle`]: the exact closest point of a triangle
//!   (Ericson, *Real-Time Collision Detection*, §5.1.5), degenerate
//!   triangles (segments or points) included;
//! * [`MeshIndex`]: a bounding-volume hierarchy over the triangles whose
//!   query returns the same closest distance as trying every triangle (a
//!   box is skipped only when it is strictly further than the best found);
//! * [`ReferenceIndex`]: a surface's [`ClosestPoints`] or a mesh's
//!   [`MeshIndex`] behind one `distances`, so callers measure either.

use super::closest::ClosestPoints;
use super::reference::ReferenceSurface;
use glam::DVec3;
use std::fmt;

/// A triangle mesh: positions and triangles as indices into them.
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleMesh {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

/// Why a [`TriangleMesh`] cannot be made.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshError {
    /// No triangle.
    Empty,
    /// A vertex with a NaN or infinite coordinate.
    NonFinite {
        /// Its index (0-based).
        vertex: usize,
    },
    /// A triangle naming a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle (0-based).
        triangle: usize,
        /// The index it names.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Empty => write!(f, "the mesh has no triangle"),
            MeshError::NonFinite { vertex } => write!(
                f,
                "vertex {} has a coordinate that is not a finite number",
                vertex + 1
            ),
            MeshError::IndexOutOfRange {
                triangle,
                index,
                vertices,
            } => write!(
                f,
                "triangle {} names vertex {}, but there are {vertices}",
                triangle + 1,
                *index as u64 + 1
            ),
        }
    }
}

impl std::error::Error for MeshError {}

impl TriangleMesh {
    /// A mesh of `triangles` over `positions`, refused when it has no
    /// triangle, a vertex that is not finite or an index past the end.
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        if triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite { vertex });
        }
        for (triangle, t) in triangles.iter().enumerate() {
            if let Some(&index) = t.iter().find(|&&i| i as usize >= positions.len()) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    vertices: positions.len(),
                });
            }
        }
        Ok(TriangleMesh {
            positions,
            triangles,
        })
    }

    /// The vertex positions.
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// The triangles, as indices into [`Self::positions`].
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The corners of triangle `k`.
    pub fn corners(&self, k: usize) -> [DVec3; 3] {
        let t = self.triangles[k];
        t.map(|i| self.positions[i as usize])
    }

    /// The sum of the triangles' areas.
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|k| {
                let [a, b, c] = self.corners(k);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// The axis-aligned box `[min, max]` of the vertices the triangles use.
    pub fn bbox(&self) -> [DVec3; 2] {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for t in &self.triangles {
            for &i in t {
                let p = self.positions[i as usize];
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        [lo, hi]
    }
}

/// The closest point to `p` on the segment `a b`.
fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let l2 = ab.length_squared();
    if l2 <= 0.0 {
        return a;
    }
    a + ab * ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
}

/// The closest point to `p` on the triangle `a b c` (Ericson, *Real-Time
/// Collision Detection*, §5.1.5): the projection of `p` on the triangle's
/// plane when it lies in the triangle (its three barycentric areas, signed
/// along the normal, not negative), else the closest point of the three
/// edges, since the closest point of a convex polygon is on its border when
/// the projection is outside. This form, rather than the Voronoi-region
/// tests, stays exact for slivers: a misjudged inside test errs by a
/// rounding of the position, not of the barycentric coordinates. A
/// degenerate triangle (zero normal) is the closest of its edges.
///
/// Every candidate is clamped to the triangle's bounding box: the exact
/// closest point lies in it, so the clamp only undoes rounding (an edge
/// point's `a + t (b - a)` past `b`, a sliver's projection through its
/// tilted normal landing beyond the sliver), and a box's distance is then
/// never more than the distance found for a triangle inside it, which the
/// hierarchy's pruning ([`MeshIndex::closest`]) relies on to agree with
/// the brute-force minimum exactly.
pub fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
    let inside = |q: DVec3| q.max(lo).min(hi);
    let mut best = inside(closest_on_segment(p, a, b));
    for q in [closest_on_segment(p, b, c), closest_on_segment(p, c, a)] {
        let q = inside(q);
        if (q - p).length_squared() < (best - p).length_squared() {
            best = q;
        }
    }
    // the projection, where it falls inside; kept only when nearer than the
    // border: on a sliver the computed normal's direction is off by a
    // rounding over its tiny length and the projection can land far away,
    // while the border is within the sliver's width of every point of it
    let n = (b - a).cross(c - a);
    let n2 = n.length_squared();
    if n2 > 0.0 && n2.is_finite() {
        let q = p - n * (n.dot(p - a) / n2);
        let (qa, qb, qc) = (a - q, b - q, c - q);
        if n.dot(qb.cross(qc)) >= 0.0 && n.dot(qc.cross(qa)) >= 0.0 && n.dot(qa.cross(qb)) >= 0.0 {
            let q = inside(q);
            if (q - p).length_squared() < (best - p).length_squared() {
                return q;
            }
        }
    }
    best
}

/// The distance from `p` to the triangle `a b c` ([`closest_on_triangle`]).
pub fn distance_to_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    (closest_on_triangle(p, a, b, c) - p).length()
}

/// Triangles per leaf of the hierarchy at most.
const LEAF: usize = 4;

/// A node of the hierarchy: its box and either two children or a range of
/// the ordered triangles.
#[derive(Debug, Clone)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: `(first, count)` into `order`; inner: `(left child, 0)`, the
    /// right child is `left + 1`.
    start: u32,
    count: u32,
}

/// The squared distance from `p` to the box `lo..hi` (0 inside).
fn box_distance2(p: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    let d = (lo - p).max(p - hi).max(DVec3::ZERO);
    d.length_squared()
}

/// A triangle mesh with a bounding-volume hierarchy over its triangles:
/// the closest point of the mesh to any point (eq. 12.8). Build once,
/// query often.
#[derive(Debug, Clone)]
pub struct MeshIndex {
    mesh: TriangleMesh,
    nodes: Vec<Node>,
    /// Triangle indices in leaf order.
    order: Vec<u32>,
}

impl MeshIndex {
    /// The hierarchy over `mesh`: boxes split at the median of the
    /// triangles' centres along their longest side, at most four
    /// triangles a leaf.
    pub fn new(mesh: TriangleMesh) -> Self {
        let n = mesh.triangles.len();
        let boxes: Vec<(DVec3, DVec3, DVec3)> = (0..n)
            .map(|k| {
                let [a, b, c] = mesh.corners(k);
                let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
                (lo, hi, (lo + hi) * 0.5)
            })
            .collect();
        let mut order: Vec<u32> = (0..n as u32).collect();
        let mut nodes = Vec::with_capacity(2 * n / LEAF + 1);
        nodes.push(Node {
            lo: DVec3::ZERO,
            hi: DVec3::ZERO,
            start: 0,
            count: 0,
        });
        // (node, first, end) still to build
        let mut todo = vec![(0usize, 0usize, n)];
        while let Some((node, first, end)) = todo.pop() {
            let items = &mut order[first..end];
            let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            let (mut clo, mut chi) = (lo, hi);
            for &k in items.iter() {
                let (l, h, c) = boxes[k as usize];
                lo = lo.min(l);
                hi = hi.max(h);
                clo = clo.min(c);
                chi = chi.max(c);
            }
            nodes[node].lo = lo;
            nodes[node].hi = hi;
            if items.len() <= LEAF {
                nodes[node].start = first as u32;
                nodes[node].count = items.len() as u32;
                continue;
            }
            let ext = chi - clo;
            let axis = if ext.x >= ext.y && ext.x >= ext.z {
                0
            } else if ext.y >= ext.z {
                1
            } else {
                2
            };
            let mid = items.len() / 2;
            items.select_nth_unstable_by(mid, |&i, &j| {
                boxes[i as usize].2[axis].total_cmp(&boxes[j as usize].2[axis])
            });
            let left = nodes.len();
            for _ in 0..2 {
                nodes.push(Node {
                    lo: DVec3::ZERO,
                    hi: DVec3::ZERO,
                    start: 0,
                    count: 0,
                });
            }
            nodes[node].start = left as u32;
            nodes[node].count = 0;
            todo.push((left, first, first + mid));
            todo.push((left + 1, first + mid, end));
        }
        MeshIndex { mesh, nodes, order }
    }

    /// The mesh.
    pub fn mesh(&self) -> &TriangleMesh {
        &self.mesh
    }

    /// The closest point of the mesh to `p`, its distance and its triangle
    /// (the first in the hierarchy's order among equally close ones). A
    /// non-finite `p` gives an infinite distance.
    pub fn closest(&self, p: DVec3) -> (f64, DVec3, usize) {
        if !p.is_finite() {
            return (f64::INFINITY, p, 0);
        }
        let mut best = (f64::INFINITY, p, 0usize);
        let mut stack: Vec<(f64, u32)> = Vec::with_capacity(64);
        stack.push((box_distance2(p, self.nodes[0].lo, self.nodes[0].hi), 0));
        while let Some((d2, node)) = stack.pop() {
            if d2 > best.0 {
                continue;
            }
            let n = &self.nodes[node as usize];
            if n.count > 0 {
                let range = n.start as usize..(n.start + n.count) as usize;
                for &k in &self.order[range] {
                    let [a, b, c] = self.mesh.corners(k as usize);
                    let q = closest_on_triangle(p, a, b, c);
                    let e2 = (q - p).length_squared();
                    if e2 < best.0 {
                        best = (e2, q, k as usize);
                    }
                }
                continue;
            }
            let (l, r) = (n.start, n.start + 1);
            let dl = box_distance2(p, self.nodes[l as usize].lo, self.nodes[l as usize].hi);
            let dr = box_distance2(p, self.nodes[r as usize].lo, self.nodes[r as usize].hi);
            // the nearer child is searched first (pushed last)
            if dl <= dr {
                stack.push((dr, r));
                stack.push((dl, l));
            } else {
                stack.push((dl, l));
                stack.push((dr, r));
            }
        }
        (best.0.sqrt(), best.1, best.2)
    }

    /// The distance from every point to the mesh (on two threads for large
    /// inputs, as [`ClosestPoints::distances`]).
    pub fn distances(&self, points: &[DVec3]) -> Vec<f64> {
        let mut out = vec![0.0; points.len()];
        let work = |pts: &[DVec3], out: &mut [f64]| {
            for (o, p) in out.iter_mut().zip(pts) {
                *o = self.closest(*p).0;
            }
        };
        if points.len() < 2048 {
            work(points, &mut out);
        } else {
            let h = points.len() / 2;
            let (pa, pb) = points.split_at(h);
            let (oa, ob) = out.split_at_mut(h);
            crate::parallel::join(|| work(pa, oa), || work(pb, ob));
        }
        out
    }

    /// The diagonal of the box of the mesh's vertices.
    pub fn diagonal(&self) -> f64 {
        let [lo, hi] = self.mesh.bbox();
        (hi - lo).length()
    }
}

/// The diagonal of the box of a 33 × 33 sample of `surface` (a reference's
/// size, as the deviation map's tolerance takes it).
pub fn sampled_diagonal(surface: &dyn ReferenceSurface) -> f64 {
    let ([u0, u1], [v0, v1]) = surface.domain();
    let n = 32;
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for i in 0..=n {
        for j in 0..=n {
            let u = u0 + (u1 - u0) * i as f64 / n as f64;
            let v = v0 + (v1 - v0) * j as f64 / n as f64;
            let p = surface.point(u, v);
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (hi - lo).length()
}

/// What a reference is measured with: a surface's closest points (eq.
/// 12.6) or a triangle mesh's (eq. 12.8).
pub enum ReferenceIndex {
    /// A B-spline surface.
    Surface(ClosestPoints<'static>),
    /// A triangle mesh.
    Mesh(MeshIndex),
}

impl ReferenceIndex {
    /// The distance from every point to the reference.
    pub fn distances(&self, points: &[DVec3]) -> Vec<f64> {
        match self {
            ReferenceIndex::Surface(c) => c.distances(points),
            ReferenceIndex::Mesh(m) => m.distances(points),
        }
    }

    /// The reference's size: the diagonal of the box of a 33 × 33 sample of
    /// the surface ([`sampled_diagonal`]), or of the mesh's vertices.
    pub fn diagonal(&self) -> f64 {
        match self {
            ReferenceIndex::Surface(c) => sampled_diagonal(c.reference()),
            ReferenceIndex::Mesh(m) => m.diagonal(),
        }
    }
}
