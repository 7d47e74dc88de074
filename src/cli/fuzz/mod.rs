//! Fuzz targets: what the libFuzzer targets in `fuzz/` (cargo-fuzz, nightly)
//! and the short fuzz run of the tests (`tests/fuzz.rs`, proptest) feed with
//! arbitrary bytes. Every target accepts any input. It panics only when an
//! invariant breaks — a panic inside our code, a NaN or infinity in a mesh or
//! a tangent, a tangent off the unit sphere, a file that does not read back
//! as itself — which is what the fuzzers look for. See `docs/reliability.md`.
//!
//! Work per input is bounded (small depths, a few iterations), so a fuzzer
//! runs thousands of inputs a second; sizes beyond the bounds are the
//! resource limits' business, tested on their own.

use crate::cli::geometry::{
    CurveArgs, CurveName, OrderName, SurfaceArgs, SurfaceName, curve_json, integrate_json,
    surface_json,
};
use crate::scene::edits::script::{Script, output::output_path};
use crate::scene::{Document, Scene, loop_mesh::obj};
use std::path::Path;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::levels::incremental::place_rows_tuned;
use streamline_kernel::loop_subdiv::mesh_interpolation::{Method, Options, interpolate};
use streamline_kernel::loop_subdiv::subdivide::{
    BoundaryRule, limit_points, subdivide as loop_subdivide,
};
use streamline_kernel::loop_subdiv::trimesh::TriMesh;
use streamline_kernel::{DVec3, Design};

mod kernel_input;
pub use kernel_input::kernel;

/// The most tangents a fuzzed scene is built with (its depth is lowered to fit).
const FUZZ_BUILD_TANGENTS: usize = 20_000;

/// Asserts every point is finite.
pub(super) fn finite(what: &str, points: &[DVec3]) {
    if let Some(p) = points.iter().find(|p| !p.is_finite()) {
        panic!("{what}: a non-finite point {p:?}");
    }
}

/// Asserts every tangent is finite and of unit length (the oracle every
/// target applies to the tangents it gets back).
pub fn unit(what: &str, tangents: &[DVec3]) {
    finite(what, tangents);
    if let Some(t) = tangents.iter().find(|t| (t.length() - 1.0).abs() > 1e-9) {
        panic!(
            "{what}: a tangent off the unit sphere {t:?} (length {})",
            t.length()
        );
    }
}

/// The scene parser, every version: arbitrary text is an error or a design
/// (version 1 or 2 as one patch, version 3 as its patches); a design's own
/// text reads back as the same design, and it builds without a NaN.
pub fn scene(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let path = Path::new("fuzz.ron");
    let Ok(doc) = Document::parse(&text, path) else {
        return;
    };
    let again = Document::parse(&doc.to_ron(), path)
        .unwrap_or_else(|e| panic!("a parsed design's own text does not parse: {e}"));
    match doc.one_scene() {
        // one patch saves as version 2, which names its patch `main`
        Some(scene) => {
            let back = again.one_scene().expect("one patch reads back as one");
            assert_eq!(
                back.to_file(),
                scene.to_file(),
                "a scene changed through save and load"
            );
            build_scene(&scene);
        }
        None => {
            assert_eq!(
                again.to_file(),
                doc.to_file(),
                "a design of several patches changed through save and load"
            );
            build_document(&doc);
        }
    }
}

/// Builds a design of several patches through its joins (its depth lowered
/// to at most [`FUZZ_BUILD_TANGENTS`] tangents in all) and checks every
/// tangent, point and seam measure. A join refused at a deeper level (a
/// side G1 tangent along the normal) is an error, not a failure.
pub fn build_document(doc: &Document) {
    let size = |d: u32| {
        doc.patches
            .iter()
            .map(|p| {
                let c = p.design.scheme().curve();
                let (mut r, mut k) = (p.design.net().rows(), p.design.net().cols());
                for _ in 0..d {
                    r = c.refined_len(r);
                    k = c.refined_len(k);
                }
                r.saturating_mul(k)
            })
            .fold(0usize, usize::saturating_add)
    };
    let mut depth = doc.display_depth;
    while depth > 0 && size(depth) > FUZZ_BUILD_TANGENTS {
        depth -= 1;
    }
    let built = match doc.build(depth) {
        Ok(b) => b,
        Err(e) if depth > 0 => {
            assert!(!e.message.is_empty(), "a build error says what is wrong");
            return;
        }
        Err(e) => panic!("a valid design does not build at depth 0: {e}"),
    };
    for stack in &built.patches {
        unit("patch tangents", stack.finest().tangents.data());
        finite("patch points", stack.finest_points().data());
    }
    for seam in &built.seams {
        let r = &seam.report;
        assert!(
            r.gap.is_finite() && r.angle_deg.is_finite() && r.curvature_dev.is_finite(),
            "a seam measure is not finite: {r:?}"
        );
    }
}

/// Builds `scene` (its depth lowered to at most [`FUZZ_BUILD_TANGENTS`]
/// tangents), fine-tuned if it says so, and checks every point and normal.
pub fn build_scene(scene: &Scene) {
    let design = scene.effective_design();
    unit("interpolated net", design.net().data());
    let mut depth = scene.display_depth;
    let c = design.scheme().curve();
    let size = |d: u32| {
        let (mut r, mut k) = (design.net().rows(), design.net().cols());
        for _ in 0..d {
            r = c.refined_len(r);
            k = c.refined_len(k);
        }
        r.saturating_mul(k)
    };
    while depth > 0 && size(depth) > FUZZ_BUILD_TANGENTS {
        depth -= 1;
    }
    let built = design
        .build(depth)
        .unwrap_or_else(|e| panic!("a valid scene does not build at depth {depth}: {e}"));
    unit("level tangents", built.level.tangents.data());
    finite("streamline points", built.points.data());
    finite("mesh normals", &built.mesh.normals);
    if let Some(tuning) = &scene.tuning {
        tune(&design, &built.level, tuning);
    }
}

/// Fine-tunes every streamline of `level` and checks the points.
fn tune(design: &Design, level: &streamline_kernel::Level, tuning: &SurfaceTuning) {
    let mut out = Vec::new();
    place_rows_tuned(
        design.initial(),
        &level.tangents,
        &level.params,
        Some(tuning),
        &mut out,
    );
    finite("fine-tuned streamlines", &out);
}

/// The script parser: arbitrary text is an error or a script whose own text
/// reads back as itself; every output path it names is refused or lies
/// inside the script's folder.
pub fn script(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let Ok(s) = Script::parse(&text, Path::new("fuzz.ron")) else {
        return;
    };
    let again = ron::to_string(&s).expect("a script serialises");
    let back = Script::parse(&again, Path::new("again.ron"))
        .unwrap_or_else(|e| panic!("a parsed script's own text does not parse: {e}\n{again}"));
    let twice = ron::to_string(&back).expect("a script serialises");
    assert_eq!(twice, again, "a script changed through its own text");
    let dir = Path::new("/fuzz/scripts");
    for step in &s.steps {
        use crate::scene::edits::script::step::Step;
        if let Step::Save(p) | Step::Export(p) = step
            && let Ok(out) = output_path(dir, p)
        {
            assert!(
                lexically_inside(dir, &out),
                "`{p}` resolved to {} outside {}",
                out.display(),
                dir.display()
            );
        }
    }
}

/// Whether `path` stays inside `dir` once `.` and `..` are resolved by hand.
fn lexically_inside(dir: &Path, path: &Path) -> bool {
    use std::path::Component;
    let Ok(rel) = path.strip_prefix(dir) else {
        return false;
    };
    let mut depth = 0i64;
    for c in rel.components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            _ => depth -= 1,
        }
        if depth < 0 {
            return false;
        }
    }
    true
}

/// The OBJ importer: arbitrary text is an error or a valid mesh, which
/// subdivides and is interpolated (a few iterations) without a NaN.
pub fn obj(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let Ok((mesh, topo)) = obj::parse(&text, Path::new("fuzz.obj")) else {
        return;
    };
    finite("OBJ vertices", &mesh.positions);
    check_mesh(&mesh, &topo);
}

/// Limit points, one Loop step and a few interpolation iterations of a valid mesh.
pub(super) fn check_mesh(mesh: &TriMesh, topo: &streamline_kernel::loop_subdiv::trimesh::Topology) {
    if mesh.faces.len() > 20_000 {
        return;
    }
    for rule in BoundaryRule::ALL {
        let mut limits = Vec::new();
        limit_points(&mesh.positions, topo, rule, &mut limits);
        finite("limit points", &limits);
        let fine = loop_subdivide(mesh, topo, rule)
            .unwrap_or_else(|e| panic!("a valid mesh does not subdivide: {e}"));
        finite("Loop subdivision", &fine.positions);
    }
    for (method, boundary) in [
        (Method::Plain, BoundaryRule::Paper),
        (Method::Fast, BoundaryRule::EdgeAndCorner),
        (Method::Fast, BoundaryRule::EdgeOnly),
    ] {
        let opts = Options {
            tolerance: 1e-6,
            max_iterations: 8,
            method,
            boundary,
        };
        let (control, report) = interpolate(mesh, topo, &opts);
        finite("interpolated control mesh", &control);
        assert!(
            report.max_error.is_finite(),
            "interpolation error is {}",
            report.max_error
        );
    }
}

/// The JSON commands (`curve`, `surface`, `integrate`): the first byte picks
/// the command and its options, the rest is the JSON on stdin.
pub fn cli_json(data: &[u8]) {
    let Some((&op, rest)) = data.split_first() else {
        return;
    };
    let (&knob, rest) = rest.split_first().unwrap_or((&0, &[]));
    let text = String::from_utf8_lossy(rest);
    let depth = u32::from(knob % 4);
    let omega = [0.0, 1.0, 2.4, -1.0, f64::NAN, 1e300][usize::from(knob / 4) % 6];
    match op % 6 {
        0..=3 => {
            let a = CurveArgs {
                scheme: [
                    CurveName::Chaikin,
                    CurveName::CubicBspline,
                    CurveName::FourPoint,
                    CurveName::Qi,
                ][usize::from(op % 4)],
                depth,
                omega,
                order: usize::from(knob % 7),
                // mostly small; now and then past the cap (refused, never allocated)
                samples: if knob >= 250 {
                    usize::MAX >> (knob - 250)
                } else {
                    usize::from(knob / 7) % 40
                },
            };
            if let Ok(out) = curve_json(&a, &text) {
                unit("curve", &to_vecs(&out));
            }
        }
        4 => {
            let a = SurfaceArgs {
                scheme: [
                    SurfaceName::Kobbelt,
                    SurfaceName::CatmullClark,
                    SurfaceName::DooSabin,
                ][usize::from(knob / 4) % 3],
                depth: depth.min(2),
                order: if knob & 0x80 == 0 {
                    OrderName::SFirst
                } else {
                    OrderName::TFirst
                },
                omega,
            };
            if let Ok(rows) = surface_json(&a, &text) {
                for r in &rows {
                    unit("surface", &to_vecs(r));
                }
            }
        }
        _ => {
            if let Ok(p) = integrate_json(&text) {
                finite("streamline", &to_vecs(&p));
            }
        }
    }
}

fn to_vecs(a: &[[f64; 3]]) -> Vec<DVec3> {
    a.iter().map(|&p| DVec3::from_array(p)).collect()
}

/// A STEP file (any bytes): an error, or faces whose surfaces evaluate to
/// finite points with a finite area and box, and whose fit (bounded: depth
/// 2, a net of at most 6 × 6) is an error or a design of unit tangents.
pub fn step(data: &[u8]) {
    reference(streamline_reference::Format::Step, "fuzz.step", data);
}

/// An IGES file (any bytes), checked as [`step`] checks a STEP file.
pub fn iges(data: &[u8]) {
    reference(streamline_reference::Format::Iges, "fuzz.igs", data);
}

/// An OBJ reference (any bytes): an error, one grid of quadrilaterals (its
/// surface checked and fitted as [`step`]'s) or a triangle mesh, whose
/// points, area and distances to a few points are finite.
pub fn reference_obj(data: &[u8]) {
    reference(streamline_reference::Format::Obj, "fuzz.obj", data);
}

/// An STL file (any bytes, binary or ASCII), checked as [`reference_obj`]
/// checks a triangle mesh.
pub fn stl(data: &[u8]) {
    reference(streamline_reference::Format::Stl, "fuzz.stl", data);
}

fn reference(format: streamline_reference::Format, name: &str, data: &[u8]) {
    use streamline_kernel::fit::{ReferenceFitOptions, fit_reference};
    let Ok(file) = streamline_reference::parse(Path::new(name), format, data.to_vec()) else {
        return;
    };
    assert!(file.metres_per_unit.is_finite() && file.metres_per_unit > 0.0);
    for (i, face) in file.faces.iter().enumerate() {
        let info = &face.info;
        assert!(
            info.area.is_finite() && info.area >= 0.0,
            "face {i}: area {}",
            info.area
        );
        if let Some([lo, hi]) = info.bbox {
            assert!(lo.iter().chain(&hi).all(|x| x.is_finite()), "face {i}: box");
        }
        if let Some(mesh) = &face.mesh {
            finite("reference mesh", mesh.positions());
            if mesh.triangles().len() <= 20_000 {
                let [lo, hi] = mesh.bbox();
                let probes = [lo, hi, (lo + hi) * 0.5, hi + (hi - lo), DVec3::ZERO];
                let index = streamline_kernel::fit::MeshIndex::new(mesh.clone());
                for d in index.distances(&probes) {
                    assert!(d.is_finite() && d >= 0.0, "face {i}: mesh distance {d}");
                }
            }
        }
        let Some(surface) = &face.surface else {
            continue;
        };
        let ([u0, u1], [v0, v1]) = surface.domain();
        let mut points = Vec::new();
        for a in 0..5 {
            for b in 0..5 {
                let (u, v) = (
                    u0 + (u1 - u0) * a as f64 / 4.0,
                    v0 + (v1 - v0) * b as f64 / 4.0,
                );
                points.extend(surface.derivatives(u, v));
            }
        }
        finite("reference surface", &points);
        let opts = ReferenceFitOptions {
            depth: 2,
            max_net: (6, 6),
            ..Default::default()
        };
        if let Ok(fit) = fit_reference(surface, &opts) {
            unit("fitted design", fit.design.net().data());
        }
    }
}
