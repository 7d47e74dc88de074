//! The benchmark workloads, shared by `streamline-studio bench` and `cargo bench`
//! (`benches/table1.rs`) so both measure exactly the same thing.

use streamline_kernel::curve::qi::QiCurve;
use streamline_kernel::curve::scheme::{CurveScheme, subdivide_into};
use streamline_kernel::{Builder, DVec3, Design, levels::presets};

/// The five control tangents of the Table 1 rows (a wavy curve on the sphere).
pub fn table1_tangents() -> Vec<DVec3> {
    [
        (1.0, 0.0, 0.2),
        (0.8, 0.6, 0.1),
        (0.2, 0.9, 0.4),
        (-0.3, 0.8, 0.6),
        (-0.7, 0.4, 0.5),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect()
}

/// A named, repeatable piece of work.
pub struct Workload {
    /// Row name, e.g. `curve/chaikin/d7`.
    pub name: String,
    /// Runs the work once and returns a value that depends on all of it.
    pub run: Box<dyn FnMut() -> f64>,
}

/// The work of a row, made by its setup.
pub type Work = Box<dyn FnMut() -> f64>;

impl Workload {
    /// A row whose setup (an app built, a mesh read and subdivided) runs on
    /// its first call, so that `bench --filter` prepares only the rows it
    /// times (every row's setup took about 1.2 s before). Callers run a row
    /// once untimed first (`bench`'s warm-up, criterion's).
    pub fn lazy(name: String, setup: impl FnOnce() -> Work + 'static) -> Workload {
        let mut setup = Some(setup);
        let mut work: Option<Work> = None;
        Workload {
            name,
            run: Box::new(move || {
                let w = work.get_or_insert_with(|| (setup.take().expect("set up once"))());
                w()
            }),
        }
    }
}

fn curve_row(scheme: CurveScheme, depth: u32) -> Workload {
    let input = table1_tangents();
    let (mut a, mut b) = (Vec::with_capacity(512), Vec::with_capacity(512));
    let name = match scheme {
        CurveScheme::FourPoint { .. } => format!("curve/four-point/d{depth}"),
        s => format!("curve/{}/d{depth}", s.name()),
    };
    Workload {
        name,
        run: Box::new(move || {
            a.clear();
            a.extend_from_slice(&input);
            subdivide_into(scheme, depth, &mut a, &mut b);
            a[a.len() / 2].x + a.len() as f64
        }),
    }
}

fn qi_row(order: usize, samples: usize) -> Workload {
    let q = QiCurve::new(&table1_tangents(), order).expect("valid");
    let mut out = Vec::with_capacity(samples);
    Workload {
        name: format!("curve/qi-k{order}/{samples}"),
        run: Box::new(move || {
            out.clear();
            let m = (samples - 1) as f64;
            out.extend((0..samples).map(|j| q.tangent(j as f64 / m)));
            out[samples / 2].x
        }),
    }
}

fn surface_row(design: Design, label: &str, depth: u32) -> Workload {
    Workload {
        name: format!("surface/kobbelt/{label}/d{depth}/full"),
        run: Box::new(move || {
            let b = design.build(depth).expect("valid");
            b.mesh.positions[b.mesh.positions.len() / 2].x
        }),
    }
}

/// The rows of the paper's Table 1: Chaikin d7, cubic B-spline d7, 4-point d6, QI k = 3, 4, 5 at 257 samples.
pub fn table1() -> Vec<Workload> {
    vec![
        curve_row(CurveScheme::Chaikin, 7),
        curve_row(CurveScheme::CubicBSpline, 7),
        curve_row(CurveScheme::FourPoint { omega: 1.0 }, 6),
        qi_row(3, 257),
        qi_row(4, 257),
        qi_row(5, 257),
    ]
}

/// Full builds (blend + integrate + mesh) of the 9×6 car at `depths`.
pub fn car_surface(depths: impl IntoIterator<Item = u32>) -> Vec<Workload> {
    depths
        .into_iter()
        .map(|d| surface_row(presets::car1(), "9x6", d))
        .collect()
}

/// Full builds of the car at `depth` into a kept [`Builder`] (buffers
/// reused, every entry recomputed; issue 2's 0.5 ms target) on one thread:
/// with the CPU's widest vector path, with AVX2 at most, and scalar
/// (`surface/kobbelt/9x6/d5/builder-1t`, `…/builder-1t-avx2`,
/// `…/builder-1t-scalar`; the results are bitwise equal).
pub fn car_builder(depth: u32) -> Vec<Workload> {
    use streamline_kernel::parallel;
    use streamline_kernel::simd::{Width, set_limit};
    [
        ("1t", Width::Avx512),
        ("1t-avx2", Width::Avx2),
        ("1t-scalar", Width::Scalar),
    ]
    .into_iter()
    .map(|(label, width)| {
        let design = presets::car1();
        let mut b = Builder::new();
        Workload {
            name: format!("surface/kobbelt/9x6/d{depth}/builder-{label}"),
            run: Box::new(move || {
                parallel::set_enabled(false);
                set_limit(width);
                b.build(&design, depth).expect("valid");
                parallel::set_enabled(true);
                set_limit(Width::Avx512);
                b.mesh().positions[b.mesh().positions.len() / 2].x
            }),
        }
    })
    .collect()
}

/// Every row `streamline-studio bench` reports.
pub fn all() -> Vec<Workload> {
    let mut rows = table1();
    rows.extend(car_drag(6));
    rows.extend(car_surface([3, 5]));
    rows.extend(car_builder(5));
    rows.extend(incremental());
    rows.extend(fine_tuning());
    rows.extend(loop_rows());
    rows.extend(authoring());
    rows.extend(fit_rows());
    rows
}

/// An edit of a drag: tangent (`row`, `col`) turned 0.01 rad about `y`,
/// the other way each time (`sign` flips), so that a row alternates
/// between two states.
pub(super) fn wiggle(row: usize, col: usize, sign: &mut f64) -> crate::ecs::Edit {
    *sign = -*sign;
    crate::ecs::Edit::Rotate {
        row,
        col,
        axis: DVec3::Y,
        radians: 0.01 * *sign,
    }
}

/// A drag's frame on the car at `depth` as the editor runs it: control
/// tangent (2, 4) turned back and forth, with the mesh stage's `f32` staging
/// pair ([`crate::ecs::vertex_mirror::VertexMirror`]) that the editor's
/// renderer swaps in (`ecs/car/d6/drag`; issue 26 item 7's frame, less the
/// panels and the renderer); the same with the surface's `f64` normals left
/// behind as the editor leaves them while a handle is dragged
/// (`…/drag-deferred`, [`crate::ecs::DeferNormals`]); and the frame after
/// the drag, which makes them (`…/release`: the window of a drag's frame).
pub fn car_drag(depth: u32) -> Vec<Workload> {
    use crate::ecs::{self, DeferNormals, SurfaceData, vertex_mirror::VertexMirror};
    use crate::scene::Scene;
    use streamline_kernel::parallel;
    let app = move |defer: bool| {
        let mut app = ecs::headless_app(Scene::from_design("car", presets::car1(), depth));
        app.init_resource::<VertexMirror>();
        app.insert_resource(DeferNormals(defer));
        app.update();
        app
    };
    // one thread, as the editor runs on a machine of fewer than four cores
    // (`editor::kernel_helper_wanted`)
    let frame = |app: &mut bevy::app::App, edit: Option<ecs::Edit>| {
        parallel::set_enabled(false);
        if let Some(edit) = edit {
            ecs::send(app, edit);
        }
        app.update();
        parallel::set_enabled(true);
        app.world().resource::<SurfaceData>().points.data()[0].x
    };
    let drag = move |name: &str, defer: bool| {
        Workload::lazy(format!("ecs/car/d{depth}/{name}"), move || {
            let mut app = app(defer);
            let mut sign = 1.0;
            Box::new(move || frame(&mut app, Some(wiggle(2, 4, &mut sign))))
        })
    };
    let release = Workload::lazy(format!("ecs/car/d{depth}/release"), move || {
        let mut app = app(true);
        let mut sign = 1.0;
        frame(&mut app, Some(wiggle(2, 4, &mut sign)));
        frame(&mut app, Some(wiggle(2, 4, &mut sign)));
        let behind = app.world().resource::<SurfaceData>().normals_behind();
        assert!(behind.is_some(), "a drag's frame leaves its normals behind");
        app.insert_resource(DeferNormals(false));
        Box::new(move || {
            app.world_mut().resource_mut::<SurfaceData>().normals_behind = behind;
            frame(&mut app, None)
        })
    });
    vec![drag("drag", false), drag("drag-deferred", true), release]
}

/// Authoring on the car at depth 5 (issue 20, `docs/math.md §9`), each
/// from message to updated mesh: a row inserted and deleted in turn
/// (`ecs/car/d5/insert-row`, a full rebuild each), an initial-curve tangent
/// turned back and forth (`ecs/car/d5/initial-curve`: every streamline
/// placed again, no tangent re-blended; compare `ecs/car/d5/edit-interior`),
/// and the mirrored car (11 doubled rows): its full build beside the plain
/// one's (`surface/kobbelt/9x6-mirrored/d5/full`) and a tangent edit
/// (`ecs/car-mirrored/d5/edit-interior`: both copies of the cell re-blended).
pub fn authoring() -> Vec<Workload> {
    use crate::ecs::{self, Edit, SurfaceData, authoring::AuthorEdit};
    use crate::scene::Scene;
    use streamline_kernel::authoring::Axis;
    let depth = 5;
    let app_of = move |mirror: bool| {
        let mut scene = Scene::from_design("car", presets::car1(), depth);
        scene.mirror = mirror;
        ecs::headless_app(scene)
    };
    let point = |app: &bevy::prelude::App| app.world().resource::<SurfaceData>().points.data()[0].x;
    let mut out = Vec::new();
    out.push(Workload::lazy(
        format!("ecs/car/d{depth}/insert-row"),
        move || {
            let mut app = app_of(false);
            let mut inserted = false;
            Box::new(move || {
                let axis = Axis::Row;
                inserted = !inserted;
                let edit = if inserted {
                    AuthorEdit::insert(axis, 3)
                } else {
                    AuthorEdit::delete(axis, 3)
                };
                ecs::send(&mut app, Edit::Author(edit));
                app.update();
                point(&app)
            })
        },
    ));
    out.push(Workload::lazy(
        format!("ecs/car/d{depth}/initial-curve"),
        move || {
            let mut app = app_of(false);
            let mut sign = 1.0;
            Box::new(move || {
                sign = -sign;
                let edit = AuthorEdit::RotateInitial {
                    index: 1,
                    axis: DVec3::X,
                    radians: 0.01 * sign,
                };
                ecs::send(&mut app, Edit::Author(edit));
                app.update();
                point(&app)
            })
        },
    ));
    let mirrored = presets::car1().mirrored().expect("the car mirrors");
    out.push(surface_row_named(
        mirrored,
        format!("surface/kobbelt/9x6-mirrored/d{depth}/full"),
        depth,
    ));
    out.push(Workload::lazy(
        format!("ecs/car-mirrored/d{depth}/edit-interior"),
        move || {
            let mut app = app_of(true);
            let mut sign = 1.0;
            Box::new(move || {
                let edit = wiggle(2, 4, &mut sign);
                ecs::send(&mut app, edit);
                app.update();
                point(&app)
            })
        },
    ));
    out
}

fn surface_row_named(design: Design, name: String, depth: u32) -> Workload {
    Workload {
        name,
        run: Box::new(move || {
            let b = design.build(depth).expect("valid");
            b.mesh.positions[b.mesh.positions.len() / 2].x
        }),
    }
}

/// The B-spline fit of CAD export (docs/math.md §10, docs/cad.md) on one thread:
/// the car at depth 5 (161 × 258 points, checked at depth 6's 321 × 514)
/// within the default `1e-4` of its diagonal (`fit/car/d5`, issue 21's
/// 10 ms target), the reshaped car likewise, and the car at depth 4. The
/// builds of both depths are made once, outside the timing.
pub fn fit_rows() -> Vec<Workload> {
    use streamline_kernel::nurbs::{FitOptions, Samples, fit};
    [
        ("car", presets::car1(), 5),
        ("car2", presets::car2(), 5),
        ("car", presets::car1(), 4),
    ]
    .into_iter()
    .map(|(label, design, depth)| {
        Workload::lazy(format!("fit/{label}/d{depth}"), move || {
            let data = Samples::build(&design, depth).expect("valid");
            let check = Samples::build(&design, depth + 1).expect("valid");
            Box::new(move || {
                let f = fit(&data, &check, &FitOptions::DEFAULT).expect("fits");
                f.report.deviation.max + f.report.poles.0 as f64
            })
        })
    })
    .chain(export_fit_rows())
    .collect()
}

/// CAD export's fit from the display depth (docs/math.md §10; issue 27): the
/// car shown at depth 3 fitted within the default `1e-4` of its diagonal,
/// which its depth-3 grid is too coarse for, so the fit samples deeper
/// (`cad::fit_scene`; the depth it settles on is the row's result), every
/// build included: as shipped (`export-fit/car/d3`) and after a fixed
/// pseudo-random turn of every control tangent by up to 0.1 rad
/// (`export-fit/car/d3/edited`).
fn export_fit_rows() -> Vec<Workload> {
    use crate::scene::{Scene, cad};
    let car = presets::car1();
    let mut edited = car.clone();
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let (rows, cols) = (car.net().rows(), car.net().cols());
    for r in 0..rows {
        for c in 0..cols {
            let axis = DVec3::new(next(), next(), next()).normalize_or(DVec3::Z);
            let turn = streamline_kernel::DQuat::from_axis_angle(axis, 0.1 * next());
            let t = turn * car.net().get(r, c);
            edited
                .set_tangent(r, c, t)
                .expect("a unit tangent in the net");
        }
    }
    [("car/d3", car), ("car/d3/edited", edited)]
        .into_iter()
        .map(|(label, design)| {
            let scene = Scene::from_design("car", design, 3);
            Workload {
                name: format!("export-fit/{label}"),
                run: Box::new(move || {
                    let f = cad::fit_scene(&scene, 3, &Default::default()).expect("fits");
                    f.depth as f64 + f.fit.report.deviation.max
                }),
            }
        })
        .collect()
}

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
    crate::scene::obj::read(&test_mesh_path(name))
        .expect("the checkout's test mesh reads")
        .0
}

/// Loop subdivision (the topology from the face list, then 1–3 levels, each
/// level's topology derived from the one before) of a small, a medium and the
/// largest test mesh (`loop/subdivide/<mesh>/d<k>`, 002's rule); the same for
/// a 19,730-vertex open mesh (fairing-cross subdivided once, 4 boundary loops)
/// under each boundary rule (`loop/20k/<rule>/d<k>`, issue 22: beside
/// OpenSubdiv in `docs/loop.md`); and
/// progressive interpolation to 1e-3 of a 1,151,994-vertex mesh (fertility
/// subdivided 4 times, every vertex then moved by up to 2 mean edge lengths),
/// topology included (`pi/1m/<plain|fast>`) — issue 5.
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
/// topology from the face list included (`loop/20k/<rule>/d<k>`, issue 22;
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

/// One fine-tuning control-value edit on the car at depth 3 (3×3 quadratic
/// function, paper 003's surfaces), from message to updated mesh (issue 6),
/// free and with every streamline's ends kept, beside the same app's tangent
/// edit. Rows: `tune/car/d3/<free|keep-ends>`.
pub fn fine_tuning() -> Vec<Workload> {
    use crate::ecs::{self, Edit, SurfaceData};
    use crate::scene::Scene;
    use streamline_kernel::finetune::{Constraint, SurfaceTuning};
    [
        ("free", Constraint::Free),
        ("keep-ends", Constraint::KeepEnds),
    ]
    .into_iter()
    .map(|(what, constraint)| {
        Workload::lazy(format!("tune/car/d3/{what}"), move || {
            let mut scene = Scene::from_design("car", presets::car1(), 3);
            scene.tuning = Some(SurfaceTuning {
                constraint,
                ..SurfaceTuning::identity()
            });
            let mut app = ecs::headless_app(scene);
            let mut flip = false;
            Box::new(move || {
                flip = !flip;
                let value = if flip { 1.3 } else { 0.8 };
                ecs::send(
                    &mut app,
                    Edit::SetTuningValue {
                        row: 1,
                        col: 1,
                        value,
                    },
                );
                app.update();
                app.world().resource::<SurfaceData>().points.data()[0].x
            })
        })
    })
    .collect()
}

/// Marks the patch's [`PatchStructure`](crate::ecs::patch::PatchStructure)
/// changed, so that the next update builds every level and streamline afresh.
fn force_full_build(app: &mut bevy::prelude::App) {
    use crate::ecs::patch::{PatchStructure, patch_entity};
    use bevy::prelude::DetectChangesMut;
    let w = app.world_mut();
    if let Some(mut st) = patch_entity(w).and_then(|p| w.get_mut::<PatchStructure>(p)) {
        st.set_changed();
    }
}

/// One edit through the ECS pipeline (message → blend → integrate → mesh) vs a
/// full rebuild, on the car and on a 20×20 net, at depths 3 and 5 (issue 3).
/// Rows: `ecs/<net>/d<depth>/<edit-interior|edit-corner|full>`; `full` sends
/// the blend order the design has and builds everything afresh.
pub fn incremental() -> Vec<Workload> {
    use crate::ecs::{self, Edit, SurfaceData};
    use crate::scene::Scene;
    let mut out = Vec::new();
    for (net, design, interior) in [
        ("car", presets::car1(), (2usize, 4usize)),
        ("grid20", presets::wavy(20, 20), (10, 9)),
    ] {
        for depth in [3u32, 5] {
            let cases = [
                ("edit-interior", Some(interior)),
                ("edit-corner", Some((0, 0))),
                ("full", None),
            ];
            for (what, cell) in cases {
                let design = design.clone();
                out.push(Workload::lazy(
                    format!("ecs/{net}/d{depth}/{what}"),
                    move || {
                        let order = design.order();
                        let mut app = ecs::headless_app(Scene::from_design(net, design, depth));
                        let mut sign = 1.0;
                        Box::new(move || {
                            let edit = match cell {
                                Some((row, col)) => {
                                    sign = -sign;
                                    Edit::Rotate {
                                        row,
                                        col,
                                        axis: DVec3::Y,
                                        radians: 0.01 * sign,
                                    }
                                }
                                None => Edit::SetBlendOrder(order),
                            };
                            ecs::send(&mut app, edit);
                            if cell.is_none() {
                                // the order it has changes no component, so asks
                                // for no build (issue 26): mark the patch's
                                // structure changed, as a structural edit does
                                force_full_build(&mut app);
                            }
                            app.update();
                            app.world().resource::<SurfaceData>().points.data()[0].x
                        })
                    },
                ));
            }
        }
    }
    out
}
