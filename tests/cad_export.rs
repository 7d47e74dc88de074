//! CAD exchange (docs/math.md §10, docs/cad.md): STEP and IGES files of the shipped
//! scenes, a Cylinder template and a mirrored design read back by OpenCascade (tests/python/check_cad.py, in the test
//! virtual environment that `scripts/setup.sh --tests` makes), scenes with
//! hostile names read back with their names, and `.glb`
//! files read back by the `gltf` crate against the OBJ of the same build;
//! Catmull–Clark and Doo–Sabin designs exported at the default tolerance.

mod common;

use std::path::{Path, PathBuf};
use streamline_kernel::authoring::Template;
use streamline_kernel::levels::surface::SurfaceScheme;
use streamline_kernel::nurbs::FitOptions;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;
use streamline_studio::scene::export::document::{
    DocumentExportSettings, DocumentExported, export_document,
};
use streamline_studio::scene::export::format::{Format, write_meshes};
use streamline_studio::scene::export::glb::GlbPart;
use streamline_studio::scene::{Document, Scene, SceneError, design::builtin, fit::surface};

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("streamline-cad-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// What the command line, scripts and the editor write for a scene: the
/// scene as a design of one patch, through `export_document`.
fn export_scene(
    scene: &Scene,
    depth: u32,
    path: &Path,
    fit: FitOptions,
) -> Result<DocumentExported, SceneError> {
    let doc = Document::from_scene(scene.clone());
    let built = doc
        .build(depth)
        .map_err(|e| SceneError::file(path, e.to_string()))?;
    let settings = DocumentExportSettings {
        depth: Some(depth),
        fit,
        colors: None,
    };
    export_document(&doc, &built, path, &settings)
}

/// The figures of a one-patch CAD export's face.
#[derive(Debug)]
struct OneFace {
    /// The depth the fit sampled.
    depth: u32,
    degree: (usize, usize),
    poles: (usize, usize),
    tolerance: f64,
    /// The largest deviation at the check grid.
    max: f64,
}

/// The one face a design of one patch writes, with its figures.
fn one_face(out: &DocumentExported) -> OneFace {
    let [f] = out.faces.as_slice() else {
        panic!("one patch writes one face, not {}", out.faces.len())
    };
    OneFace {
        depth: out.depth,
        degree: f.surface.degree(),
        poles: f.surface.pole_counts(),
        tolerance: f.tolerance,
        max: f.deviation.max,
    }
}

/// A mesh written alone, as a design of one patch's mesh is.
fn export(mesh: &SurfaceMesh, name: &str, path: &Path) -> Result<Format, SceneError> {
    let format = Format::of(path)?;
    let part = GlbPart {
        name,
        mesh,
        colors: None,
    };
    write_meshes(path, format, &[part])?;
    Ok(format)
}

fn mesh_of(scene: &Scene, depth: u32) -> SurfaceMesh {
    let s = surface::samples(scene, depth).unwrap();
    SurfaceMesh::from_points(&s.points)
}

fn write_points(path: &Path, scene: &Scene, depth: u32) {
    let s = surface::samples(scene, depth).unwrap();
    let text: String = s
        .points
        .data()
        .iter()
        .map(|p| format!("{:?} {:?} {:?}\n", p.x, p.y, p.z))
        .collect();
    std::fs::write(path, text).unwrap();
}

/// The scenes the reader checks, with their export depths: both cars at
/// their display depth (4); qi-side at 5; a Cylinder template (120° of
/// radius 0.5); car1 mirrored (docs/math.md §9), fitted as one surface over
/// both halves, at depth 5; and the exports a fit at the display depth alone
/// would refuse, which sample as deep as the default tolerance needs
/// (`surface::fit_scene`): qi-side, qi-up and car1 shown at depth 3, qi-side at
/// 4, and car1 after random turns of every control tangent at 3 and 4; and
/// car1 on Catmull–Clark and on Doo–Sabin at 4 (docs/math.md §4, "The anchor").
fn scenes() -> Vec<(&'static str, Scene, u32)> {
    let mut out: Vec<(&'static str, Scene, u32)> = ["car1", "car2", "qi-side"]
        .into_iter()
        .map(|n| {
            (
                n,
                builtin::scene(n).unwrap(),
                if n == "qi-side" { 5 } else { 4 },
            )
        })
        .collect();
    let cylinder = Scene::new_design(
        5,
        6,
        2.0,
        Template::Cylinder {
            radius: 0.5,
            degrees: 120.0,
        },
        SurfaceScheme::default(),
    )
    .unwrap();
    out.push(("cylinder", cylinder, 4));
    out.push(("car1-mirrored", mirrored("car1"), 5));
    for (label, name, depth) in [
        ("qi-side-d3", "qi-side", 3),
        ("qi-up-d3", "qi-up", 3),
        ("car1-d3", "car1", 3),
        ("qi-side-d4", "qi-side", 4),
    ] {
        out.push((label, builtin::scene(name).unwrap(), depth));
    }
    out.push(("car1-turned-d3", turned("car1", 7), 3));
    out.push(("car1-turned-d4", turned("car1", 8), 4));
    // the approximating schemes, whose rows shorten with depth
    for scheme in [SurfaceScheme::CatmullClark, SurfaceScheme::DooSabin] {
        let mut scene = builtin::scene("car1").unwrap();
        scene.design.set_scheme(scheme).unwrap();
        let name = match scheme {
            SurfaceScheme::CatmullClark => "car1-catmull-clark",
            _ => "car1-doo-sabin",
        };
        out.push((name, scene, 4));
    }
    out
}

/// A shipped scene with every control tangent turned by up to 0.1 rad
/// about a pseudo-random axis (a fixed seed: the same scene every run).
fn turned(name: &str, seed: u64) -> Scene {
    let mut scene = builtin::scene(name).unwrap();
    let mut x = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let net = scene.design.net().clone();
    for r in 0..net.rows() {
        for c in 0..net.cols() {
            let axis = streamline_kernel::DVec3::new(next(), next(), next()).normalize();
            let q = streamline_kernel::DQuat::from_axis_angle(axis, 0.1 * next());
            scene.design.set_tangent(r, c, q * net.get(r, c)).unwrap();
        }
    }
    scene
}

/// A shipped scene with the mirror on, as the editor's mirror toggle makes
/// it (row 0 moved into the plane, then doubled).
fn mirrored(name: &str) -> Scene {
    let mut scene = builtin::scene(name).unwrap();
    scene.design = scene.design.with_seam_in_plane().unwrap();
    scene.mirror = true;
    scene
}

#[test]
fn a_mirrored_scene_is_fitted_over_both_halves() {
    let half = builtin::scene("car1").unwrap();
    let both = mirrored("car1");
    let (h, b) = (
        surface::samples(&half, 5).unwrap().points,
        surface::samples(&both, 5).unwrap().points,
    );
    assert_eq!(b.cols(), h.cols());
    assert_eq!(b.rows(), 2 * h.rows() - 1, "the doubled grid");
    // independently of the kernel's mirror: the points lie on both sides of
    // the plane, and every point's reflection is a point of the grid
    let plane = both.design.mirror_plane();
    let side = |sign: f64| {
        b.data()
            .iter()
            .map(|&p| sign * plane.distance(p))
            .fold(0.0, f64::max)
    };
    assert!(
        side(1.0) > 0.1 && side(-1.0) > 0.1,
        "{} {}",
        side(1.0),
        side(-1.0)
    );
    for r in 0..b.rows() {
        for c in 0..b.cols() {
            let p = plane.reflect_point(b.get(r, c));
            let q = b.get(b.rows() - 1 - r, c);
            assert!((p - q).length() < 1e-9, "({r}, {c}): {p} vs {q}");
        }
    }
    let fit = surface::fit_scene(&both, 5, &Default::default()).unwrap();
    assert!(fit.fit.report.deviation.max <= fit.fit.report.tolerance);
}

#[test]
fn opencascade_reads_every_step_and_iges_file_we_write() {
    let dir = scratch("occ");
    let mut manifest = Vec::new();
    for (name, scene, depth) in scenes() {
        for ext in ["step", "igs"] {
            let path = dir.join(format!("{name}.{ext}"));
            let out = export_scene(&scene, depth, &path, FitOptions::default())
                .unwrap_or_else(|e| panic!("{name} at depth {depth}: {e}"));
            let r = one_face(&out);
            assert!(r.max <= r.tolerance, "{name}: {r:?}");
            assert!(r.depth >= depth, "{name}: sampled at {}", r.depth);
            eprintln!(
                "{name}.{ext}: shown at depth {depth}, sampled at {}",
                r.depth
            );
            // the points of the depth the fit sampled, and one finer
            let mut pts = serde_json::Map::new();
            for (label, d) in [("export depth", r.depth), ("one finer", r.depth + 1)] {
                let p = dir.join(format!("{name}-d{d}.xyz"));
                write_points(&p, &scene, d);
                pts.insert(label.into(), p.to_string_lossy().into());
            }
            manifest.push(serde_json::json!({
                "file": path,
                "degree": [r.degree.0, r.degree.1],
                "poles": [r.poles.0, r.poles.1],
                "tolerance": r.tolerance,
                "points": pts,
            }));
        }
    }
    let results = common::opencascade_manifest("check_cad.py", &dir, &manifest);
    for (r, m) in results.iter().zip(&manifest) {
        assert_eq!(r["file"], m["file"]);
        assert!(r.get("error").is_none() && r["valid"] == true, "{r}");
        assert_eq!(
            (&r["degree"], &r["poles"]),
            (&m["degree"], &m["poles"]),
            "{r}"
        );
        eprintln!("{r}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// What IGES holds of a name in this file's test names (scene/export/cad_text.rs):
/// its first 1000 characters in ASCII, these letters transliterated,
/// whitespace a space, anything else `?`.
fn iges_name(name: &str) -> String {
    name.chars()
        .take(1000)
        .map(|c| match c {
            ' '..='~' => c,
            '\n' | '\t' => ' ',
            'Ü' => 'U',
            'ï' => 'i',
            'ø' => 'o',
            'é' => 'e',
            _ => '?',
        })
        .collect()
}

/// A scene may be called anything. Each name below goes through
/// the export the CLI and the editor use into a STEP and an IGES file (one
/// file name hostile too); OpenCascade must read every file (one valid
/// face, degree and poles as reported) and read back, from STEP, the name
/// itself (the PRODUCT's id and name, the shape representation's, the name
/// XCAF shows, and the header's file name): its first 1000 characters, NUL
/// left out; from IGES (ASCII only) its transliteration.
#[test]
fn any_scene_name_gives_step_and_iges_files_that_opencascade_reads_with_the_name() {
    let long: String = "a');b\\ Ü🚗,".chars().cycle().take(500).collect();
    let too_long: String = "🚗é'".chars().cycle().take(1500).collect();
    let names = [
        "a');b",
        "'",
        "''",
        "\\",
        "a\\b",
        ";",
        "(",
        ")",
        "Ünïcødé 車",
        "emoji 🚗",
        "",
        "x'\" ,)",
        "ADVANCED_FACE(#99",
        "line\nbreak\ttab",
        "\\X2\\0041\\X0\\ \\S\\A",
        "END-ISO-10303-21;",
        "nul\0byte",
        &long,
        &too_long,
    ];
    let dir = scratch("names");
    let base = builtin::scene("minimal").unwrap();
    let depth = 4;
    let mut manifest = Vec::new();
    for (i, name) in names.into_iter().enumerate() {
        let mut scene = base.clone();
        scene.name = name.to_string();
        let stem = match i {
            0 => "a');b Ü 車".to_string(),
            _ => format!("name{i}"),
        };
        for ext in ["step", "igs"] {
            let file = format!("{stem}.{ext}");
            let path = dir.join(&file);
            let out = export_scene(&scene, depth, &path, FitOptions::default())
                .unwrap_or_else(|e| panic!("{name:?}: {e}"));
            let r = one_face(&out);
            let written = if ext == "step" {
                let kept: String = name.chars().take(1000).filter(|&c| c != '\0').collect();
                serde_json::json!({
                    "product id": [kept],
                    "product name": [kept],
                    "representation": [kept],
                    "xcaf": [kept],
                    "file": file,
                })
            } else {
                serde_json::json!({
                    "sender": iges_name(name),
                    "receiver": iges_name(name),
                    "file": iges_name(&file),
                })
            };
            manifest.push(serde_json::json!({
                "file": path,
                "degree": [r.degree.0, r.degree.1],
                "poles": [r.poles.0, r.poles.1],
                "tolerance": r.tolerance,
                "points": {},
                "names": written,
            }));
        }
    }
    let results = common::opencascade_manifest("check_cad.py", &dir, &manifest);
    for (r, m) in results.iter().zip(&manifest) {
        assert_eq!(r["file"], m["file"]);
        assert!(r.get("error").is_none() && r["valid"] == true, "{r}");
        assert_eq!(r["names"], m["names"], "{r}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The `v x y z` lines of an OBJ.
fn obj_positions(text: &str) -> Vec<[f64; 3]> {
    text.lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

#[test]
fn a_glb_holds_the_same_vertices_as_the_obj_of_the_same_build() {
    let dir = scratch("glb");
    for (name, scene, _) in scenes() {
        let mesh = mesh_of(&scene, scene.display_depth);
        let (glb, obj) = (
            dir.join(format!("{name}.glb")),
            dir.join(format!("{name}.obj")),
        );
        assert_eq!(export(&mesh, name, &glb).unwrap(), Format::Glb);
        export(&mesh, name, &obj).unwrap();
        let want = obj_positions(&std::fs::read_to_string(&obj).unwrap());
        let bytes = std::fs::read(&glb).unwrap();
        let g = gltf::Gltf::from_slice(&bytes).unwrap();
        let blob = g.blob.as_deref();
        let prim = g.meshes().next().unwrap().primitives().next().unwrap();
        let reader = prim.reader(|b| match b.source() {
            gltf::buffer::Source::Bin => blob,
            gltf::buffer::Source::Uri(_) => None,
        });
        let got: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
        let tris = reader.read_indices().unwrap().into_u32().count() / 3;
        assert_eq!(got.len(), want.len(), "{name}: vertex count");
        assert_eq!(normals.len(), want.len(), "{name}: one normal per vertex");
        assert_eq!(tris, mesh.triangle_count(), "{name}: triangles");
        for (i, (g, w)) in got.iter().zip(&want).enumerate() {
            for k in 0..3 {
                // f32 in the .glb: within half an f32 ulp of the f64 position
                let tol = (w[k].abs() * f64::from(f32::EPSILON)).max(1e-30);
                assert!(
                    (f64::from(g[k]) - w[k]).abs() <= tol,
                    "{name}: vertex {i}: {g:?} vs {w:?}"
                );
            }
        }
        assert!(
            reader.read_colors(0).is_none(),
            "{name}: no map, no COLOR_0"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn refused_exports_write_nothing_and_keep_the_old_file() {
    let dir = scratch("refuse");
    let scene = builtin::scene("car1").unwrap();
    for ext in ["step", "igs"] {
        let path = dir.join(format!("old.{ext}"));
        std::fs::write(&path, "the old file").unwrap();
        for (opts, want) in [
            (
                streamline_kernel::nurbs::FitOptions {
                    degree: (3, 3),
                    tolerance: streamline_kernel::nurbs::Tolerance::Absolute(0.0),
                },
                "positive finite",
            ),
            (
                streamline_kernel::nurbs::FitOptions {
                    degree: (6, 3),
                    tolerance: streamline_kernel::nurbs::Tolerance::Relative(1e-4),
                },
                "outside 2 to 5",
            ),
            (
                streamline_kernel::nurbs::FitOptions {
                    degree: (3, 3),
                    tolerance: streamline_kernel::nurbs::Tolerance::Relative(1e-9),
                },
                "the deepest an export samples (the closest it came was",
            ),
        ] {
            let e = export_scene(&scene, 2, &path, opts).unwrap_err();
            assert!(
                e.message.contains(want) && e.message.contains("nothing was written"),
                "{ext}: {e}"
            );
            assert_eq!(std::fs::read_to_string(&path).unwrap(), "the old file");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The points the fit sees are the surface the editor shows: multiresolution
/// details and fine tuning included (the ECS pipeline's points, to rounding).
#[test]
fn the_fitted_points_are_the_edited_surface() {
    use streamline_studio::ecs::{self, Edit, SurfaceData};
    for name in ["car1", "car1-tuned"] {
        let mut app = ecs::headless_app(builtin::scene(name).unwrap());
        for edit in [
            Edit::SetEditDepth(1),
            Edit::Rotate {
                row: 5,
                col: 8,
                axis: streamline_kernel::DVec3::Z,
                radians: 0.4,
            },
            Edit::SetDisplayDepth(3),
        ] {
            ecs::apply(&mut app, edit).unwrap();
        }
        let scene = ecs::patch::scene(app.world());
        assert_eq!(scene.details.len(), 1, "{name}: one detail");
        let ecs_points = app.world().resource::<SurfaceData>().points.clone();
        let ours = surface::samples(&scene, 3).unwrap().points;
        assert_eq!(
            (ours.rows(), ours.cols()),
            (ecs_points.rows(), ecs_points.cols())
        );
        let worst = ours
            .data()
            .iter()
            .zip(ecs_points.data())
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, f64::max);
        assert!(worst < 1e-12, "{name}: {worst:e}");
    }
}

/// A design on an approximating scheme exports at the default tolerance:
/// its rows anchored at their limit start and its check grid measured in
/// its data's frame (docs/math.md §4, "The anchor"; §10), the surface stays
/// put between depths. The car turned Catmull–Clark and Doo–Sabin, every
/// face within the tolerance at the depth it was sampled; the kernel's
/// `approximating_drift` holds the negative controls (each grid in its own
/// frame is refused).
#[test]
fn a_catmull_clark_or_doo_sabin_design_exports_at_the_default_tolerance() {
    let dir = scratch("approximating");
    let car = || Document::from_scene(builtin::scene("car1").unwrap());
    for scheme in [SurfaceScheme::CatmullClark, SurfaceScheme::DooSabin] {
        let doc = turn(car(), scheme);
        let built = doc.build(doc.display_depth).unwrap();
        let path = dir.join(format!("car-{}.step", scheme.name()));
        let out = export_document(&doc, &built, &path, &DocumentExportSettings::default())
            .unwrap_or_else(|e| panic!("{}: {e}", scheme.name()));
        assert!(path.exists(), "{}: nothing written", scheme.name());
        let r = one_face(&out);
        assert!(r.max <= r.tolerance, "{}: {r:?}", scheme.name());
        // the depth shown, or one deeper (Doo–Sabin's car)
        assert!(
            r.depth <= doc.display_depth + 1,
            "{}: sampled at {}",
            scheme.name(),
            r.depth
        );
        eprintln!(
            "car {}: within {:.3e} of {:.3e} at depth {}, {} × {} poles",
            scheme.name(),
            r.max,
            r.tolerance,
            r.depth,
            r.poles.0,
            r.poles.1
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A document with every patch on `scheme`.
fn turn(mut doc: Document, scheme: SurfaceScheme) -> Document {
    for p in &mut doc.patches {
        p.design.set_scheme(scheme).unwrap();
    }
    doc
}

/// A side patch whose rows run past the end of its parent's streamline,
/// which an approximating scheme shortens as it is sampled deeper, is
/// refused saying so (hood-screen-wing turned Catmull–Clark, its screen G1).
#[test]
fn a_side_row_past_its_parent_s_shortened_streamline_is_refused_saying_so() {
    use streamline_studio::scene::design::document::Start;
    use streamline_studio::scene::design::document_io::load;
    let dir = scratch("moving");
    let mut doc = turn(
        load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron")).unwrap(),
        SurfaceScheme::CatmullClark,
    );
    for p in &mut doc.patches {
        if let Start::Edge { join, .. } = &mut p.start {
            join.continuity = streamline_kernel::joins::Continuity::G1;
        }
    }
    let built = doc.build(doc.display_depth).unwrap();
    let refused = export_document(
        &doc,
        &built,
        &dir.join("side-past-the-end.step"),
        &DocumentExportSettings::default(),
    )
    .expect_err("a side row past its parent's streamline exported")
    .to_string();
    eprintln!("hood-screen-wing, Catmull–Clark, G1: {refused}");
    assert!(
        refused.contains("past the end of the earlier patch's Last streamline"),
        "{refused}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
