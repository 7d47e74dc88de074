//! Scene files: the shipped scenes, save → load identity, located errors,
//! atomic saving.

mod expectations;

use proptest::prelude::*;
use std::path::Path;
use streamline_studio::scene::{
    Scene,
    design::{builtin, document_io},
    files::io,
};

/// The shipped scenes are the kernel presets written out (set
/// `REGENERATE_SCENES=1` to write them again after changing a preset; never
/// in CI).
#[test]
fn shipped_scenes_match_presets() {
    for (name, _) in builtin::SCENES {
        let preset = builtin::preset(name).expect("every shipped scene has a preset");
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.ron"));
        if expectations::rewriting("REGENERATE_SCENES") {
            std::fs::write(&path, preset.to_ron()).unwrap();
            continue; // the compiled-in copies are stale until the next build
        }
        let loaded = document_io::load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            loaded.to_file(),
            preset.to_file(),
            "{name}.ron differs from its preset"
        );
        let compiled = builtin::scene(name).unwrap();
        assert_eq!(
            compiled.to_file(),
            loaded.to_file(),
            "{name}: the compiled-in copy is stale"
        );
    }
    assert_eq!(builtin::default_scene().name, "car1");
}

fn tmpdir(tag: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("ss-scenes-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn random_scene() -> impl Strategy<Value = Scene> {
    use streamline_kernel::{BlendOrder, DVec3, Design, Grid, SurfaceScheme};
    (
        2usize..6,
        2usize..7,
        any::<u64>(),
        0u32..3,
        0u32..3,
        0usize..3,
        0u8..3,
        any::<bool>(),
    )
        .prop_filter_map(
            "a valid random scene",
            |(rows, cols, seed, display, edit, ndetails, sch, tfirst)| {
                let mut x = seed | 1;
                let mut rnd = move || {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
                };
                let net: Vec<DVec3> = (0..rows * cols)
                    .map(|_| {
                        // Nasty magnitudes: tiny, huge, and ordinary.
                        let scale = [1e-300, 1.0, 1e250][(rnd().abs() * 2.99) as usize];
                        DVec3::new(rnd() + 1.1, rnd(), rnd()) * scale
                    })
                    .collect();
                let mut s = Vec::new();
                for _ in 0..rows {
                    let mut acc = rnd() * 10.0;
                    for _ in 0..cols {
                        s.push(acc);
                        acc += 0.5 + 0.2 * rnd().abs();
                    }
                }
                let scheme = [
                    SurfaceScheme::Kobbelt {
                        omega: 1.0 + 0.5 * rnd(),
                    },
                    SurfaceScheme::CatmullClark,
                    SurfaceScheme::DooSabin,
                ][sch as usize];
                let order = if tfirst {
                    BlendOrder::TFirst
                } else {
                    BlendOrder::SFirst
                };
                let t = (0..rows).map(|r| r as f64 * 0.3).collect();
                let design = Design::new(
                    &Grid::new(rows, cols, net).ok()?,
                    Grid::new(rows, cols, s).ok()?,
                    t,
                    cols - 1,
                    scheme,
                    order,
                    streamline_kernel::levels::presets::car1().initial().clone(),
                )
                .ok()?;
                let mut scene = Scene::from_design("random", design, display);
                scene.edit_depth = edit;
                for _ in 0..ndetails {
                    let level = edit.max(1);
                    let c = scheme.curve();
                    let (mut r, mut k) = (rows, cols);
                    for _ in 0..level {
                        r = c.refined_len(r);
                        k = c.refined_len(k);
                    }
                    let key = (
                        level,
                        (rnd().abs() * r as f64) as usize % r,
                        (rnd().abs() * k as f64) as usize % k,
                    );
                    scene
                        .details
                        .insert(key, DVec3::new(rnd(), rnd(), 1.0).normalize());
                }
                scene.view.yaw = streamline_studio::scene::files::format::Finite(rnd() * 180.0);
                scene.interpolate_tangents = rnd() > 0.3;
                if rnd() > 0.0 {
                    // fine tuning with random degrees, counts and values (docs/math.md §6)
                    let (ds, dt) = ((rnd().abs() * 3.0) as usize, (rnd().abs() * 3.0) as usize);
                    let (ns, nt) = (
                        ds + 1 + (rnd().abs() * 3.0) as usize,
                        dt + 1 + (rnd().abs() * 2.0) as usize,
                    );
                    let vals =
                        Grid::new(nt, ns, (0..ns * nt).map(|_| 1.0 + rnd()).collect()).ok()?;
                    scene.tuning = Some(streamline_kernel::finetune::SurfaceTuning {
                        function: streamline_kernel::finetune::bspline::TensorBSpline::new(
                            ds, dt, vals,
                        )
                        .ok()?,
                        constraint: [
                            streamline_kernel::finetune::Constraint::Free,
                            streamline_kernel::finetune::Constraint::KeepEnds,
                            streamline_kernel::finetune::Constraint::KeepClosed,
                        ][(rnd().abs() * 2.99) as usize],
                    });
                }
                scene.mirror = rnd() > 0.0;
                scene.validate(Path::new("<random>"), "").ok()?;
                Some(scene)
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Save → load is the identity (through the file, atomic save included).
    #[test]
    fn save_load_is_identity(scene in random_scene()) {
        let dir = tmpdir("prop");
        let path = dir.join("s.ron");
        document_io::save_scene(&scene, &path).unwrap();
        let back = document_io::load_scene(&path).unwrap();
        prop_assert_eq!(back.to_file(), scene.to_file());
        // And a second save writes the same bytes.
        let text1 = std::fs::read_to_string(&path).unwrap();
        document_io::save_scene(&back, &path).unwrap();
        prop_assert_eq!(std::fs::read_to_string(&path).unwrap(), text1);
    }
}

/// Bad files: each error names the file, the line and column, and the fix.
#[test]
fn bad_scenes_have_located_errors() {
    let good = builtin::SCENES[5].1; // minimal.ron
    let dir = tmpdir("bad");
    let tuned = |t: &str| {
        let end = good
            .trim_end()
            .strip_suffix(')')
            .expect("a scene ends with )");
        format!("{end}    tuning: {t},\n)\n")
    };
    let cases: [(&str, String, &str); 13] = [
        (
            "tuning: too few values for the degree",
            tuned("Some((degree_s: 3, degree_t: 1, values: [[1.0, 1.0], [1.0, 1.0]]))"),
            "degree 3 needs at least 4 control values",
        ),
        (
            "tuning: ragged values",
            tuned("Some((degree_s: 1, degree_t: 1, values: [[1.0, 1.0], [1.0]]))"),
            "row 1 of values has 1 entries",
        ),
        (
            "tuning: NaN value",
            tuned("Some((degree_s: 1, degree_t: 1, values: [[1.0, NaN], [1.0, 1.0]]))"),
            "NaN is not a finite number",
        ),
        (
            "unknown field",
            good.replace("anchor: 0,", "anchor: 0,\n    colour: 3,"),
            ":17:5: unknown field `colour`",
        ),
        (
            "zero tangent",
            good.replacen(
                "[(1.0, 0.0, 0.0), (1.0, 0.0, 0.0)],",
                "[(1.0, 0.0, 0.0), (0.0, 0.0, 0.0)],",
                1,
            ),
            ":5:",
        ),
        (
            "nan tangent",
            good.replacen("(1.0, 0.0, 0.0)]", "(NaN, 0.0, 0.0)]", 1),
            "NaN or infinite",
        ),
        (
            "non-increasing s",
            good.replacen("[0.0, 1.0],", "[1.0, 1.0],", 1),
            "increase strictly",
        ),
        (
            "ragged rows",
            good.replacen(
                "[(1.0, 0.0, 0.0), (1.0, 0.0, 0.0)],",
                "[(1.0, 0.0, 0.0)],",
                1,
            ),
            ":4:5: row 0 of tangents has 1",
        ),
        (
            "depth past the cap",
            good.replace("display_depth: 2,", "display_depth: 15,"),
            ":27:5: depth 15 would produce",
        ),
        (
            "wrong version",
            good.replace("version: 1,", "version: 4,"),
            "version 4 is not supported; this build reads versions 1 to 3",
        ),
        (
            "mirror in a version-1 file",
            tuned("None").replace("tuning: None,", "mirror: true,"),
            "mirror symmetry is a version 2 field; write `version: 2`",
        ),
        ("truncated", good[..good.len() / 2].to_string(), "truncated"),
        (
            "omega",
            good.replace("omega: 1.0", "omega: 7.0"),
            "omega 7 is outside",
        ),
    ];
    for (what, text, want) in cases {
        let path = dir.join("bad.ron");
        std::fs::write(&path, &text).unwrap();
        let e = document_io::load_scene(&path).expect_err(what).to_string();
        assert!(
            e.starts_with(&path.display().to_string()),
            "{what}: names the file: {e}"
        );
        assert!(e.contains(want), "{what}: `{e}` lacks `{want}`");
        let parts: Vec<&str> = e.splitn(4, ':').collect();
        assert!(
            parts.len() == 4
                && parts[1].parse::<usize>().is_ok()
                && parts[2].parse::<usize>().is_ok(),
            "{what}: line and column: {e}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A save that fails verification leaves the old file as it was.
#[test]
fn failed_save_keeps_the_old_file() {
    let dir = tmpdir("atomic");
    let path = dir.join("scene.ron");
    let scene = builtin::scene("car1").unwrap();
    document_io::save_scene(&scene, &path).unwrap();
    let before = std::fs::read(&path).unwrap();
    let e = io::write_atomic(&path, b"garbage", |_| Err("refused by test".into())).unwrap_err();
    assert!(e.to_string().contains("previous file is unchanged"), "{e}");
    assert_eq!(std::fs::read(&path).unwrap(), before);
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .collect();
    assert_eq!(leftovers.len(), 1, "no temporary file is left behind");
    // Saving into a folder that does not exist fails with a message and writes nothing.
    let e = document_io::save_scene(&scene, &dir.join("missing/x.ron")).unwrap_err();
    assert!(e.to_string().contains("cannot create"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Version 1 files open unchanged (the shipped scenes are version 1); saving
/// writes version 2 with `mirror`, and a version-2 file reads back the same.
#[test]
fn version_1_opens_and_saves_as_version_2() {
    let dir = tmpdir("v2");
    for (name, text) in builtin::SCENES {
        assert!(text.contains("version: 1,"), "{name} is a version-1 file");
        let v1 = Scene::parse(text, Path::new(name)).unwrap();
        assert!(!v1.mirror, "{name}: no mirror in version 1");
        let path = dir.join(format!("{name}.ron"));
        document_io::save_scene(&v1, &path).unwrap();
        let written = std::fs::read_to_string(&path).unwrap();
        assert!(
            written.contains("version: 2,") && written.contains("mirror: false"),
            "{name}: {written}"
        );
        let back = document_io::load_scene(&path).unwrap();
        assert_eq!(back.to_file(), v1.to_file(), "{name}: v1 → v2 → read");
        assert_eq!(back.design.net(), v1.design.net(), "{name}: the same net");
    }
    // a mirrored version-2 scene round-trips, and its doubled design is built
    let mut s = builtin::scene("car1").unwrap();
    s.mirror = true;
    let path = dir.join("mirrored.ron");
    document_io::save_scene(&s, &path).unwrap();
    let back = document_io::load_scene(&path).unwrap();
    assert!(back.mirror);
    let m = back.mirrored_design().unwrap().unwrap();
    assert_eq!(m.net().rows(), 2 * s.design.net().rows() - 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A mirrored scene whose seam tangent points along the plane's normal is
/// refused at `mirror`, with the fix.
#[test]
fn mirror_with_a_seam_tangent_along_the_normal_is_located() {
    let mut s = builtin::scene("minimal").unwrap();
    s.mirror = true;
    // minimal: initial curve along +y, so the plane's normal is +y
    s.design
        .set_tangent(0, 1, streamline_kernel::DVec3::Y)
        .unwrap();
    let text = s.to_ron();
    let e = Scene::parse(&text, Path::new("m.ron"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("points along the mirror plane's normal"), "{e}");
    let line = text
        .lines()
        .position(|l| l.trim_start().starts_with("mirror:"))
        .unwrap()
        + 1;
    assert!(
        e.starts_with(&format!("m.ron:{line}:")),
        "located at `mirror`: {e}"
    );
}

/// `Scene::new_design`: the templates, a sensible depth, a framing view, and
/// the kernel's errors with the fix.
#[test]
fn new_design_from_templates() {
    use streamline_kernel::SurfaceScheme;
    use streamline_kernel::authoring::Template;
    let s = Scene::new_design(
        5,
        7,
        4.0,
        Template::Flat { width: 2.0 },
        SurfaceScheme::default(),
    )
    .unwrap();
    assert_eq!((s.design.net().rows(), s.design.net().cols()), (5, 7));
    assert_eq!(
        (s.display_depth, s.edit_depth),
        (4, 0),
        "a small net is shown at depth 4"
    );
    assert!(
        (s.view.target.0 - 2.0).abs() < 1e-9 && (s.view.target.1 - 1.0).abs() < 1e-9,
        "the view frames the rectangle: {:?}",
        s.view.target
    );
    let big = Scene::new_design(
        64,
        64,
        4.0,
        Template::Flat { width: 2.0 },
        SurfaceScheme::default(),
    )
    .unwrap();
    assert!(
        big.display_depth <= 1,
        "a 64 × 64 net is shown shallow: depth {}",
        big.display_depth
    );
    let e = Scene::new_design(
        3,
        3,
        1.0,
        Template::Cylinder {
            radius: 1.0,
            degrees: 360.0,
        },
        SurfaceScheme::default(),
    )
    .unwrap_err();
    assert!(
        e.to_string().contains("strictly between 0 and 360 degrees"),
        "{e}"
    );
    // saved and read back as a version-2 scene
    let dir = tmpdir("new");
    let path = dir.join("new.ron");
    let c = Scene::new_design(
        4,
        4,
        3.0,
        Template::Cylinder {
            radius: 1.5,
            degrees: 150.0,
        },
        SurfaceScheme::default(),
    )
    .unwrap();
    document_io::save_scene(&c, &path).unwrap();
    assert_eq!(
        document_io::load_scene(&path).unwrap().to_file(),
        c.to_file()
    );
    let _ = std::fs::remove_dir_all(&dir);
}
