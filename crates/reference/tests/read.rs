//! The fixtures of tests/data read as OpenCascade reads them
//! (expected.json, written by make_fixtures.py), and the files the
//! project's own exporter writes.

use serde_json::Value;
use std::path::{Path, PathBuf};
use streamline_kernel::DVec3;
use streamline_kernel::nurbs::rational::NurbsSurface;
use streamline_reference::{Format, ReferenceFile, SurfaceKind, read};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn load(name: &str) -> ReferenceFile {
    read(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn expected() -> serde_json::Map<String, Value> {
    let text = std::fs::read_to_string(data("expected.json")).expect("expected.json");
    match serde_json::from_str(&text).expect("expected.json is JSON") {
        Value::Object(m) => m,
        _ => panic!("expected.json is not an object"),
    }
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

fn point(v: &Value) -> DVec3 {
    let f = floats(v);
    DVec3::new(f[0], f[1], f[2])
}

/// |a − b| relative to the larger of |b| and the fixtures' size (1 m).
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1.0)
}

fn rel3(a: DVec3, b: DVec3) -> f64 {
    (a - b).abs().max_element() / b.abs().max_element().max(1.0)
}

/// The largest differences of one face from OpenCascade's description:
/// (knots, poles, weights, evaluated points).
fn compare(name: &str, s: &NurbsSurface, e: &Value) -> [f64; 4] {
    let degrees: Vec<usize> = floats(&e["degrees"]).iter().map(|&d| d as usize).collect();
    let (p, q) = s.degrees();
    assert_eq!(vec![p, q], degrees, "{name}: degrees");
    let mut err = [0.0f64; 4];
    for (mine, theirs) in [(s.knots_u(), &e["knots_u"]), (s.knots_v(), &e["knots_v"])] {
        let theirs = floats(theirs);
        assert_eq!(mine.len(), theirs.len(), "{name}: knot count");
        for (a, b) in mine.iter().zip(&theirs) {
            err[0] = err[0].max(rel(*a, *b));
        }
    }
    let rows = e["poles"].as_array().expect("pole rows");
    let (nu, nv) = s.pole_counts();
    assert_eq!(rows.len(), nv, "{name}: pole rows (v)");
    for (j, row) in rows.iter().enumerate() {
        let row = row.as_array().expect("a pole row");
        assert_eq!(row.len(), nu, "{name}: pole columns (u)");
        for (i, pole) in row.iter().enumerate() {
            err[1] = err[1].max(rel3(s.poles().get(j, i), point(pole)));
        }
    }
    match (&e["weights"], s.weights()) {
        (Value::Null, None) => {}
        (Value::Array(rows), Some(w)) => {
            for (j, row) in rows.iter().enumerate() {
                for (i, x) in floats(row).iter().enumerate() {
                    err[2] = err[2].max(rel(w.get(j, i), *x));
                }
            }
        }
        (theirs, mine) => panic!("{name}: weights {theirs:?} vs {:?}", mine.is_some()),
    }
    for pt in e["points"].as_array().expect("points") {
        let (u, v) = (pt["u"].as_f64().unwrap(), pt["v"].as_f64().unwrap());
        err[3] = err[3].max(rel3(s.point(u, v), point(&pt["point"])));
    }
    err
}

#[test]
fn every_fixture_reads_as_opencascade_reads_it() {
    let mut worst = [0.0f64; 4];
    let expected = expected();
    assert_eq!(expected.len(), 11, "expected.json lists the 11 fixtures");
    for (name, faces) in &expected {
        let file = load(name);
        let faces = faces.as_array().expect("faces");
        assert_eq!(file.faces.len(), faces.len(), "{name}: face count");
        let format = if name.ends_with(".step") {
            Format::Step
        } else {
            Format::Iges
        };
        assert_eq!(file.format, format);
        for (k, (face, e)) in file.faces.iter().zip(faces).enumerate() {
            let kind = match e["kind"].as_str().expect("kind") {
                "bspline" => SurfaceKind::BSpline,
                "rational" => SurfaceKind::Rational,
                "plane" => SurfaceKind::Plane,
                _ => SurfaceKind::Other,
            };
            assert_eq!(face.info.kind, kind, "{name} face {k}: kind");
            assert_eq!(face.info.index, k);
            if matches!(kind, SurfaceKind::BSpline | SurfaceKind::Rational) {
                let s = file.surface(k).unwrap_or_else(|e| panic!("{e}"));
                let err = compare(&format!("{name} face {k}"), s, e);
                for i in 0..4 {
                    worst[i] = worst[i].max(err[i]);
                }
                let (p, q) = s.degrees();
                assert_eq!(face.info.degrees, Some([p, q]));
                let (a, b) = s.pole_counts();
                assert_eq!(face.info.poles, Some([a, b]));
            } else {
                assert!(face.surface.is_none());
                assert_eq!(face.info.degrees, None);
            }
        }
    }
    eprintln!(
        "largest relative differences from OpenCascade: knots {:.1e}, poles {:.1e}, weights {:.1e}, evaluated points {:.1e}",
        worst[0], worst[1], worst[2], worst[3]
    );
    assert!(worst[0] <= 1e-12, "knots differ by {:e}", worst[0]);
    assert!(worst[1] <= 1e-9, "poles differ by {:e}", worst[1]);
    assert!(worst[2] <= 1e-12, "weights differ by {:e}", worst[2]);
    assert!(worst[3] <= 1e-9, "points differ by {:e}", worst[3]);
}

#[test]
fn units_millimetre_and_inch_give_the_same_metres() {
    for (name, unit, mpu) in [
        ("bicubic.step", "metre", 1.0),
        ("bicubic-mm.step", "millimetre", 0.001),
        ("bicubic-inch.step", "inch", 0.0254),
        ("bicubic.igs", "metre", 1.0),
        ("bicubic-mm.igs", "millimetre", 0.001),
        ("bicubic-inch.igs", "inch", 0.0254),
    ] {
        let f = load(name);
        assert_eq!(f.unit, unit, "{name}");
        assert!(
            (f.metres_per_unit - mpu).abs() <= 1e-15,
            "{name}: {}",
            f.metres_per_unit
        );
    }
    let mut worst = 0.0f64;
    for (a, b) in [
        ("bicubic.step", "bicubic-mm.step"),
        ("bicubic.step", "bicubic-inch.step"),
        ("bicubic.igs", "bicubic-mm.igs"),
        ("bicubic.igs", "bicubic-inch.igs"),
        // IGES carries about ten significant digits, STEP thirteen
        ("bicubic.step", "bicubic.igs"),
    ] {
        let (fa, fb) = (load(a), load(b));
        let (sa, sb) = (fa.surface(0).unwrap(), fb.surface(0).unwrap());
        assert_eq!(sa.pole_counts(), sb.pole_counts());
        for (x, y) in sa.poles().data().iter().zip(sb.poles().data()) {
            worst = worst.max(rel3(*y, *x));
        }
    }
    eprintln!("largest pole difference between units and formats: {worst:.1e} (relative to 1 m)");
    assert!(worst <= 1e-9, "{worst:e}");
}

#[test]
fn trimmed_faces_are_flagged_and_whole_ones_not() {
    for name in ["trimmed.step", "trimmed.igs"] {
        let f = load(name);
        assert_eq!(f.faces.len(), 1);
        assert!(f.faces[0].info.trimmed, "{name} is trimmed");
    }
    for name in [
        "bicubic.step",
        "bicubic-mm.step",
        "bicubic-inch.step",
        "cylinder.step",
        "bicubic.igs",
        "bicubic-mm.igs",
        "bicubic-inch.igs",
        "cylinder.igs",
    ] {
        let f = load(name);
        assert!(!f.faces[0].info.trimmed, "{name} is not trimmed");
    }
    let two = load("two-faces.step");
    assert!(!two.faces[0].info.trimmed);
    assert!(two.faces[1].info.trimmed, "a plane has no sides of its own");
}

#[test]
fn two_faces_has_the_plane_second() {
    let f = load("two-faces.step");
    assert_eq!(f.faces.len(), 2);
    assert_eq!(f.faces[0].info.kind, SurfaceKind::BSpline);
    let plane = &f.faces[1].info;
    assert_eq!(plane.kind, SurfaceKind::Plane);
    assert!(plane.entity.ends_with(" PLANE"), "{}", plane.entity);
    assert_eq!(plane.degrees, None);
    assert_eq!(plane.poles, None);
    // the rectangle [0, 1] × [0, 0.9] at z = -0.5
    assert!((plane.area - 0.9).abs() < 1e-12, "{}", plane.area);
    let [lo, hi] = plane.bbox.expect("the plane's vertices");
    for (a, b) in lo
        .iter()
        .zip([0.0, 0.0, -0.5])
        .chain(hi.iter().zip([1.0, 0.9, -0.5]))
    {
        assert!((a - b).abs() < 1e-12, "{lo:?} {hi:?}");
    }
}

#[test]
fn area_and_box_come_from_the_surface() {
    let f = load("cylinder.step");
    let info = &f.faces[0].info;
    assert_eq!(info.kind, SurfaceKind::Rational);
    // a quarter of a cylinder of radius 0.5 and height 1
    let exact = std::f64::consts::PI / 4.0;
    eprintln!(
        "quarter cylinder area {} (error {:.1e})",
        info.area,
        (info.area - exact).abs()
    );
    assert!((info.area - exact).abs() < 1e-9, "{}", info.area);
    let [lo, hi] = info.bbox.unwrap();
    for (a, b) in lo
        .iter()
        .zip([0.0; 3])
        .chain(hi.iter().zip([0.5, 1.0, 0.5]))
    {
        assert!((a - b).abs() < 1e-9, "{lo:?} {hi:?}");
    }
    // the bicubic patch: its box lies inside its poles' box
    let f = load("bicubic.step");
    let [lo, hi] = f.faces[0].info.bbox.unwrap();
    let [plo, phi] = f.surface(0).unwrap().pole_bounds();
    for k in 0..3 {
        assert!(lo[k] >= plo[k] - 1e-12 && hi[k] <= phi[k] + 1e-12);
    }
    assert!(f.faces[0].info.area > 0.9, "{}", f.faces[0].info.area);
}

#[test]
fn closed_and_periodic_flags() {
    for name in expected().keys() {
        for face in load(name).faces {
            assert_eq!(face.info.closed, [false, false], "{name}");
            assert_eq!(face.info.periodic, [false, false], "{name}");
        }
    }
    let text = std::fs::read_to_string(data("bicubic.step")).unwrap();
    let closed = text.replace(
        ".UNSPECIFIED.,.F.,.F.,.F.,(4,1,4)",
        ".UNSPECIFIED.,.T.,.F.,.F.,(4,1,4)",
    );
    assert_ne!(closed, text);
    let dir = scratch();
    let p = dir.join("closed.step");
    std::fs::write(&p, closed).unwrap();
    assert_eq!(read(&p).unwrap().faces[0].info.closed, [true, false]);
    // uniform knots that are not clamped: periodic in u
    let periodic = text.replace(
        "(4,1,4),(4,4),(0.,0.4,1.),(0.,2.)",
        "(1,1,1,1,1,1,1,1,1),(4,4),(0.,1.,2.,3.,4.,5.,6.,7.,8.),(0.,2.)",
    );
    assert_ne!(periodic, text);
    let p = dir.join("periodic.step");
    std::fs::write(&p, periodic).unwrap();
    let f = read(&p).unwrap();
    assert_eq!(f.faces[0].info.periodic, [true, false]);
    assert!(f.faces[0].info.trimmed, "its corners are not its vertices");
}

fn scratch() -> PathBuf {
    let d = std::env::temp_dir().join(format!("streamline-reference-read-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn surface_refuses_a_face_past_the_end_or_not_a_bspline() {
    let f = load("two-faces.step");
    let e = f.surface(99).unwrap_err();
    assert_eq!(
        e.message,
        "there is no face 99: the file has 2 faces (0 and 1); choose one with --face"
    );
    assert_eq!(
        e.to_string(),
        format!(
            "{}: there is no face 99: the file has 2 faces (0 and 1); choose one with --face",
            data("two-faces.step").display()
        )
    );
    let e = f.surface(1).unwrap_err();
    assert!(e.is_located());
    assert_eq!(e.line, f.faces[1].info.line);
    assert!(
        e.message.contains("face 1 (#")
            && e.message
                .contains("PLANE) is a plane, not a B-spline surface")
            && e.message.contains("--face (face 0)"),
        "{e}"
    );
    let one = load("bicubic.igs");
    assert!(
        one.surface(1)
            .unwrap_err()
            .message
            .contains("the file has 1 face (0)")
    );
    assert!(one.surface(0).is_ok());
}

#[test]
fn infos_serialize_with_lowercase_kinds() {
    let f = load("two-faces.step");
    let json = serde_json::to_value(f.infos()).unwrap();
    assert_eq!(json[0]["kind"], "bspline");
    assert_eq!(json[1]["kind"], "plane");
    assert_eq!(json[0]["degrees"], serde_json::json!([3, 3]));
    assert_eq!(json[0]["poles"], serde_json::json!([5, 4]));
    assert_eq!(json[1]["poles"], Value::Null);
    let c = load("cylinder.igs");
    assert_eq!(
        serde_json::to_value(c.infos()).unwrap()[0]["kind"],
        "rational"
    );
    assert_eq!(c.faces[0].info.entity, "DE 3 (128)");
    assert_eq!(serde_json::to_value(Format::Iges).unwrap(), "iges");
    let b = load("bicubic.step");
    assert_eq!(b.faces[0].info.entity, "#33 B_SPLINE_SURFACE_WITH_KNOTS");
    assert_eq!(b.faces[0].info.line, 46);
    let r = load("cylinder.step");
    assert_eq!(
        r.faces[0].info.entity,
        "#31 (B_SPLINE_SURFACE_WITH_KNOTS RATIONAL_B_SPLINE_SURFACE)"
    );
}

#[test]
fn format_comes_from_the_extension() {
    use streamline_reference::Format;
    assert_eq!(
        Format::from_path(Path::new("a/B.STP")).unwrap(),
        Format::Step
    );
    assert_eq!(Format::from_path(Path::new("b.P21")).unwrap(), Format::Step);
    assert_eq!(
        Format::from_path(Path::new("c.Iges")).unwrap(),
        Format::Iges
    );
    assert_eq!(
        Format::from_path(Path::new("scan.OBJ")).unwrap(),
        Format::Obj
    );
    assert_eq!(
        Format::from_path(Path::new("scan.Stl")).unwrap(),
        Format::Stl
    );
    let e = Format::from_path(Path::new("mesh.ply")).unwrap_err();
    assert!(
        e.message.contains(".ply")
            && e.message.contains(".stl")
            && e.message.contains(".step, .stp, .p21")
            && e.message.contains(".igs, .iges")
            && e.message.contains(".obj"),
        "{e}"
    );
    assert!(Format::from_path(Path::new("noext")).is_err());
}

/// The project's exporter (`streamline-studio build car1 --depth 3 --export
/// …`, src/scene/export/step.rs and src/scene/export/iges.rs) writes one B-spline face in
/// metres: both files read, as the same surface.
#[test]
fn the_projects_own_exports_read() {
    let mut surfaces = Vec::new();
    for name in ["car1-streamline.step", "car1-streamline.igs"] {
        let f = load(name);
        assert_eq!(f.unit, "metre", "{name}");
        assert_eq!(f.metres_per_unit, 1.0);
        assert_eq!(f.faces.len(), 1, "{name}");
        let info = &f.faces[0].info;
        assert_eq!(info.kind, SurfaceKind::BSpline, "{name}");
        assert!(!info.trimmed, "{name}");
        assert_eq!(info.degrees, Some([3, 3]));
        let [lo, hi] = info.bbox.unwrap();
        let size: Vec<f64> = (0..3).map(|k| hi[k] - lo[k]).collect();
        eprintln!(
            "{name}: {} poles, box {lo:?} – {hi:?}, area {:.4} m²",
            {
                let [a, b] = info.poles.unwrap();
                format!("{a} × {b}")
            },
            info.area
        );
        // a car body: about 4 m long, 2 m wide, a metre high
        assert!(
            size.iter().all(|s| s.is_finite() && *s > 0.05 && *s < 5.0),
            "{size:?}"
        );
        let [plo, phi] = f.surface(0).unwrap().pole_bounds();
        for k in 0..3 {
            assert!(lo[k] >= plo[k] - 1e-9 && hi[k] <= phi[k] + 1e-9);
        }
        assert!(info.area > 0.0 && info.area.is_finite());
        surfaces.push(f.surface(0).unwrap().clone());
    }
    let (a, b) = (&surfaces[0], &surfaces[1]);
    assert_eq!(a.pole_counts(), b.pole_counts());
    assert_eq!(a.knots_u(), b.knots_u());
    for (x, y) in a.poles().data().iter().zip(b.poles().data()) {
        assert!((*x - *y).length() < 1e-12);
    }
}

/// An IGES file of `entities` (type, parameters without the type,
/// transformation matrix DE), in metres: fixed columns as IGES 5.3 lays
/// them out.
fn iges(entities: &[(i64, String, usize)]) -> String {
    let mut out = String::new();
    out += &format!("{:<72}S{:>7}\n", "reference reader test", 1);
    let global = ",,4HTest,8Htest.igs,4HTest,4HTest,32,38,6,308,15,4HTest,1.,6,1HM,1,0.001,15H20260101.000000,1E-07,10.,4Htest,4Htest,11,0,15H20260101.000000;";
    let g: Vec<String> = global
        .as_bytes()
        .chunks(72)
        .map(|c| String::from_utf8(c.to_vec()).unwrap())
        .collect();
    for (i, c) in g.iter().enumerate() {
        out += &format!("{c:<72}G{:>7}\n", i + 1);
    }
    let mut p_lines = Vec::new();
    let mut d = String::new();
    for (k, (ty, params, transform)) in entities.iter().enumerate() {
        let de = 2 * k + 1;
        let text = format!("{ty},{params};");
        let start = p_lines.len() + 1;
        for chunk in text.as_bytes().chunks(64) {
            p_lines.push((String::from_utf8(chunk.to_vec()).unwrap(), de));
        }
        let count = p_lines.len() + 1 - start;
        d += &format!(
            "{ty:>8}{start:>8}{:>8}{:>8}{:>8}{:>8}{transform:>8}{:>8}{:>8}D{de:>7}\n",
            0, 0, 0, 0, 0, "00000000"
        );
        d += &format!(
            "{ty:>8}{:>8}{:>8}{count:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}\n",
            0,
            0,
            0,
            "",
            "",
            "",
            0,
            de + 1
        );
    }
    out += &d;
    for (i, (chunk, de)) in p_lines.iter().enumerate() {
        out += &format!("{chunk:<64}{de:>8}P{:>7}\n", i + 1);
    }
    out += &format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}{:>40}T{:>7}\n",
        1,
        g.len(),
        2 * entities.len(),
        p_lines.len(),
        "",
        1
    );
    out
}

/// The parameters (after the type) of the bicubic patch's entity 128.
fn bicubic_128() -> String {
    let text = std::fs::read_to_string(data("bicubic.igs")).unwrap();
    let p: String = text
        .lines()
        .filter(|l| l.len() >= 73 && &l[72..73] == "P" && l[64..72].trim().parse() == Ok(3))
        .map(|l| &l[..64])
        .collect();
    let p = p.trim().trim_end_matches(';');
    p.strip_prefix("128,").unwrap().to_string()
}

fn read_iges(name: &str, entities: &[(i64, String, usize)]) -> ReferenceFile {
    let p = scratch().join(name);
    std::fs::write(&p, iges(entities)).unwrap();
    read(&p).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn iges_faces_510_and_transforms() {
    let s = bicubic_128();
    // the builder's lone 128 reads as the fixture's
    let lone = read_iges("lone.igs", &[(128, s.clone(), 0)]);
    let fixture = load("bicubic.igs");
    assert_eq!(lone.surface(0).unwrap(), fixture.surface(0).unwrap());
    assert!(!lone.faces[0].info.trimmed);
    // a face (510) whose one loop (508) runs through the four corners
    let corners = "4,0.,0.,0.,1.,0.,-8.834546557E-02,1.,0.9,0.325043662,0.,0.9,8.632093666E-02";
    let face = |corners: &str, loops: &str| {
        vec![
            (128, s.clone(), 0),                                          // DE 1
            (502, corners.to_string(), 0),                                // DE 3
            (504, "4,0,3,1,3,2,0,3,2,3,3,0,3,3,3,4,0,3,4,3,1".into(), 0), // DE 5
            (508, "4,0,5,1,1,0,0,5,2,1,0,0,5,3,1,0,0,5,4,1,0".into(), 0), // DE 7
            (510, format!("1,{loops}"), 0),                               // DE 9
        ]
    };
    let f = read_iges("face.igs", &face(corners, "1,1,7"));
    assert_eq!(f.faces.len(), 1, "the 510 and its 128 are one face");
    assert_eq!(f.faces[0].info.entity, "DE 1 (128)");
    assert!(!f.faces[0].info.trimmed);
    // a vertex off the corners, or a second loop: trimmed
    let off = corners.replacen("1.,0.9,", "0.5,0.9,", 1);
    assert!(
        read_iges("off.igs", &face(&off, "1,1,7")).faces[0]
            .info
            .trimmed
    );
    assert!(
        read_iges("two.igs", &face(corners, "2,1,7,7")).faces[0]
            .info
            .trimmed
    );
    // a 144 on the same patch: no boundary, an outer boundary along the
    // domain's sides (a 142 over a 102 of 110 lines), or a hole
    let sides = |n2: &str| {
        vec![
            (128, s.clone(), 0),                      // DE 1
            (110, "0.,0.,0.,1.,0.,0.".into(), 0),     // DE 3
            (110, "1.,0.,0.,1.,2.,0.".into(), 0),     // DE 5
            (110, "1.,2.,0.,0.,2.,0.".into(), 0),     // DE 7
            (110, "0.,2.,0.,0.,0.,0.".into(), 0),     // DE 9
            (102, "4,3,5,7,9".into(), 0),             // DE 11
            (142, "0,1,11,0,1".into(), 0),            // DE 13
            (110, "0.2,0.5,0.,0.6,0.5,0.".into(), 0), // DE 15: inside
            (142, "0,1,15,0,1".into(), 0),            // DE 17
            (
                144,
                format!("1,1,{n2},13{}", if n2 == "1" { ",17" } else { "" }),
                0,
            ), // DE 19
        ]
    };
    let f = read_iges("outer.igs", &sides("0"));
    assert_eq!(f.faces.len(), 1);
    assert!(
        !f.faces[0].info.trimmed,
        "the outer boundary is the domain's"
    );
    assert!(read_iges("hole.igs", &sides("1")).faces[0].info.trimmed);
    let mut inner = sides("0");
    inner[6].1 = "0,1,15,0,1".into(); // the outer boundary inside the domain
    assert!(read_iges("inside.igs", &inner).faces[0].info.trimmed);
    // a transformation matrix (124) moves the poles: by (1, 2, 3) m, then
    // through the matrix's own matrix, a half turn about z
    let moved = read_iges(
        "moved.igs",
        &[
            (124, "-1.,0.,0.,0.,0.,-1.,0.,0.,0.,0.,1.,0.".into(), 0), // DE 1
            (124, "1.,0.,0.,1.,0.,1.,0.,2.,0.,0.,1.,3.".into(), 1),   // DE 3
            (128, s.clone(), 3),                                      // DE 5
        ],
    );
    assert_eq!(moved.faces.len(), 1);
    let (a, b) = (moved.surface(0).unwrap(), fixture.surface(0).unwrap());
    for (x, y) in a.poles().data().iter().zip(b.poles().data()) {
        let want = DVec3::new(-(y.x + 1.0), -(y.y + 2.0), y.z + 3.0);
        assert!((*x - want).length() < 1e-12, "{x} vs {want}");
    }
}
