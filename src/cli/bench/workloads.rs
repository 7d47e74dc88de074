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
    /// Timed one run at a time, each after other work has left the caches
    /// cold ([`super::evict_caches`]), as the software renderer's frame
    /// leaves them between two of the editor's (`bench` only; criterion
    /// times the run warm).
    pub cold: bool,
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
            cold: false,
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
        cold: false,
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
        cold: false,
        run: Box::new(move || {
            out.clear();
            let m = (samples - 1) as f64;
            out.extend((0..samples).map(|j| q.tangent(j as f64 / m)));
            out[samples / 2].x
        }),
    }
}

fn surface_row(design: Design, label: &str, depth: u32) -> Workload {
    surface_row_named(
        design,
        format!("surface/kobbelt/{label}/d{depth}/full"),
        depth,
    )
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

/// Full builds of the car at `depth` into a kept [`Builder`] (buffers reused,
/// every entry recomputed; the 0.5 ms target of docs/benchmarks.md) on one
/// thread: with the CPU's widest vector path, with AVX2 at most, and scalar
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
            cold: false,
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

/// A full build of `design` at `depth`, as the row `name`.
pub(super) fn surface_row_named(design: Design, name: String, depth: u32) -> Workload {
    Workload {
        name,
        cold: false,
        run: Box::new(move || {
            let b = design.build(depth).expect("valid");
            b.mesh.positions[b.mesh.positions.len() / 2].x
        }),
    }
}

/// The B-spline fit of CAD export (docs/math.md §10, docs/cad.md) on one thread:
/// the car at depth 5 (161 × 258 points, checked at depth 6's 321 × 514)
/// within the default `1e-4` of its diagonal (`fit/car/d5`, against a
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

/// CAD export's fit from the display depth (docs/math.md §10): the
/// car shown at depth 3 fitted within the default `1e-4` of its diagonal,
/// which its depth-3 grid is too coarse for, so the fit samples deeper
/// (`surface::fit_scene`; the depth it settles on is the row's result), every
/// build included: as shipped (`export-fit/car/d3`) and after a fixed
/// pseudo-random turn of every control tangent by up to 0.1 rad
/// (`export-fit/car/d3/edited`).
fn export_fit_rows() -> Vec<Workload> {
    use crate::scene::{Scene, fit::surface};
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
                cold: false,
                run: Box::new(move || {
                    let f = surface::fit_scene(&scene, 3, &Default::default()).expect("fits");
                    f.depth as f64 + f.fit.report.deviation.max
                }),
            }
        })
        .collect()
}
