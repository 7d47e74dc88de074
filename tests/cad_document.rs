//! Export of a design of several patches (docs/cad.md, "Several patches";
//! docs/math.md §9, §11) through `scene::export::document::export_document`,
//! on the shipped `scenes/hood-screen-wing.ron` (a G2 chain and a G1 side
//! join), as it is and mirrored (its first streamline projected into the
//! mirror plane, as turning the mirror on does), read back by outside
//! readers: OpenCascade (tests/python/check_shell.py) for STEP and IGES, the
//! `gltf` crate and the Khronos glTF validator (npm `gltf-validator`,
//! tests/node/validate_glb.js, installed by `scripts/setup.sh --tests`) for
//! `.glb`, `tobj` for OBJ. The mirror's reflections are checked against the
//! plane's formula computed here from the file's initial curve.

mod common;

use common::shell_read::{point_file, seam_angle, shell_as_it_lies, valid_within};

use glam::DVec3;
use std::path::{Path, PathBuf};
use std::process::Command;
use streamline_kernel::Design;
use streamline_kernel::grid::Grid;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;
use streamline_studio::scene::design::document::{Document, Start};
use streamline_studio::scene::design::document_io::load;
use streamline_studio::scene::design::document_mirror::mirrored;
use streamline_studio::scene::export::document::{
    DocumentExportSettings, DocumentExported, export_document, turned,
};
use streamline_studio::scene::export::format::{Format, write_meshes};
use streamline_studio::scene::export::glb::{GlbPart, glb_parts_bytes};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("streamline-doc-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn hood_screen_wing() -> Document {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
    load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The design with a new net (same parameters, scheme, order and initial curve).
fn with_net(d: &Design, net: Grid<DVec3>) -> Design {
    Design::new(
        &net,
        d.params().s.clone(),
        d.params().t.clone(),
        d.anchor(),
        d.scheme(),
        d.order(),
        d.initial().clone(),
    )
    .unwrap()
}

/// The shipped design mirrored: the hood's row 0 projected into its mirror
/// plane (what turning the mirror on does), and the screen's too (the G2
/// chain is one net, so the hood's first streamline stays in the plane only
/// if the screen's row 0 is in it as well), its seam tangent the hood's.
fn mirrored_doc() -> Document {
    let mut doc = hood_screen_wing();
    doc.mirror = true;
    let (_, n) = plane(&doc);
    let hood = doc.patches[0].design.with_seam_in_plane().unwrap();
    let last = hood.net().cols() - 1;
    let screen = &doc.patches[1].design;
    let mut net = screen.net().clone();
    for c in 1..net.cols() {
        let v = net.get(0, c);
        net.set(0, c, (v - v.dot(n) * n).normalize());
    }
    net.set(0, 0, hood.net().get(0, last));
    doc.patches[1].design = with_net(screen, net);
    doc.patches[0].design = hood;
    doc
}

/// The mirror plane computed here from the file's initial curve (docs/math.md
/// §9): through its start point (`t₀ = 0`), normal to its first control tangent.
fn plane(doc: &Document) -> (DVec3, DVec3) {
    let Start::Curve(c) = &doc.patches[0].start else {
        panic!("the first patch starts on its own curve")
    };
    assert_eq!(doc.patches[0].design.params().t[0], 0.0);
    (c.origin.vec(), c.tangents[0].vec().normalize())
}

fn reflect((p, n): (DVec3, DVec3), x: DVec3) -> DVec3 {
    x - 2.0 * (x - p).dot(n) * n
}

fn reflect_dir((_, n): (DVec3, DVec3), v: DVec3) -> DVec3 {
    v - 2.0 * v.dot(n) * n
}

fn max_diff(a: &[DVec3], b: &[DVec3]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max)
}

#[test]
fn every_mirrored_patch_is_the_reflection_of_its_original_at_every_level() {
    let doc = mirrored_doc();
    let pl = plane(&doc);
    let n = doc.patches.len();
    let built = doc.build(3).unwrap();
    let m = mirrored(&doc, &built);
    assert_eq!(m.patches.len(), 2 * n);
    assert_eq!(m.seams.len(), 2 * built.seams.len());
    for (s, r) in built.seams.iter().zip(&m.seams[built.seams.len()..]) {
        assert_eq!((r.a, r.b, r.join), (s.a + n, s.b + n, s.join));
    }
    // the hood's first streamline lies in the plane (what lets its STEP
    // face share that edge with its reflection)
    let hood = &built.patches[0].points[3];
    let off = hood.row(0).iter().map(|&x| (x - pl.0).dot(pl.1).abs());
    let off = off.fold(0.0, f64::max);
    assert!(off < 1e-12, "the first streamline is {off:e} off the plane");
    let tilted = (pl.0, (pl.1 + DVec3::new(1e-6, 0.0, 0.0)).normalize());
    for i in 0..n {
        for d in 0..=3 {
            let (orig, refl) = (&built.patches[i].points[d], &m.patches[n + i].points[d]);
            let want: Vec<DVec3> = orig.data().iter().map(|&x| reflect(pl, x)).collect();
            assert!(max_diff(refl.data(), &want) < 1e-12, "patch {i} depth {d}");
            // the negative control: a plane 1e-6 rad off is seen
            let off: Vec<DVec3> = orig.data().iter().map(|&x| reflect(tilted, x)).collect();
            assert!(max_diff(refl.data(), &off) > 1e-7, "patch {i} depth {d}");
            let (ta, tb) = (
                &built.patches[i].levels[d].tangents,
                &m.patches[n + i].levels[d].tangents,
            );
            let want: Vec<DVec3> = ta.data().iter().map(|&v| reflect_dir(pl, v)).collect();
            assert!(max_diff(tb.data(), &want) < 1e-14);
            // the original is the document's own build, untouched
            assert_eq!(m.patches[i].points[d], *orig);
        }
        // exported meshes face the way the original does: normals R(n)
        let orig = SurfaceMesh::from_points(&built.patches[i].points[3]);
        let refl = turned(SurfaceMesh::from_points(&m.patches[n + i].points[3]));
        let want: Vec<DVec3> = orig.normals.iter().map(|&v| reflect_dir(pl, v)).collect();
        assert!(max_diff(&refl.normals, &want) < 1e-9, "patch {i}");
        let unturned = SurfaceMesh::from_points(&m.patches[n + i].points[3]);
        assert!(
            max_diff(&unturned.normals, &want) > 1.9,
            "a reflection turns the normals over"
        );
    }
    // without the mirror, the export's patches are the build's
    let mut plain = doc.clone();
    plain.mirror = false;
    assert_eq!(mirrored(&plain, &built).patches.len(), n);
}

/// The manifest entry of an exported CAD file: every face's points (the
/// originals' check grids; the reflections' reflected here).
fn entry(
    dir: &Path,
    tag: &str,
    path: &Path,
    doc: &Document,
    out: &DocumentExported,
) -> serde_json::Value {
    let fit = out.fit.as_ref().expect("a CAD export has its fit");
    let n = doc.patches.len();
    // what the designer reads (the status line, File ▸ CAD export): every face
    let summary = out
        .fit_summary()
        .expect("a CAD export says what its fit made");
    for f in &out.faces {
        let (nu, nv) = f.surface.pole_counts();
        let line = format!("`{}` {nu}x{nv} poles", f.name);
        assert!(summary.contains(&line), "{tag}: {line} not in {summary}");
    }
    assert!(summary.starts_with(&format!("sampled at depth {}", out.depth)));
    let points: Vec<String> = (0..out.faces.len())
        .map(|f| {
            // the points the fit's tolerance is promised at: the check grid
            // one depth finer (docs/math.md §10; a streamline's points sit at
            // interval midpoints, so a depth's points are not a finer one's)
            let g = &fit.grids[f % n].check.points;
            let pts: Vec<DVec3> = if f < n {
                g.data().to_vec()
            } else {
                g.data().iter().map(|&x| reflect(plane(doc), x)).collect()
            };
            point_file(dir, tag, f, &pts)
        })
        .collect();
    serde_json::json!({
        "file": path.display().to_string(),
        "points": points,
        "tolerance": out.faces.iter().map(|f| f.tolerance).fold(f64::INFINITY, f64::min),
        "samples": 40,
    })
}

#[test]
fn opencascade_reads_the_document_as_one_shell_and_as_iges_faces() {
    let dir = scratch("cad");
    let settings = DocumentExportSettings::default();
    let cases = [("plain", hood_screen_wing()), ("mirror", mirrored_doc())];
    let mut manifest = Vec::new();
    let mut outs = Vec::new();
    for (tag, doc) in &cases {
        let built = doc.build(doc.display_depth).unwrap();
        for ext in ["step", "igs"] {
            let path = dir.join(format!("{tag}.{ext}"));
            let out = export_document(doc, &built, &path, &settings)
                .unwrap_or_else(|e| panic!("{tag}.{ext}: {e}"));
            eprintln!(
                "{tag}.{ext}: {} faces sampled at depth {}, poles {:?}, tolerances {:?}, deviations {:?}",
                out.faces.len(),
                out.depth,
                out.faces
                    .iter()
                    .map(|f| f.surface.pole_counts())
                    .collect::<Vec<_>>(),
                out.faces.iter().map(|f| f.tolerance).collect::<Vec<_>>(),
                out.faces
                    .iter()
                    .map(|f| f.deviation.max)
                    .collect::<Vec<_>>()
            );
            manifest.push(entry(&dir, &format!("{tag}-{ext}"), &path, doc, &out));
            outs.push(out);
        }
    }
    // the shell sampled from depth 0 up: raised until the fit meets the tolerance
    let doc = hood_screen_wing();
    let built = doc.build(1).unwrap();
    let shallow = DocumentExportSettings {
        depth: Some(0),
        ..Default::default()
    };
    let path = dir.join("from-depth-0.step");
    let raised = export_document(&doc, &built, &path, &shallow).unwrap();
    assert!(raised.depth > 0, "depth 0 was enough?");
    eprintln!("from depth 0: sampled at depth {}", raised.depth);
    // the negative control: at depth 0 the shell is refused
    assert!(shell_as_it_lies(&doc, 0).is_err());
    manifest.push(entry(&dir, "raised", &path, &doc, &raised));
    outs.push(raised);

    let results = common::opencascade_manifest("check_shell.py", &dir, &manifest);
    let tags = [
        "plain.step",
        "plain.igs",
        "mirror.step",
        "mirror.igs",
        "raised.step",
    ];
    let mut free_plain = 0;
    for ((tag, out), r) in tags.iter().zip(&outs).zip(&results) {
        eprintln!("{tag}: {r}");
        let faces = out.faces.len();
        valid_within(tag, &out.faces, r);
        if tag.ends_with(".igs") {
            // separate faces: nothing shared
            assert_eq!(r["shared_edges"], 0, "{tag}: {r}");
            continue;
        }
        assert_eq!(r["shells"], 1, "{tag}: {r}");
        let n = 3;
        // the G2 chain hood → screen: normals within 0.1°; the G1 side join
        // hood → wing: oriented the same way (a wrong one reads ~180°)
        for k in 0..faces / n {
            assert!(seam_angle(r, [k * n, k * n + 1]) < 0.1, "{tag}: {r}");
            assert!(seam_angle(r, [k * n, k * n + 2]) < 90.0, "{tag}: {r}");
        }
        let free = r["free_edges"].as_u64().unwrap();
        if *tag == "mirror.step" {
            // both halves, each seam shared; the hood's first streamline is
            // one edge for it and its reflection, oriented alike
            assert_eq!(out.mirror_seams, [(0, 3), (1, 4)], "{tag}");
            assert_eq!(r["shared_edges"], 2 * 2 + 2, "{tag}: {r}");
            assert_eq!(free, 2 * free_plain - 4, "{tag}: {r}");
            for f in [0, 1] {
                let angle = seam_angle(r, [f, f + 3]);
                eprintln!("mirror seam of face {f}: normals {angle:.4}° apart");
                assert!(angle < 90.0, "{tag}: {r}");
            }
        } else {
            assert_eq!(r["shared_edges"], 2, "{tag}: {r}");
            // hood: first, last in three (the wing's seam the middle one), left;
            // screen and wing: all but their start edge
            assert_eq!(free, 4 + 3 + 3, "{tag}: {r}");
            free_plain = free;
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The node folder of `scripts/node.sh` (`$STREAMLINE_NODE`, default
/// `~/.cache/streamline-node`) with the validator, or a failure saying how to make it.
fn node_dir() -> PathBuf {
    let dir = std::env::var_os("STREAMLINE_NODE")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(std::env::var_os("HOME").expect("HOME is set"))
                .join(".cache/streamline-node")
        });
    assert!(
        dir.join("node_modules/gltf-validator/package.json")
            .exists(),
        "the Khronos glTF validator is missing ({}); run `bash scripts/setup.sh --tests` (it installs it with npm)",
        dir.display()
    );
    dir
}

/// The validator's reports, and whether it passed every file.
fn validate(files: &[&Path]) -> (Vec<serde_json::Value>, bool) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/node/validate_glb.js");
    let out = Command::new("node")
        .arg(&script)
        .arg(node_dir())
        .args(files)
        .output()
        .expect("node runs (install Node.js 18 or later)");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let reports: Vec<serde_json::Value> = stdout
        .lines()
        .filter(|l| l.starts_with('{'))
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(
        reports.len(),
        files.len(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (reports, out.status.success())
}

#[test]
fn a_glb_has_one_named_node_and_mesh_per_patch_and_the_khronos_validator_passes_it() {
    let dir = scratch("glb");
    let mut files = Vec::new();
    for (tag, doc) in [("plain", hood_screen_wing()), ("mirror", mirrored_doc())] {
        let depth = doc.display_depth as usize;
        let built = doc.build(doc.display_depth).unwrap();
        let path = dir.join(format!("{tag}.glb"));
        let out = export_document(&doc, &built, &path, &DocumentExportSettings::default()).unwrap();
        assert_eq!(out.format, Format::Glb);
        let all = mirrored(&doc, &built);
        let n = doc.patches.len();
        assert_eq!(out.patches.len(), all.patches.len());
        // read back by the gltf crate
        let bytes = std::fs::read(&path).unwrap();
        let g = gltf::Gltf::from_slice(&bytes).unwrap();
        let blob = g.blob.as_deref().unwrap();
        let scene = g.default_scene().unwrap();
        let nodes: Vec<_> = scene.nodes().collect();
        assert_eq!(nodes.len(), out.patches.len(), "{tag}");
        assert_eq!(g.meshes().count(), out.patches.len(), "{tag}");
        for (i, node) in nodes.iter().enumerate() {
            let name = &out.patches[i];
            let want = if i < n {
                doc.patches[i].name.clone()
            } else {
                format!("{}-mirror", doc.patches[i - n].name)
            };
            assert_eq!(name, &want);
            assert_eq!(node.name(), Some(name.as_str()), "{tag}");
            let mesh = node.mesh().unwrap();
            assert_eq!(mesh.name(), Some(name.as_str()), "{tag}");
            let prim = mesh.primitives().next().unwrap();
            let reader = prim.reader(|_| Some(blob));
            let pos: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            let grid = &all.patches[i].points[depth];
            // the patch's grid, row by row
            assert_eq!(pos.len(), grid.rows() * grid.cols(), "{tag} {name}");
            for (p, q) in pos.iter().zip(grid.data()) {
                let d = (DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) - *q).length();
                assert!(d <= 1e-6 * (1.0 + q.length()), "{tag} {name}: {d}");
            }
            let idx: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
            let cells = (grid.rows() - 1) * (grid.cols() - 1);
            assert_eq!(idx.len(), 6 * cells, "{tag} {name}");
        }
        files.push(path);
    }
    // the negative control: a mesh whose index points past its vertices
    let mut bad =
        SurfaceMesh::from_points(&hood_screen_wing().build(1).unwrap().patches[0].points[1]);
    let last = bad.indices.len() - 1;
    bad.indices[last] = bad.positions.len() as u32 + 5;
    let bytes = glb_parts_bytes(&[GlbPart {
        name: "bad",
        mesh: &bad,
        colors: None,
    }])
    .unwrap();
    let bad_path = dir.join("bad.glb");
    std::fs::write(&bad_path, bytes).unwrap();
    let paths: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    let (reports, ok) = validate(&paths);
    for r in &reports {
        eprintln!("{r}");
        assert_eq!(r["errors"], 0, "the validator found errors: {r}");
    }
    assert!(ok);
    let (reports, ok) = validate(&[&bad_path]);
    eprintln!("control: {}", reports[0]);
    assert!(
        !ok && reports[0]["errors"].as_u64().unwrap() > 0,
        "{}",
        reports[0]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn obj_and_stl_hold_one_object_per_patch_and_bad_names_say_what_to_do() {
    let dir = scratch("mesh");
    let doc = mirrored_doc();
    let built = doc.build(doc.display_depth).unwrap();
    let all = mirrored(&doc, &built);
    let d = doc.display_depth as usize;
    let obj = dir.join("doc.obj");
    let out = export_document(&doc, &built, &obj, &DocumentExportSettings::default()).unwrap();
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(&obj, &opts).unwrap();
    let names: Vec<&str> = models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        names,
        out.patches.iter().map(String::as_str).collect::<Vec<_>>()
    );
    for (m, s) in models.iter().zip(&all.patches) {
        assert_eq!(
            m.mesh.positions.len(),
            3 * s.points[d].data().len(),
            "{}",
            m.name
        );
    }
    // STL: one solid per patch
    let stl = dir.join("doc.stl");
    export_document(&doc, &built, &stl, &DocumentExportSettings::default()).unwrap();
    let text = std::fs::read_to_string(&stl).unwrap();
    let solids: Vec<&str> = text.lines().filter(|l| l.starts_with("solid ")).collect();
    assert_eq!(solids.len(), 6);
    assert_eq!(solids[3], "solid hood-mirror");
    // an unknown extension: the formats named, nothing written
    let bad = dir.join("doc.xyz");
    let e = export_document(&doc, &built, &bad, &DocumentExportSettings::default()).unwrap_err();
    assert!(e.to_string().contains(".step/.stp"), "{e}");
    assert!(!bad.exists());
    // one patch: one object named for the design, the surface shown
    let car = streamline_studio::scene::design::builtin::scene("car1").unwrap();
    let one = Document::from_scene(car.clone());
    let one_built = one.build(one.display_depth).unwrap();
    let (a, b) = (dir.join("one.obj"), dir.join("mesh.obj"));
    export_document(&one, &one_built, &a, &DocumentExportSettings::default()).unwrap();
    let design = car.shown_design().unwrap();
    let level = design.levels(car.display_depth).unwrap().pop().unwrap();
    let mesh = SurfaceMesh::from_points(&design.streamlines(&level));
    let part = GlbPart {
        name: &car.name,
        mesh: &mesh,
        colors: None,
    };
    write_meshes(&b, Format::Obj, &[part]).unwrap();
    let text = std::fs::read_to_string(&a).unwrap();
    assert!(
        text.starts_with("# Streamline Studio surface\no car1\n"),
        "{text:.60}"
    );
    assert_eq!(text.into_bytes(), std::fs::read(&b).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}
