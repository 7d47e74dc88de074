//! docs/math.md §7 (paper 002): the limit masks of every boundary rule
//! (002's, OpenSubdiv's edge-only and edge-and-corner) agree with 40 levels of
//! actual subdivision, inside and on 14 boundary configurations, and the edge
//! rules subdivide as the crease rules.

mod common;

use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::loop_subdiv::subdivide::{BoundaryRule, limit_points, subdivide};
use streamline_kernel::loop_subdiv::trimesh::TriMesh;

/// The position vertex 0 reaches after `levels` steps of actual Loop
/// subdivision. After each step the mesh is cut down to the faces within 4
/// rings of vertex 0 (renumbered, vertex 0 first): vertex 0 and its 1-ring at
/// the next level depend only on its 2-ring here, and every vertex of the
/// 3-ring keeps all its faces (so its valence and type), so the cut changes
/// nothing vertex 0 will see, and 40 levels stay cheap. Subdivision commutes
/// with affine maps, so after each level the piece is moved to put vertex 0 at
/// the origin and scaled by 2 (exact): near the boundary the crease rules
/// flatten it onto the boundary curve (width shrinking by 4 a level, length by
/// 2), and at the original scale its faces' areas would fall below rounding.
fn subdivided_limit(mesh: &TriMesh, levels: usize, rule: BoundaryRule) -> DVec3 {
    let mut m = mesh.clone();
    let (mut origin, mut scale) = (DVec3::ZERO, 1.0);
    for k in 0..levels {
        let t = m
            .topology()
            .unwrap_or_else(|e| panic!("{}: level {k}: {e}: {m:?}", rule.name()));
        m = subdivide(&m, &t, rule).unwrap();
        m = around_vertex_0(&m, 4);
        let o = m.positions[0];
        origin += o / scale;
        scale *= 2.0;
        for p in &mut m.positions {
            *p = (*p - o) * 2.0;
        }
    }
    origin + m.positions[0] / scale
}

fn around_vertex_0(m: &TriMesh, rings: usize) -> TriMesh {
    let n = m.positions.len();
    let mut dist = vec![usize::MAX; n];
    dist[0] = 0;
    for d in 0..rings {
        for f in &m.faces {
            if f.iter().any(|&v| dist[v as usize] == d) {
                for &v in f {
                    if dist[v as usize] == usize::MAX {
                        dist[v as usize] = d + 1;
                    }
                }
            }
        }
    }
    let keep: Vec<&[u32; 3]> = m
        .faces
        .iter()
        .filter(|f| f.iter().any(|&v| dist[v as usize] < rings))
        .collect();
    let mut index = vec![u32::MAX; n];
    let mut positions = vec![m.positions[0]];
    index[0] = 0;
    let faces = keep
        .iter()
        .map(|f| {
            f.map(|v| {
                if index[v as usize] == u32::MAX {
                    index[v as usize] = positions.len() as u32;
                    positions.push(m.positions[v as usize]);
                }
                index[v as usize]
            })
        })
        .collect();
    TriMesh { positions, faces }
}

/// A fan of `n` triangles around vertex 0 (open when `open`), with wiggled heights.
fn fan(n: usize, open: bool) -> TriMesh {
    let mut p = vec![DVec3::new(0.0, 0.0, 0.3)];
    let k = if open { n + 1 } else { n };
    let span = if open {
        std::f64::consts::PI * 1.2
    } else {
        std::f64::consts::TAU
    };
    for i in 0..k {
        let a = span * i as f64 / n as f64;
        p.push(DVec3::new(a.cos(), a.sin(), 0.2 * (3.0 * a).sin()));
    }
    let faces = (0..n)
        .map(|i| [0, 1 + i as u32, 1 + ((i + 1) % k) as u32])
        .collect();
    TriMesh {
        positions: p,
        faces,
    }
}

#[test]
fn interior_limit_masks_match_subdivision() {
    // closed fans are not closed meshes; use the interior vertex of a double fan (two caps)
    for n in [3usize, 4, 5, 6, 7, 9] {
        let mut m = fan(n, false);
        // close it with a second cone below, so vertex 0 is interior and the ring too
        let base = m.positions.len() as u32;
        m.positions.push(DVec3::new(0.0, 0.0, -1.0));
        for i in 0..n as u32 {
            m.faces.push([base, 1 + (i + 1) % n as u32, 1 + i]);
        }
        let t = m.topology().unwrap();
        for rule in BoundaryRule::ALL {
            let mut lim = Vec::new();
            limit_points(&m.positions, &t, rule, &mut lim);
            let sub = subdivided_limit(&m, 40, rule);
            let d = (lim[0] - sub).length();
            assert!(
                d < 1e-12,
                "valence {n}: mask {:?} vs 40 levels {:?} ({d:e})",
                lim[0],
                sub
            );
        }
    }
}

/// The boundary configurations tested: centre, left and right valences (2 is
/// a single-face corner, 4 a regular boundary vertex of 002).
const BOUNDARY_CASES: [(usize, usize, usize); 14] = [
    (4, 4, 4),
    (4, 3, 4),
    (4, 3, 5),
    (3, 4, 4),
    (3, 3, 4),
    (5, 2, 3),
    (2, 4, 2),
    (6, 4, 5),
    (2, 3, 2),
    (2, 2, 2),
    (3, 2, 4),
    (4, 2, 2),
    (7, 2, 6),
    (5, 5, 3),
];

/// The mask at vertex 0 of `m` against 40 levels of subdivision under `rule`.
fn check_boundary_vertex_0(m: &TriMesh, rule: BoundaryRule) -> Result<(), String> {
    let t = m.topology().map_err(|e| e.to_string())?;
    let mut lim = Vec::new();
    limit_points(&m.positions, &t, rule, &mut lim);
    let sub = subdivided_limit(m, 40, rule);
    let d = (lim[0] - sub).length();
    let ring = t.ring(0);
    let (l, r) = (ring[0] as usize, ring[ring.len() - 1] as usize);
    if d < 1e-12 {
        Ok(())
    } else {
        Err(format!(
            "{}: valences {},{},{}: mask {:?} vs 40 levels {:?} ({d:e})",
            rule.name(),
            t.valence(0),
            t.valence(l),
            t.valence(r),
            lim[0],
            sub
        ))
    }
}

#[test]
fn boundary_limit_masks_match_subdivision() {
    // every configuration: centre regular (valence 4) or not, a corner (valence
    // 2) or not, neighbours likewise; under every rule
    let mut covered = std::collections::BTreeSet::new();
    let mut corners = std::collections::BTreeSet::new();
    for (n_c, n_l, n_r) in BOUNDARY_CASES {
        let m = boundary_case(n_c, n_l, n_r);
        let t = m.topology().unwrap();
        let ring = t.ring(0);
        let (l, r) = (ring[0] as usize, ring[ring.len() - 1] as usize);
        let reg = |v: usize| t.valence(v) == 4;
        let (a, b) = (reg(l), reg(r));
        covered.insert((reg(0), a.min(b), a.max(b)));
        let corner = |v: usize| t.valence(v) == 2;
        corners.insert((corner(0), corner(l) || corner(r)));
        for rule in BoundaryRule::ALL {
            check_boundary_vertex_0(&m, rule).unwrap();
        }
    }
    assert_eq!(
        covered.len(),
        6,
        "all six boundary configurations of 002: {covered:?}"
    );
    assert_eq!(
        corners.len(),
        4,
        "corner centre or not, beside a corner or not: {corners:?}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// Random valences and random positions (the strip wiggled per vertex):
    /// every rule's mask agrees with 40 levels of subdivision.
    #[test]
    fn boundary_masks_match_subdivision_on_random_strips(
        nc in 2usize..8, nl in 2usize..7, nr in 2usize..7,
        jitter in prop::collection::vec(
            (-0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3), 32),
    ) {
        let mut m = boundary_case(nc, nl, nr);
        for (p, j) in m.positions.iter_mut().zip(&jitter) {
            *p += DVec3::new(j.0, j.1, j.2) * 0.3;
        }
        if m.topology().is_ok() {
            for rule in BoundaryRule::ALL {
                prop_assert!(check_boundary_vertex_0(&m, rule).is_ok(), "{:?}",
                    check_boundary_vertex_0(&m, rule));
            }
        }
    }
}

/// An open mesh where vertex 0 is a boundary vertex of valence `nc` whose
/// boundary neighbours 1 and 2 have valences `nl` and `nr`.
fn boundary_case(nc: usize, nl: usize, nr: usize) -> TriMesh {
    // the centre's fan: neighbours 1 (left), interior ring x_1..x_{nc−2}, 2 (right)
    let mut p = vec![
        DVec3::new(0.0, 0.0, 0.1),
        DVec3::new(-1.0, 0.0, 0.2),
        DVec3::new(1.0, 0.0, -0.1),
    ];
    let mut ring = vec![1u32];
    for i in 0..nc - 2 {
        let a = std::f64::consts::PI * (1.0 - (i + 1) as f64 / (nc - 1) as f64);
        p.push(DVec3::new(a.cos(), a.sin(), 0.15 * (2.0 * a).cos()));
        ring.push(p.len() as u32 - 1);
    }
    ring.push(2);
    let mut faces: Vec<[u32; 3]> = ring.windows(2).map(|w| [0, w[1], w[0]]).collect();
    // give the side neighbours more faces, away from the centre, below the boundary
    let extend = |side: u32,
                  next_in: u32,
                  want: usize,
                  dir: f64,
                  faces: &mut Vec<[u32; 3]>,
                  p: &mut Vec<DVec3>| {
        // current valence of `side`: 0 and `next_in` (its first face) → 2
        let have = 2usize;
        let mut prev = next_in;
        for k in 0..want.saturating_sub(have) {
            let a = std::f64::consts::PI * (0.5 + 0.4 * (k + 1) as f64 / want as f64);
            p.push(
                p[side as usize]
                    + DVec3::new(dir * a.sin() * 0.8, a.cos() * 0.8 + 0.6, 0.1 * k as f64),
            );
            let new = p.len() as u32 - 1;
            if dir < 0.0 {
                faces.push([side, prev, new]);
            } else {
                faces.push([side, new, prev]);
            }
            prev = new;
        }
    };
    let first_in = ring[1];
    let last_in = ring[ring.len() - 2];
    extend(1, first_in, nl, -1.0, &mut faces, &mut p);
    extend(2, last_in, nr, 1.0, &mut faces, &mut p);
    TriMesh {
        positions: p,
        faces,
    }
}

#[test]
fn edge_rules_subdivide_as_the_crease_rules() {
    // one step on a fan with a corner: boundary edge points are midpoints, the
    // corner stays (edge-and-corner) or moves by ⅛–¾–⅛ (edge-only), interior
    // rules are Loop's under every rule
    let m = boundary_case(4, 2, 3);
    let t = m.topology().unwrap();
    let p = &m.positions;
    for rule in BoundaryRule::ALL {
        let s = subdivide(&m, &t, rule).unwrap();
        for (e, &([a, b], [c, d])) in t.edges.iter().enumerate() {
            let (pa, pb) = (p[a as usize], p[b as usize]);
            let got = s.positions[p.len() + e];
            let want = if d != u32::MAX {
                (pa + pb) * 0.375 + (p[c as usize] + p[d as usize]) * 0.125
            } else if rule == BoundaryRule::Paper {
                continue;
            } else {
                (pa + pb) * 0.5
            };
            assert!((got - want).length() < 1e-15, "{}: edge {e}", rule.name());
        }
        let ring = t.ring(1);
        assert_eq!(ring.len(), 2, "vertex 1 is a corner");
        let moved = p[1] * 0.75 + (p[ring[0] as usize] + p[ring[1] as usize]) * 0.125;
        let want = if rule == BoundaryRule::EdgeAndCorner {
            p[1]
        } else {
            moved
        };
        assert!((s.positions[1] - want).length() < 1e-15, "{}", rule.name());
    }
}
