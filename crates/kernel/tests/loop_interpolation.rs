//! docs/math.md §7 (paper 002): progressive interpolation (plain and fast)
//! reaches 1e-3 and 1e-6 on the real meshes of `tests/data/meshes` under every
//! boundary rule, the fast one in at most half the iterations, and the control
//! mesh's limit points, by a separate helper, match the given vertices.

mod common;

use common::loop_meshes::*;
use glam::DVec3;
use streamline_kernel::loop_subdiv::mesh_interpolation::{Method, Options, interpolate};
use streamline_kernel::loop_subdiv::subdivide::BoundaryRule;

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

#[test]
fn progressive_interpolation_on_real_meshes() {
    for name in MESHES {
        let (m, t) = read_mesh(name);
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
