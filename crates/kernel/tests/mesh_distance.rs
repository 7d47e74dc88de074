//! The distance from points to a triangle mesh (docs/math.md §12, eq. 12.8):
//! the hierarchy's answer is the brute-force minimum over every triangle,
//! on random meshes with degenerate and sliver triangles and points far
//! away, on vertices and on edges; the closest point of one triangle agrees
//! with Ericson's Voronoi-region form and no sample of the triangle is
//! closer; a flat tessellated square gives `|z|`; a fine tessellation of a
//! B-spline surface measures as the surface does within its chord error.
//! Each with a negative control.

use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::Grid;
use streamline_kernel::fit::mesh::{closest_on_triangle, distance_to_triangle};
use streamline_kernel::fit::{ClosestPoints, MeshError, MeshIndex, ReferenceIndex, TriangleMesh};
use streamline_kernel::nurbs::rational::NurbsSurface;

/// The smallest distance over every triangle.
fn brute(mesh: &TriangleMesh, p: DVec3) -> f64 {
    (0..mesh.triangles().len())
        .map(|k| {
            let [a, b, c] = mesh.corners(k);
            distance_to_triangle(p, a, b, c)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Ericson's closest point on a triangle, the Voronoi-region form
/// (*Real-Time Collision Detection*, §5.1.5), written out independently.
fn ericson(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// A small deterministic generator (the proptest seed picks the start).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn point(&mut self, s: f64) -> DVec3 {
        DVec3::new(
            s * (2.0 * self.next() - 1.0),
            s * (2.0 * self.next() - 1.0),
            s * (2.0 * self.next() - 1.0),
        )
    }
    fn index(&mut self, n: usize) -> u32 {
        ((self.next() * n as f64) as usize).min(n - 1) as u32
    }
}

/// A random mesh with nasty triangles: repeated corners (a segment or a
/// point), a corner on another's edge (zero area), slivers (a corner 1e-9
/// off an edge), and ordinary ones.
fn nasty_mesh(rng: &mut Rng, vertices: usize, triangles: usize) -> TriangleMesh {
    let mut pos: Vec<DVec3> = (0..vertices).map(|_| rng.point(1.0)).collect();
    let mut tris = Vec::new();
    for k in 0..triangles {
        let (a, b) = (rng.index(pos.len()), rng.index(pos.len()));
        let c = match k % 5 {
            0 => a, // a segment (or a point when a == b)
            1 => {
                let (pa, pb) = (pos[a as usize], pos[b as usize]);
                pos.push(pa + (pb - pa) * rng.next());
                (pos.len() - 1) as u32
            }
            2 => {
                let (pa, pb) = (pos[a as usize], pos[b as usize]);
                pos.push(pa + (pb - pa) * rng.next() + rng.point(1e-9));
                (pos.len() - 1) as u32
            }
            _ => rng.index(pos.len()),
        };
        tris.push([a, b, c]);
    }
    TriangleMesh::new(pos, tris).unwrap()
}

/// Query points: random near the mesh and far from it, on vertices, on
/// edges (midpoints and random points) and inside triangles.
fn queries(rng: &mut Rng, mesh: &TriangleMesh, n: usize) -> Vec<DVec3> {
    let mut q = Vec::new();
    let t = mesh.triangles().len();
    for i in 0..n {
        let [a, b, c] = mesh.corners(rng.index(t) as usize);
        q.push(match i % 7 {
            0 => rng.point(1.5),
            1 => rng.point(1e3),
            2 => a,
            3 => (a + b) * 0.5,
            4 => b + (c - b) * rng.next(),
            5 => {
                let (s, u) = (rng.next(), rng.next());
                let (s, u) = if s + u > 1.0 {
                    (1.0 - s, 1.0 - u)
                } else {
                    (s, u)
                };
                a + (b - a) * s + (c - a) * u + rng.point(0.01)
            }
            _ => rng.point(0.3) + a,
        });
    }
    q
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The hierarchy finds the brute-force closest distance, to 1e-12
    /// (it is the same minimum: a box is skipped only when strictly
    /// further). Negative control: without the triangle a query lies on,
    /// the distance of that query is not 0.
    #[test]
    fn the_index_finds_the_brute_force_minimum(seed in any::<u64>(), v in 3usize..40, t in 1usize..160) {
        let mut rng = Rng(seed);
        let mesh = nasty_mesh(&mut rng, v, t);
        let index = MeshIndex::new(mesh.clone());
        let pts = queries(&mut rng, &mesh, 300);
        let got = index.distances(&pts);
        for (p, g) in pts.iter().zip(&got) {
            let want = brute(&mesh, *p);
            prop_assert!((g - want).abs() <= 1e-12, "{p}: {g} vs {want}");
            let (d, q, k) = index.closest(*p);
            prop_assert_eq!(d, *g);
            let [a, b, c] = mesh.corners(k);
            prop_assert!((distance_to_triangle(*p, a, b, c) - d).abs() <= 1e-12);
            prop_assert!(((q - *p).length() - d).abs() <= 1e-12);
        }
        // negative control: a vertex of the last ordinary triangle, with
        // every triangle using that vertex dropped, is not on the mesh
        let keep: Vec<[u32; 3]> = mesh.triangles().iter().copied().filter(|tri| !tri.contains(&0)).collect();
        let used = mesh.triangles().iter().any(|tri| tri.contains(&0));
        if used && !keep.is_empty() {
            let p0 = mesh.positions()[0];
            let others = TriangleMesh::new(mesh.positions().to_vec(), keep).unwrap();
            let d_without = MeshIndex::new(others.clone()).closest(p0).0;
            prop_assert_eq!(index.closest(p0).0, 0.0);
            prop_assert!((d_without - brute(&others, p0)).abs() <= 1e-12);
            // vertex 0 is random, so it lies on no other triangle
            prop_assert!(d_without > 0.0 || others.positions().iter().skip(1).any(|p| *p == p0));
        }
    }

    /// One triangle: the closest point is Ericson's (Voronoi regions) on
    /// well-shaped triangles, to 1e-12; on slivers and degenerate ones no
    /// sample of the triangle is closer.
    #[test]
    fn the_closest_point_of_a_triangle_is_exact(seed in any::<u64>()) {
        let mut rng = Rng(seed);
        for _ in 0..50 {
            let (a, b, c) = (rng.point(1.0), rng.point(1.0), rng.point(1.0));
            let p = rng.point(2.0);
            let n = (b - a).cross(c - a).length();
            let longest = (b - a).length().max((c - a).length()).max((c - b).length());
            if n > 0.05 * longest * longest {
                let mine = closest_on_triangle(p, a, b, c);
                let his = ericson(p, a, b, c);
                prop_assert!((mine - his).length() <= 1e-12, "{mine} vs {his}");
            }
            // a sliver: c 1e-10 off the edge a b, and a segment
            for (a, b, c) in [
                (a, b, a + (b - a) * 0.37 + (c - a) * 1e-10),
                (a, b, a + (b - a) * 0.37),
                (a, a, b),
                (a, a, a),
            ] {
                let d = distance_to_triangle(p, a, b, c);
                let mut best = f64::INFINITY;
                for i in 0..=40 {
                    for j in 0..=40 - i {
                        let s = a + (b - a) * (i as f64 / 40.0) + (c - a) * (j as f64 / 40.0);
                        best = best.min((s - p).length());
                    }
                }
                prop_assert!(d <= best + 1e-12, "{d} > {best}");
                // and it is no further than the sample spacing from the best sample
                prop_assert!(d >= best - 0.05 * longest, "{d} vs {best}");
            }
        }
    }
}

/// A square `[0, 1]²` in `z = 0`, `n × n` cells each split in two.
fn flat_square(n: usize) -> TriangleMesh {
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            pos.push(DVec3::new(i as f64 / n as f64, j as f64 / n as f64, 0.0));
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    TriangleMesh::new(pos, tris).unwrap()
}

#[test]
fn a_flat_square_is_at_the_height_above_it() {
    let index = MeshIndex::new(flat_square(17));
    let area = index.mesh().area();
    assert!((area - 1.0).abs() <= 1e-13, "{area}");
    assert!((index.diagonal() - 2f64.sqrt()).abs() <= 1e-15);
    let mut rng = Rng(7);
    let mut worst = 0.0f64;
    for _ in 0..5000 {
        let p = DVec3::new(rng.next(), rng.next(), 4.0 * rng.next() - 2.0);
        let d = index.closest(p).0;
        worst = worst.max((d - p.z.abs()).abs());
    }
    assert!(worst <= 1e-15, "{worst}");
    // negative control: beside the square the distance is more than |z|
    let p = DVec3::new(1.5, 0.5, 0.2);
    let d = index.closest(p).0;
    assert!(
        (d - (0.25f64 + 0.04).sqrt()).abs() <= 1e-15 && d > 0.2 + 0.3,
        "{d}"
    );
    // a point that is not finite is infinitely far
    assert_eq!(
        index.closest(DVec3::new(f64::NAN, 0.0, 0.0)).0,
        f64::INFINITY
    );
}

/// A wavy bicubic face with interior knots.
fn wavy() -> NurbsSurface {
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let (nu, nv) = (ku.len() - 4, kv.len() - 4);
    let mut poles = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (x, y) = (i as f64 / (nu - 1) as f64, j as f64 / (nv - 1) as f64);
            let z = 0.2 * ((3.0 * x + 0.4).sin() * (2.0 * y - 0.4).cos());
            poles.push(DVec3::new(2.0 * x + 0.1 * y * y, 1.5 * y, z));
        }
    }
    NurbsSurface::new(3, 3, ku, kv, Grid::new(nv, nu, poles).unwrap(), None).unwrap()
}

/// The surface sampled on an `n × n` grid of parameters, each cell split in
/// two, and its chord error: the largest distance between the surface and
/// the triangles at the same parameters (6 × 6 points a cell).
fn tessellate(s: &NurbsSurface, n: usize) -> (TriangleMesh, f64) {
    let ([u0, u1], [v0, v1]) = s.domain();
    let uv = |i: f64, j: f64| (u0 + (u1 - u0) * i / n as f64, v0 + (v1 - v0) * j / n as f64);
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = uv(i as f64, j as f64);
            pos.push(s.point(u, v));
        }
    }
    let at = |i: usize, j: usize| j * (n + 1) + i;
    let mut tris = Vec::new();
    let mut chord = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            tris.push([a, b, c].map(|k| k as u32));
            tris.push([a, c, d].map(|k| k as u32));
            for si in 0..=5 {
                for sj in 0..=5 {
                    let (x, y) = (si as f64 / 5.0, sj as f64 / 5.0);
                    // the triangle a b c holds x ≥ y, a c d the rest
                    let flat = if x >= y {
                        pos[a] + (pos[b] - pos[a]) * (x - y) + (pos[c] - pos[a]) * y
                    } else {
                        pos[a] + (pos[c] - pos[a]) * x + (pos[d] - pos[a]) * (y - x)
                    };
                    let (u, v) = uv(i as f64 + x, j as f64 + y);
                    chord = chord.max((s.point(u, v) - flat).length());
                }
            }
        }
    }
    (TriangleMesh::new(pos, tris).unwrap(), chord)
}

/// A fine tessellation measures like the surface, within its chord error;
/// negative control: a coarse one does not, within the fine one's.
#[test]
fn a_tessellated_surface_measures_like_the_surface() {
    let s = wavy();
    let surface = ClosestPoints::new(&s).unwrap();
    let (fine, chord) = tessellate(&s, 96);
    let (coarse, coarse_chord) = tessellate(&s, 6);
    assert!(
        chord < 1e-3 && coarse_chord > 10.0 * chord,
        "{chord} {coarse_chord}"
    );
    // points near the surface, above and below it
    let mut rng = Rng(11);
    let ([u0, u1], [v0, v1]) = s.domain();
    let pts: Vec<DVec3> = (0..4000)
        .map(|_| {
            let (u, v) = (u0 + (u1 - u0) * rng.next(), v0 + (v1 - v0) * rng.next());
            s.point(u, v) + rng.point(0.05)
        })
        .collect();
    let exact = surface.distances(&pts);
    let fine_d = ReferenceIndex::Mesh(MeshIndex::new(fine)).distances(&pts);
    let coarse_d = MeshIndex::new(coarse).distances(&pts);
    let worst = |d: &[f64]| {
        d.iter()
            .zip(&exact)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max)
    };
    let (wf, wc) = (worst(&fine_d), worst(&coarse_d));
    eprintln!(
        "chord error {chord:.3e}, fine {wf:.3e}, coarse {wc:.3e} (its chord {coarse_chord:.3e})"
    );
    assert!(wf <= chord * 1.01 + 1e-12, "fine: {wf} > chord {chord}");
    assert!(
        wc > 2.0 * chord,
        "negative control: coarse {wc} vs fine chord {chord}"
    );
    // the surface's own points are within the chord error of the mesh
    let on: Vec<DVec3> = (0..1000)
        .map(|_| s.point(u0 + (u1 - u0) * rng.next(), v0 + (v1 - v0) * rng.next()))
        .collect();
    let d = MeshIndex::new(tessellate(&s, 96).0).distances(&on);
    assert!(d.iter().all(|&x| x <= chord * 1.01), "{chord}");
    // the unified index measures the surface as its closest points do
    let unified =
        ReferenceIndex::Surface(ClosestPoints::shared(std::sync::Arc::new(s.clone())).unwrap());
    assert_eq!(unified.distances(&pts), exact);
    assert!(unified.diagonal() > 2.0);
}

#[test]
fn a_mesh_that_is_not_one_is_refused() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    assert_eq!(TriangleMesh::new(p.clone(), vec![]), Err(MeshError::Empty));
    let e = TriangleMesh::new(p.clone(), vec![[0, 1, 3]]).unwrap_err();
    assert_eq!(
        e,
        MeshError::IndexOutOfRange {
            triangle: 0,
            index: 3,
            vertices: 3
        }
    );
    assert_eq!(e.to_string(), "triangle 1 names vertex 4, but there are 3");
    let mut bad = p.clone();
    bad[1].y = f64::NAN;
    assert_eq!(
        TriangleMesh::new(bad, vec![[0, 1, 2]]),
        Err(MeshError::NonFinite { vertex: 1 })
    );
    // negative control
    assert!(TriangleMesh::new(p, vec![[0, 1, 2]]).is_ok());
}
