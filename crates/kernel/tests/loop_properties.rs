//! docs/math.md §7 (paper 002): the limit masks of every boundary
//! rule (002's, OpenSubdiv's edge-only and edge-and-corner) agree with 40
//! levels of actual subdivision; progressive interpolation (plain and fast)
//! reaches 1e-3 and 1e-6 on the real meshes of `tests/data/meshes` under every
//! rule, the fast one in at most half the iterations, and the control mesh's
//! limit points — by a separate helper — match the given vertices.

mod common;

use glam::DVec3;
use proptest::prelude::*;
use streamline_kernel::loop_subdiv::mesh_interpolation::{Method, Options, interpolate};
use streamline_kernel::loop_subdiv::subdivide::{
    BoundaryRule, limit_points, subdivide, subdivide_levels, subdivide_refined,
};
use streamline_kernel::loop_subdiv::trimesh::{Topology, TriMesh};

/// A test mesh of `tests/data/meshes`, by the shared plain OBJ reader.
fn read_obj(name: &str) -> (TriMesh, Topology) {
    common::read_obj(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/meshes")
            .join(name),
    )
}

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

/// Limit points written separately from the kernel: neighbour sets from the
/// face list, boundary edges by counting, Eq. 3 inside, and on the boundary
/// the six masks of 002 Fig. 1 e–j as a table (centre type, neighbour types),
/// or OpenSubdiv's crease mask `(1/6, 2/3, 1/6)` (a single-face corner kept
/// under edge-and-corner).
fn limits_independent(p: &[DVec3], faces: &[[u32; 3]], rule: BoundaryRule) -> Vec<DVec3> {
    use std::collections::{BTreeSet, HashMap};
    let mut nbrs: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); p.len()];
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k] as usize, f[(k + 1) % 3] as usize);
            nbrs[a].insert(b);
            nbrs[b].insert(a);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let bnbrs = |v: usize| -> Vec<usize> {
        nbrs[v]
            .iter()
            .copied()
            .filter(|&u| count[&(v.min(u), v.max(u))] == 1)
            .collect()
    };
    (0..p.len())
        .map(|v| {
            let n = nbrs[v].len();
            let b = bnbrs(v);
            if b.is_empty() {
                let c = 3.0 / 8.0 + (2.0 * std::f64::consts::PI / n as f64).cos() / 4.0;
                let beta = 3.0 / (11.0 - 8.0 * (3.0 / 8.0 + c * c));
                let q: DVec3 = nbrs[v].iter().map(|&u| p[u]).sum::<DVec3>() / n as f64;
                return p[v] * beta + q * (1.0 - beta);
            }
            let (l, r) = (b[0], b[1]);
            let one_face = nbrs[v].len() == 2;
            match rule {
                BoundaryRule::EdgeAndCorner if one_face => return p[v],
                BoundaryRule::EdgeOnly | BoundaryRule::EdgeAndCorner => {
                    return (p[l] + p[r]) / 6.0 + p[v] * (2.0 / 3.0);
                }
                BoundaryRule::Paper => {}
            }
            let reg = |u: usize| nbrs[u].len() == 4;
            // masks (neighbour weight for a regular / extraordinary neighbour), centre weight
            let (wl, wr, wc) = match (reg(v), reg(l), reg(r)) {
                (true, true, true) => (1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0),
                (true, a, b) => {
                    // regular centre: level-1 mask (1/6, 2/3, 1/6); an extraordinary
                    // neighbour's edge point is ⅜E + ⅝C
                    let w = |r: bool| {
                        if r {
                            1.0 / 12.0 + 1.0 / 12.0
                        } else {
                            1.0 / 16.0 + 1.0 / 12.0
                        }
                    };
                    (w(a), w(b), 1.0 - w(a) - w(b))
                }
                (false, a, b) => {
                    // extraordinary centre: level-1 mask (1/5, 3/5, 1/5); a regular
                    // neighbour's edge point is ⅝R + ⅜C
                    let w = |r: bool| {
                        if r {
                            1.0 / 8.0 + 3.0 / 40.0
                        } else {
                            1.0 / 10.0 + 3.0 / 40.0
                        }
                    };
                    (w(a), w(b), 1.0 - w(a) - w(b))
                }
            };
            p[l] * wl + p[r] * wr + p[v] * wc
        })
        .collect()
}

const MESHES: [&str; 8] = [
    "knight.obj",
    "snail.obj",
    "teddy.obj",
    "spot.obj",
    "fertility.obj",
    "fairing-cross.obj",
    "max-planck.obj",
    "camelhead.obj",
];

#[test]
fn progressive_interpolation_on_real_meshes() {
    for name in MESHES {
        let (m, t) = read_obj(name);
        for rule in BoundaryRule::ALL {
            let mut its = Vec::new();
            for tol in [1e-3, 1e-6] {
                for method in [Method::Plain, Method::Fast] {
                    let opts = Options {
                        tolerance: tol,
                        max_iterations: 5000,
                        method,
                        boundary: rule,
                    };
                    let (ctrl, rep) = interpolate(&m, &t, &opts);
                    assert!(
                        rep.converged && rep.max_error < tol,
                        "{name} {} {method:?} {tol}: {rep:?}",
                        rule.name()
                    );
                    // independent check: limit points of the control mesh by a separate helper
                    let lim = limits_independent(&ctrl, &m.faces, rule);
                    let scale = m.scale();
                    let worst = (0..m.positions.len())
                        .map(|v| (lim[v] - m.positions[v]).length() / scale)
                        .fold(0.0, f64::max);
                    assert!(
                        worst < tol * 1.000_001,
                        "{name} {} {method:?}: independent limits {worst:e} from the data",
                        rule.name()
                    );
                    its.push((tol, method, rep.iterations()));
                }
            }
            let find = |m: Method| its.iter().find(|i| i.0 == 1e-6 && i.1 == m).unwrap().2;
            let (plain6, fast6) = (find(Method::Plain), find(Method::Fast));
            println!("{name} {}: {its:?}", rule.name());
            assert!(
                2 * fast6 <= plain6,
                "{name} {}: fast {fast6} vs plain {plain6} iterations to 1e-6",
                rule.name()
            );
        }
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

/// `t` against `want`, the topology rebuilt from the same faces: the same
/// rings (interior ones up to rotation), boundary, loops (up to rotation),
/// edges with their opposite vertices, and every ring edge and face edge
/// joining the vertices it should.
fn same_topology(name: &str, faces: &[[u32; 3]], t: &Topology, want: &Topology) {
    use std::collections::HashMap;
    let n = want.vertices();
    assert_eq!(t.vertices(), n, "{name}");
    assert_eq!(t.boundary, want.boundary, "{name}");
    let rotated = |a: &[u32]| -> Vec<u32> {
        let i = (0..a.len()).min_by_key(|&i| a[i]).unwrap_or(0);
        a[i..].iter().chain(&a[..i]).copied().collect()
    };
    let ends = |e: u32| t.edges[e as usize].0;
    for v in 0..n {
        let (r, w) = (t.ring(v), want.ring(v));
        if want.boundary[v] {
            assert_eq!(r, w, "{name}: ring of boundary vertex {v}");
        } else {
            assert_eq!(rotated(r), rotated(w), "{name}: ring of vertex {v}");
        }
        for (&u, &e) in r.iter().zip(t.ring_edges(v)) {
            let [a, b] = ends(e);
            assert!(
                (a, b) == (v as u32, u) || (a, b) == (u, v as u32),
                "{name}: ring edge {v}–{u}"
            );
        }
    }
    let map = |t: &Topology| -> HashMap<[u32; 2], [u32; 2]> { t.edges.iter().copied().collect() };
    assert_eq!(
        map(t),
        map(want),
        "{name}: edges and their opposite vertices"
    );
    for (f, fe) in faces.iter().zip(&t.face_edges) {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            assert_eq!(
                ends(fe[k]),
                [a.min(b), a.max(b)],
                "{name}: face {f:?} edge {k}"
            );
        }
    }
    let loops = |t: &Topology| -> Vec<Vec<u32>> {
        let mut l: Vec<Vec<u32>> = t.loops.iter().map(|l| rotated(l)).collect();
        l.sort();
        l
    };
    assert_eq!(loops(t), loops(want), "{name}: boundary loops");
}

#[test]
fn refined_topology_is_the_rebuilt_one() {
    for name in MESHES {
        let (m, t) = read_obj(name);
        let (m1, t1) = subdivide_refined(&m, &t, BoundaryRule::EdgeAndCorner).unwrap();
        same_topology(name, &m1.faces, &t1, &m1.topology().unwrap());
        let (m2, t2) = subdivide_refined(&m1, &t1, BoundaryRule::EdgeAndCorner).unwrap();
        same_topology(name, &m2.faces, &t2, &m2.topology().unwrap());
    }
}

#[test]
fn subdividing_levels_on_refined_topology_equals_rebuilding_it() {
    // three levels with derived topologies against three with rebuilt ones; the
    // new vertices are numbered by different edge orders, so they are matched
    // through the edge they split (its end points, themselves matched)
    for name in ["snail.obj", "fairing-cross.obj", "knight.obj"] {
        let (m, t) = read_obj(name);
        for rule in BoundaryRule::ALL {
            let fast = subdivide_levels(&m, &t, rule, 3).unwrap();
            let mut slow = m.clone();
            // id maps: slow's vertex → fast's vertex, level by level
            let mut map: Vec<u32> = (0..m.positions.len() as u32).collect();
            let (mut fm, mut ft) = (m.clone(), t.clone());
            for level in 0..3 {
                let st = slow.topology().unwrap();
                let next = subdivide(&slow, &st, rule).unwrap();
                let fe: std::collections::HashMap<[u32; 2], usize> =
                    ft.edges.iter().enumerate().map(|(i, e)| (e.0, i)).collect();
                let fnv = fm.positions.len() as u32;
                let mut nmap = map.clone();
                for &([a, b], _) in &st.edges {
                    let (x, y) = (map[a as usize], map[b as usize]);
                    nmap.push(fnv + fe[&[x.min(y), x.max(y)]] as u32);
                }
                map = nmap;
                slow = next;
                if level < 2 {
                    (fm, ft) = subdivide_refined(&fm, &ft, rule).unwrap();
                }
            }
            assert_eq!(fast.positions.len(), slow.positions.len());
            let scale = m.scale();
            for (v, p) in slow.positions.iter().enumerate() {
                let d = (fast.positions[map[v] as usize] - *p).length() / scale;
                assert!(d < 1e-13, "{name} {}: vertex {v} off by {d:e}", rule.name());
            }
        }
    }
}

/// The faces of `m` whose bit in `keep` is set, vertices renumbered (unused dropped).
fn sub_mesh(m: &TriMesh, keep: &[bool]) -> TriMesh {
    let mut index = vec![u32::MAX; m.positions.len()];
    let mut positions = Vec::new();
    let faces = m
        .faces
        .iter()
        .zip(keep)
        .filter(|(_, k)| **k)
        .map(|(f, _)| {
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

/// The faces of `m` less holes: every face within `r` vertex-rings of each
/// seed face is dropped.
fn with_holes(m: &TriMesh, seeds: &[(usize, usize)]) -> TriMesh {
    let mut keep = vec![true; m.faces.len()];
    for &(seed, r) in seeds {
        let mut near = vec![false; m.positions.len()];
        for &v in &m.faces[seed % m.faces.len()] {
            near[v as usize] = true;
        }
        for _ in 0..r {
            let grow: Vec<[u32; 3]> = m
                .faces
                .iter()
                .filter(|f| f.iter().any(|&v| near[v as usize]))
                .copied()
                .collect();
            for f in grow {
                for v in f {
                    near[v as usize] = true;
                }
            }
        }
        for (k, f) in keep.iter_mut().zip(&m.faces) {
            if f.iter().all(|&v| near[v as usize]) {
                *k = false;
            }
        }
    }
    sub_mesh(m, &keep)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]
    /// Nasty open meshes: the knight with random holes (several boundary
    /// loops, corners, thin bridges; the few left non-manifold are skipped):
    /// the derived topology is the rebuilt one, two levels deep.
    #[test]
    fn refined_topology_of_random_open_meshes(
        seeds in prop::collection::vec((0usize..1000, 0usize..3), 1..8),
    ) {
        let (knight, _) = read_obj("knight.obj");
        let m = with_holes(&knight, &seeds);
        let Ok(t) = m.topology() else {
            return Err(TestCaseError::reject("non-manifold after the cut"));
        };
        prop_assert!(!t.loops.is_empty());
        let (m1, t1) = subdivide_refined(&m, &t, BoundaryRule::EdgeAndCorner).unwrap();
        same_topology("random", &m1.faces, &t1, &m1.topology().unwrap());
        let (m2, t2) = subdivide_refined(&m1, &t1, BoundaryRule::Paper).unwrap();
        same_topology("random", &m2.faces, &t2, &m2.topology().unwrap());
    }
}
