//! docs/math.md §7: the topology of a refined level derived from the level
//! before (`Topology::refine`) equals the one rebuilt from its faces, on the
//! real meshes and on random open meshes with holes, and subdividing on it
//! gives the same levels.

mod common;

use common::loop_meshes::*;
use proptest::prelude::*;
use streamline_kernel::loop_subdiv::subdivide::{
    BoundaryRule, subdivide, subdivide_levels, subdivide_refined,
};
use streamline_kernel::loop_subdiv::trimesh::Topology;

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
        let (m, t) = read_mesh(name);
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
        let (m, t) = read_mesh(name);
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]
    /// Nasty open meshes: the knight with random holes (several boundary
    /// loops, corners, thin bridges; the few left non-manifold are skipped):
    /// the derived topology is the rebuilt one, two levels deep.
    #[test]
    fn refined_topology_of_random_open_meshes(
        seeds in prop::collection::vec((0usize..1000, 0usize..3), 1..8),
    ) {
        let (knight, _) = read_mesh("knight.obj");
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
