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
use crate::scene::script::{Script, output_path};
use crate::scene::{Document, Scene, obj};
use std::path::Path;
use streamline_kernel::finetune::{Constraint, SurfaceTuning, fine_tune_into};
use streamline_kernel::levels::incremental::place_rows_tuned;
use streamline_kernel::loop_subdiv::mesh_interpolation::{Method, Options, interpolate};
use streamline_kernel::loop_subdiv::subdivide::{
    BoundaryRule, limit_points, subdivide as loop_subdivide,
};
use streamline_kernel::loop_subdiv::trimesh::TriMesh;
use streamline_kernel::{
    BlendOrder, CurveScheme, DVec3, Design, Grid, SurfaceScheme, Tangent, curve::scheme as curve,
    levels::surface, levels::tangent_interpolation as sphere_pi, sphere::blend as sphere,
};

/// The most tangents a fuzzed scene is built with (its depth is lowered to fit).
const FUZZ_BUILD_TANGENTS: usize = 20_000;

/// Asserts every point is finite.
fn finite(what: &str, points: &[DVec3]) {
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
        use crate::scene::script::Step;
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
fn check_mesh(mesh: &TriMesh, topo: &streamline_kernel::loop_subdiv::trimesh::Topology) {
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

/// Reads "nasty" numbers from bytes: each value is one control byte, and raw
/// bits when it says so; NaN, infinities, signed zeros, subnormals, huge and
/// tiny values, repeats of the previous value.
struct Numbers<'a> {
    data: &'a [u8],
    last: f64,
}

impl<'a> Numbers<'a> {
    fn new(data: &'a [u8]) -> Self {
        Numbers { data, last: 0.0 }
    }

    fn byte(&mut self) -> u8 {
        match self.data.split_first() {
            Some((&b, rest)) => {
                self.data = rest;
                b
            }
            None => 0,
        }
    }

    fn f64(&mut self) -> f64 {
        let c = self.byte();
        let x = match c % 16 {
            0 => {
                let mut b = [0u8; 8];
                for x in &mut b {
                    *x = self.byte();
                }
                f64::from_le_bytes(b)
            }
            1 => f64::NAN,
            2 => f64::INFINITY,
            3 => f64::NEG_INFINITY,
            4 => 0.0,
            5 => -0.0,
            6 => f64::MIN_POSITIVE / f64::from(1 + (c >> 4)).exp2(),
            7 => 1e300 * if c & 0x10 == 0 { 1.0 } else { -1.0 },
            8 => 1e-300 * if c & 0x10 == 0 { 1.0 } else { -1.0 },
            9 => self.last,
            10 => self.last + 1e-15,
            11 => f64::MAX,
            _ => f64::from(c >> 4) - 8.0 + f64::from(c % 16 - 12) * 0.25,
        };
        self.last = x;
        x
    }

    /// A vector: fresh, or the previous one repeated, negated (antipodal) or nudged.
    fn vec(&mut self, prev: DVec3) -> DVec3 {
        match self.byte() % 8 {
            0 => prev,
            1 => -prev,
            2 => prev + DVec3::new(1e-12, -1e-13, 1e-14),
            _ => DVec3::new(self.f64(), self.f64(), self.f64()),
        }
    }

    fn vecs(&mut self, n: usize) -> Vec<DVec3> {
        let mut out = Vec::with_capacity(n);
        let mut prev = DVec3::X;
        for _ in 0..n {
            prev = self.vec(prev);
            out.push(prev);
        }
        out
    }

    fn small(&mut self, lo: usize, hi: usize) -> usize {
        lo + usize::from(self.byte()) % (hi - lo + 1)
    }
}

fn curve_scheme(k: usize, omega: f64) -> CurveScheme {
    match k % 3 {
        0 => CurveScheme::Chaikin,
        1 => CurveScheme::CubicBSpline,
        _ => CurveScheme::FourPoint { omega },
    }
}

fn surface_scheme(k: usize, omega: f64) -> SurfaceScheme {
    match k % 3 {
        0 => SurfaceScheme::DooSabin,
        1 => SurfaceScheme::CatmullClark,
        _ => SurfaceScheme::Kobbelt { omega },
    }
}

/// The kernel's public entry points with arbitrary `f64` input: each returns
/// an error or finite (and, for tangents, unit) output.
pub fn kernel(data: &[u8]) {
    let mut n = Numbers::new(data);
    let op = n.byte();
    match op % 9 {
        0 => {
            let k = n.small(0, 2);
            let depth = n.small(0, 4) as u32;
            let omega = n.f64();
            let count = n.small(0, 24);
            let t = n.vecs(count);
            if let Ok(out) = curve::subdivide(curve_scheme(k, omega), &t, depth) {
                unit("curve subdivision", &out);
            }
        }
        1 => {
            let k = n.small(0, 2);
            let depth = n.small(0, 3) as u32;
            let omega = n.f64();
            let (rows, cols) = (n.small(1, 6), n.small(1, 6));
            let order = if n.byte().is_multiple_of(2) {
                BlendOrder::SFirst
            } else {
                BlendOrder::TFirst
            };
            let data = n.vecs(rows * cols);
            if let Ok(g) = Grid::new(rows, cols, data)
                && let Ok(out) = surface::subdivide(surface_scheme(k, omega), order, &g, depth)
            {
                unit("surface subdivision", out.data());
            }
        }
        2 => {
            let order = n.small(0, 7);
            let m = n.small(0, 64);
            let count = n.small(0, 12);
            let t = n.vecs(count);
            if let Ok(q) = streamline_kernel::curve::qi::QiCurve::new(&t, order)
                && let Ok(out) = q.sample(m)
            {
                unit("QI curve", &out);
            }
        }
        3 => {
            let count = n.small(0, 16);
            let t = n.vecs(count);
            let s: Vec<f64> = (0..n.small(0, 17)).map(|_| n.f64()).collect();
            let anchor = n.small(0, 17);
            let origin = DVec3::new(n.f64(), n.f64(), n.f64());
            if let Ok(p) =
                streamline_kernel::streamline::integrate::streamline(&t, &s, anchor, origin)
            {
                finite("streamline", &p);
            }
        }
        4 => design(&mut n),
        5 => {
            let nv = n.small(0, 12);
            let positions = n.vecs(nv);
            let nf = n.small(0, 16);
            let faces: Vec<[u32; 3]> = (0..nf)
                .map(|_| {
                    let b = n.byte();
                    let i = |x: u8| u32::from(x) % (nv as u32 + 2);
                    [i(b), i(n.byte()), i(n.byte())]
                })
                .collect();
            if let Ok((mesh, topo)) = TriMesh::new(positions, faces) {
                check_mesh(&mesh, &topo);
            }
        }
        6 => {
            let a = Tangent::new(n.vec(DVec3::X));
            let b = Tangent::new(n.vec(DVec3::Y));
            // the weight is the scheme's constant, never the user's: any number in [0, 1]
            let u = n.f64().abs() % 1.0;
            let u = if u.is_finite() { u } else { 0.5 };
            if let (Ok(a), Ok(b)) = (a, b) {
                let (a, b) = (a.get(), b.get());
                let (q1, q3) = sphere::quarters(a, b);
                let what = format!("sphere blends of {a:?} and {b:?} at {u}");
                unit(
                    &what,
                    &[
                        sphere::blend(a, b, u),
                        sphere::mid(a, b),
                        q1,
                        q3,
                        sphere::quarter(a, b),
                        sphere::three_quarters(a, b),
                    ],
                );
                let w = n.f64();
                if let Some(c) = sphere::combine(&[a, b, a], &[w, 1.0 - 2.0 * w, w]) {
                    unit("sphere combine", &[c]);
                }
            }
        }
        7 => {
            let k = n.small(0, 2);
            let (rows, cols) = (n.small(1, 6), n.small(1, 6));
            let data = n.vecs(rows * cols);
            let scheme = surface_scheme(k, 1.0);
            if let Ok(g) = Grid::new(rows, cols, data)
                && let Ok(g) = surface::normalize_grid(&g)
                && scheme.check_depth(rows, cols, 1).is_ok()
            {
                let r = sphere_pi::interpolate_net(scheme, BlendOrder::SFirst, &g, 1e-9, 20);
                unit("interpolated net", r.net.data());
            }
        }
        _ => {
            let count = n.small(2, 12);
            let t = n.vecs(count);
            let Ok(t) = streamline_kernel::sphere::tangent::normalize_all(&t) else {
                return;
            };
            let mut s = vec![0.0];
            for _ in 1..count {
                let d = n.f64().abs().min(1e6);
                s.push(s[s.len() - 1] + d.max(1e-3));
            }
            let degree = n.small(0, 5);
            let values: Vec<f64> = (0..n.small(0, 10)).map(|_| n.f64()).collect();
            let constraint = [
                Constraint::Free,
                Constraint::KeepEnds,
                Constraint::KeepClosed,
            ][n.small(0, 2)];
            if let Ok(f) = streamline_kernel::finetune::bspline::BSpline::uniform(degree, values) {
                let mut out = Vec::new();
                fine_tune_into(&t, &s, s[0], DVec3::ZERO, &f, constraint, &mut out);
                finite("fine-tuned streamline", &out);
            }
        }
    }
}

/// A design from numbers: net, parameters, anchor, initial curve; built at a small depth.
fn design(n: &mut Numbers) {
    let k = n.small(0, 2);
    let omega = n.f64();
    let (rows, cols) = (n.small(1, 5), n.small(1, 5));
    let net = n.vecs(rows * cols);
    let s: Vec<f64> = (0..rows * cols).map(|_| n.f64()).collect();
    let t: Vec<f64> = (0..rows).map(|_| n.f64()).collect();
    let anchor = n.small(0, 5);
    let init_count = n.small(0, 5);
    let init = n.vecs(init_count);
    let order = n.small(0, 5);
    let length = n.f64();
    let origin = DVec3::new(n.f64(), n.f64(), n.f64());
    let depth = n.small(0, 3) as u32;
    let Ok(net) = Grid::new(rows, cols, net) else {
        return;
    };
    let Ok(s) = Grid::new(rows, cols, s) else {
        return;
    };
    let Ok(initial) = streamline_kernel::streamline::initial_curve::InitialCurve::new(
        &init, order, length, origin,
    ) else {
        return;
    };
    let Ok(d) = Design::new(
        &net,
        s,
        t,
        anchor,
        surface_scheme(k, omega),
        BlendOrder::SFirst,
        initial,
    ) else {
        return;
    };
    if let Ok(b) = d.build(depth) {
        unit("design tangents", b.level.tangents.data());
        finite("design points", b.points.data());
        finite("design normals", &b.mesh.normals);
    }
}
