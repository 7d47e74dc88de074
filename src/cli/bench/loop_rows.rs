//! The bench rows of Loop subdivision and progressive interpolation (paper
//! 002), on the checkout's test meshes.

use super::workloads::Workload;
use streamline_kernel::DVec3;

/// Where the checkout keeps test mesh `name` (rows that need one are left
/// out when it is missing, e.g. for an installed binary).
fn test_mesh_path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/meshes")
        .join(format!("{name}.obj"))
}

/// Test mesh `name`, read when a row is set up (rows whose mesh the
/// checkout lacks are left out, decided before).
fn read_test_mesh(name: &str) -> streamline_kernel::loop_subdiv::trimesh::TriMesh {
    crate::scene::loop_mesh::obj::read(&test_mesh_path(name))
        .expect("the checkout's test mesh reads")
        .0
}

/// Loop subdivision (the topology from the face list, then 1–3 levels, each
/// level's topology derived from the one before) of a small, a medium and the
/// largest test mesh (`loop/subdivide/<mesh>/d<k>`, 002's rule); the same for
/// a 19,730-vertex open mesh (fairing-cross subdivided once, 4 boundary loops)
/// under each boundary rule (`loop/20k/<rule>/d<k>`, beside
/// OpenSubdiv in `docs/loop.md`); and
/// progressive interpolation to 1e-3 of a 1,151,994-vertex mesh (fertility
/// subdivided 4 times, every vertex then moved by up to 2 mean edge lengths),
/// topology included (`pi/1m/<plain|fast>`; docs/math.md §7).
pub fn loop_rows() -> Vec<Workload> {
    use streamline_kernel::loop_subdiv::mesh_interpolation::{Method, Options, interpolate};
    use streamline_kernel::loop_subdiv::subdivide::{BoundaryRule, subdivide, subdivide_levels};
    use streamline_kernel::loop_subdiv::trimesh::TriMesh;
    let mut out = Vec::new();
    for name in ["knight", "spot", "camelhead"] {
        if !test_mesh_path(name).exists() {
            continue;
        }
        for depth in 1..=3 {
            out.push(Workload::lazy(
                format!("loop/subdivide/{name}/d{depth}"),
                move || {
                    let mesh = read_test_mesh(name);
                    Box::new(move || {
                        let t = mesh.topology().expect("valid test mesh");
                        let m = subdivide_levels(&mesh, &t, BoundaryRule::Paper, depth)
                            .expect("within the cap");
                        m.positions[m.positions.len() / 2].x
                    })
                },
            ));
        }
    }
    out.extend(loop_20k_rows());
    if test_mesh_path("fertility").exists() {
        for method in [Method::Plain, Method::Fast] {
            out.push(Workload::lazy(
                format!("pi/1m/{}", method.name()),
                move || {
                    let mut m: TriMesh = read_test_mesh("fertility");
                    for _ in 0..4 {
                        let t = m.topology().expect("valid test mesh");
                        m = subdivide(&m, &t, BoundaryRule::Paper).expect("within the cap");
                    }
                    rough_up(&mut m, 4.0);
                    Box::new(move || {
                        let t = m.topology().expect("valid mesh");
                        let opts = Options {
                            method,
                            ..Options::DEFAULT
                        };
                        let (ctrl, rep) = interpolate(&m, &t, &opts);
                        assert!(rep.converged, "{rep:?}");
                        ctrl[0].x + rep.max_error
                    })
                },
            ));
        }
    }
    out
}

/// Loop subdivision of a 19,730-vertex open mesh (fairing-cross subdivided
/// once, 4 boundary loops) under each boundary rule, levels 1–3, building the
/// topology from the face list included (`loop/20k/<rule>/d<k>`;
/// beside OpenSubdiv in `docs/loop.md`).
pub fn loop_20k_rows() -> Vec<Workload> {
    use streamline_kernel::loop_subdiv::subdivide::{BoundaryRule, subdivide, subdivide_levels};
    let mut out = Vec::new();
    if test_mesh_path("fairing-cross").exists() {
        for rule in BoundaryRule::ALL {
            for depth in 1..=3 {
                let name = format!("loop/20k/{}/d{depth}", rule.name());
                out.push(Workload::lazy(name, move || {
                    let base = read_test_mesh("fairing-cross");
                    let t = base.topology().expect("valid test mesh");
                    let mesh =
                        subdivide(&base, &t, BoundaryRule::EdgeAndCorner).expect("within the cap");
                    Box::new(move || {
                        let t = mesh.topology().expect("valid mesh");
                        let m = subdivide_levels(&mesh, &t, rule, depth).expect("within the cap");
                        m.positions[m.positions.len() / 2].x
                    })
                }));
            }
        }
    }
    out
}

/// Moves every vertex by a deterministic pseudo-random offset of up to
/// `amount` × the mean edge length over 2 in each coordinate.
pub fn rough_up(m: &mut streamline_kernel::loop_subdiv::trimesh::TriMesh, amount: f64) {
    let t = m.topology().expect("valid mesh");
    let mean = m.mean_edge_length(&t);
    let mut x: u64 = 88_172_645_463_325_252;
    let mut r = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for p in m.positions.iter_mut() {
        *p += DVec3::new(r(), r(), r()) * (amount * mean);
    }
}
