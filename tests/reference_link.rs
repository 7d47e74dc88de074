//! A design keeps the reference it was fitted to (docs/math.md §12): the
//! top-level `reference: Some((path, face))` of a version-2 and a
//! version-3 file, its path relative to the file's folder. Read, it is
//! resolved against that folder; saved to another folder, it is written
//! relative to that one and still names the same file. It survives the ECS
//! world, its edits, undo and redo, a script's `Load` and `Save`, and the
//! editor's recovery file; a file without one saves as it did before; a bad
//! one is an error at its line and column. Each with a negative control.

use std::path::{Path, PathBuf};
use streamline_studio::ecs::joined::world_io;
use streamline_studio::ecs::{self, Edit, ModelConfig};
use streamline_studio::editor::EditorDirs;
use streamline_studio::editor::autosave::write_recovery;
use streamline_studio::kernel::DVec3;
use streamline_studio::scene::design::document::Document;
use streamline_studio::scene::edits::edit::AuthorEdit;
use streamline_studio::scene::edits::patch_edit::PatchEdit;
use streamline_studio::scene::edits::script::Script;
use streamline_studio::scene::files::format::{Finite, SceneFile};
use streamline_studio::scene::files::format_v3::{ContinuitySpec, DocumentFile, EdgeSpec};
use streamline_studio::scene::files::reference_link::ReferenceLink;
use streamline_studio::scene::{
    Scene,
    design::{builtin, document_io},
};

/// A fresh, absolute folder for test files, named by `tag` and the process.
fn tmpdir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ss-reference-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A shipped scene's path.
fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.ron"))
}

/// The line that sets the reference.
fn reference_line(path: &str, face: usize) -> String {
    format!("    reference: Some((path: {path:?}, face: {face})),\n")
}

/// The text of car1 as version 2 with `line` as its last field.
fn v2_text(line: &str) -> String {
    let text = document_io::load_scene(&shipped("car1")).unwrap().to_ron();
    let body = text.trim_end().strip_suffix(')').unwrap();
    format!("{body}{line})")
}

/// The text of hood-screen-wing (version 3) with `line` before its patches.
fn v3_text(line: &str) -> String {
    let text = std::fs::read_to_string(shipped("hood-screen-wing")).unwrap();
    assert!(text.contains("\n    patches: ["));
    text.replacen("\n    patches: [", &format!("\n{line}    patches: ["), 1)
}

/// Writes `text` to `path`, making its folder.
fn write(path: &Path, text: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

/// The reference's path as written in the file at `path`.
fn written(path: &Path) -> Option<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let v3 = text.contains("version: 3");
    let spec = match v3 {
        true => ron::from_str::<DocumentFile>(&text).unwrap().reference,
        false => ron::from_str::<SceneFile>(&text).unwrap().reference,
    };
    spec.map(|s| s.path)
}

/// The same file on disk (both exist).
fn same_file(a: &Path, b: &Path) -> bool {
    a.canonicalize().unwrap() == b.canonicalize().unwrap()
}

/// A folder with `refs/panel.step` (the reference, never read) and the
/// design `a/design.ron` of `text` pointing at it as `../refs/panel.step`.
fn project(tag: &str, text: &dyn Fn(&str) -> String) -> (PathBuf, PathBuf, PathBuf) {
    let dir = tmpdir(tag);
    let panel = dir.join("refs/panel.step");
    write(&panel, "ISO-10303-21;\n");
    let design = dir.join("a/design.ron");
    write(&design, &text(&reference_line("../refs/panel.step", 2)));
    (dir, panel, design)
}

#[test]
fn a_version_2_file_keeps_its_reference_saved_anywhere() {
    let (dir, panel, design) = project("v2", &|l| v2_text(l));
    let scene = document_io::load_scene(&design).unwrap();
    let link = scene.reference.clone().expect("the reference is read");
    assert_eq!(link.face, 2);
    assert_eq!(
        link.path,
        dir.join("refs/panel.step"),
        "resolved, `..` folded"
    );
    assert!(same_file(&link.path, &panel));
    // as a document too
    let doc = document_io::load(&design).unwrap();
    assert_eq!(doc.reference, Some(link.clone()));
    // saved to the same folder, to a deeper one, to the reference's own,
    // and as a document: the written path changes, the file does not
    for (to, want) in [
        ("a/again.ron", "../refs/panel.step"),
        ("b/deeper/other.ron", "../../refs/panel.step"),
        ("refs/here.ron", "panel.step"),
        ("design.ron", "refs/panel.step"),
    ] {
        let to = dir.join(to);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        document_io::save_scene(&scene, &to).unwrap();
        assert_eq!(written(&to).as_deref(), Some(want), "{}", to.display());
        let back = document_io::load_scene(&to).unwrap();
        assert_eq!(back.reference, Some(link.clone()));
        assert!(same_file(&back.reference.clone().unwrap().path, &panel));
        assert_eq!(back.to_file(), scene.to_file(), "loads back equal");
        document_io::save(&doc, &to).unwrap();
        assert_eq!(written(&to).as_deref(), Some(want), "as a document");
        assert_eq!(
            document_io::load(&to).unwrap().reference,
            Some(link.clone())
        );
    }
    // negative control: the bytes copied into another folder, not saved
    // there, point at another file
    let copied = dir.join("b/deeper/copied.ron");
    std::fs::copy(&design, &copied).unwrap();
    let moved = document_io::load_scene(&copied).unwrap().reference.unwrap();
    assert_eq!(moved.path, dir.join("b/refs/panel.step"));
    assert_ne!(moved, link);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_version_3_file_keeps_its_reference_saved_anywhere() {
    let (dir, panel, design) = project("v3", &|l| v3_text(l));
    let doc = document_io::load(&design).unwrap();
    assert_eq!(doc.patches.len(), 3);
    let link = doc.reference.clone().expect("the reference is read");
    assert_eq!(
        (link.path.clone(), link.face),
        (dir.join("refs/panel.step"), 2)
    );
    // every patch's scene carries the design's reference
    for i in 0..3 {
        assert_eq!(doc.patch_scene(i).reference, Some(link.clone()));
    }
    // saved into the same folder: the file reads back bit for bit
    let same = dir.join("a/same.ron");
    document_io::save(&doc, &same).unwrap();
    assert_eq!(
        std::fs::read_to_string(&same).unwrap(),
        std::fs::read_to_string(&design).unwrap().replace(
            &reference_line("../refs/panel.step", 2),
            "    reference: Some((\n        path: \"../refs/panel.step\",\n        face: 2,\n    )),\n"
        ),
        "the shipped text with the reference, as written"
    );
    for (to, want) in [
        ("a/same.ron", "../refs/panel.step"),
        ("b/c/d/far.ron", "../../../refs/panel.step"),
        ("top.ron", "refs/panel.step"),
    ] {
        let to = dir.join(to);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        document_io::save(&doc, &to).unwrap();
        assert_eq!(written(&to).as_deref(), Some(want), "{}", to.display());
        let back = document_io::load(&to).unwrap();
        assert_eq!(back.to_file(), doc.to_file(), "loads back equal");
        assert!(same_file(&back.reference.clone().unwrap().path, &panel));
    }
    // a version-3 file of one patch opens as a scene with the reference;
    // a document of one patch saves as version 2 with it
    let one = Document {
        patches: vec![doc.patches[0].clone()],
        ..doc.clone()
    };
    let one_path = dir.join("b/one.ron");
    std::fs::write(&one_path, one.to_ron_at(&dir.join("b/x.ron"))).unwrap();
    assert!(
        std::fs::read_to_string(&one_path)
            .unwrap()
            .contains("version: 2")
    );
    assert_eq!(
        document_io::load_scene(&one_path).unwrap().reference,
        Some(link.clone())
    );
    let v3_one =
        ron::ser::to_string_pretty(&one.to_file_at(&one_path), ron::ser::PrettyConfig::new())
            .unwrap();
    let parsed = Scene::parse(&v3_one, &one_path).unwrap();
    assert_eq!(parsed.reference, Some(link.clone()), "version 3, one patch");
    // negative control: the file without the line has none
    let plain = document_io::load(&shipped("hood-screen-wing")).unwrap();
    assert_eq!(plain.reference, None);
    let _ = std::fs::remove_dir_all(dir);
}

/// Every shipped scene saves, as before, without a `reference` key: a
/// version-3 file byte for byte, a version-1 file as version 2 with
/// `mirror: false` added (what saving wrote before the reference existed).
#[test]
fn files_without_a_reference_save_as_before() {
    let dir = tmpdir("plain");
    let mut names: Vec<PathBuf> =
        std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes"))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "ron"))
            .collect();
    names.sort();
    assert!(names.len() >= 8, "{names:?}");
    for path in names {
        let text = std::fs::read_to_string(&path).unwrap();
        let want = if text.contains("version: 1,") {
            let body = text.replacen("version: 1,", "version: 2,", 1);
            format!(
                "{}    mirror: false,\n)",
                body.trim_end().strip_suffix(')').unwrap()
            )
        } else {
            text.clone()
        };
        let doc = document_io::load(&path).unwrap();
        assert_eq!(doc.reference, None);
        assert_eq!(doc.to_ron(), want, "{}", path.display());
        let to = dir.join(path.file_name().unwrap());
        document_io::save(&doc, &to).unwrap();
        let saved = std::fs::read_to_string(&to).unwrap();
        assert_eq!(saved, want, "{}", path.display());
        assert!(!saved.contains("reference"));
        // negative control: with a reference the key is written
        let mut with = doc.clone();
        with.reference = Some(ReferenceLink {
            path: dir.join("panel.step"),
            face: 0,
        });
        let text = with.to_ron_at(&to);
        assert!(text.contains("reference: Some(("), "{}", path.display());
        assert!(text.contains("path: \"panel.step\""), "{}", path.display());
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// The world's document and first scene hold `link`.
fn world_holds(app: &bevy::prelude::App, link: &Option<ReferenceLink>, when: &str) {
    let doc = world_io::document(app.world()).unwrap();
    assert_eq!(&doc.reference, link, "{when}: the document");
    let scene = ecs::patch::scene(app.world());
    assert_eq!(&scene.reference, link, "{when}: the first scene");
}

#[test]
fn the_world_keeps_the_reference_through_edits_undo_and_redo() {
    let (dir, panel, design) = project("world", &|l| v2_text(l));
    let doc = document_io::load(&design).unwrap();
    let link = doc.reference.clone();
    assert!(link.is_some());
    let mut app = ecs::headless_document_app(&doc, None, ModelConfig::default());
    world_holds(&app, &link, "loaded");
    let edits = [
        Edit::SetDirection {
            row: 2,
            col: 4,
            dir: DVec3::new(1.0, 0.0, 0.4),
        },
        Edit::Author(AuthorEdit::InsertRow { at: 1 }),
        Edit::SetDisplayDepth(2),
        Edit::Patch(PatchEdit::AddPatch {
            name: "tail".into(),
            from: ("main".into(), EdgeSpec::End),
            continuity: ContinuitySpec::G1,
            rows: 7,
            cols: 4,
            length: Finite(1.0),
        }),
        Edit::Patch(PatchEdit::RenamePatch("main".into(), "body".into())),
    ];
    for e in &edits {
        ecs::apply(&mut app, e.clone()).unwrap_or_else(|x| panic!("{e:?}: {x}"));
        world_holds(&app, &link, &format!("after {}", e.label()));
    }
    for _ in &edits {
        ecs::apply(&mut app, Edit::Undo).unwrap();
        world_holds(&app, &link, "undone");
    }
    for _ in &edits {
        ecs::apply(&mut app, Edit::Redo).unwrap();
        world_holds(&app, &link, "redone");
    }
    assert_eq!(world_io::document(app.world()).unwrap().patches.len(), 2);
    // saved from the world into another folder: the same file
    let out = dir.join("out/world.ron");
    std::fs::create_dir_all(out.parent().unwrap()).unwrap();
    ecs::apply(&mut app, Edit::Save(out.clone())).unwrap();
    assert_eq!(written(&out).as_deref(), Some("../refs/panel.step"));
    let back = document_io::load(&out).unwrap();
    assert_eq!(back.reference, link);
    assert!(same_file(&back.reference.clone().unwrap().path, &panel));
    // loading a design without one drops it; loading ours brings it back
    ecs::apply(&mut app, Edit::Load(shipped("car2"))).unwrap();
    world_holds(&app, &None, "another design loaded");
    ecs::apply(&mut app, Edit::Load(design.clone())).unwrap();
    world_holds(&app, &link, "loaded again");
    // a recovered design keeps it
    ecs::apply(
        &mut app,
        Edit::Recover {
            document: Box::new(back.clone()),
            origin: Some(out.clone()),
        },
    )
    .unwrap();
    world_holds(&app, &link, "recovered");
    // negative control: a new design from a template starts without one
    ecs::apply(
        &mut app,
        Edit::Author(AuthorEdit::NewDesign {
            rows: 4,
            cols: 5,
            length: 2.0,
            template: streamline_studio::kernel::authoring::Template::Flat { width: 1.0 },
            scheme: streamline_studio::kernel::SurfaceScheme::Kobbelt { omega: 1.0 },
        }),
    )
    .unwrap();
    world_holds(&app, &None, "new design");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_script_load_and_save_keep_the_reference() {
    let (dir, panel, design) = project("script", &|l| v2_text(l));
    let three = dir.join("a/three.ron");
    write(&three, &v3_text(&reference_line("../refs/panel.step", 5)));
    let script = r#"(steps: [
        Load("a/design.ron"),
        SetDirection(row: 2, col: 4, dir: (1.0, 0.0, 0.4)),
        Undo,
        Redo,
        Save("out/one.ron"),
        Save("two.ron"),
        Load("a/three.ron"),
        Save("out/deep/three.ron"),
        Load("builtin:car1"),
        Save("out/plain.ron"),
    ])"#;
    let path = dir.join("play.ron");
    write(&path, script);
    let script = Script::load(&path).unwrap();
    let report = ecs::playback::play(&script, &dir, builtin::default_scene());
    assert!(report.passed(), "{}", report.lines.join("\n"));
    for (out, want, face) in [
        ("out/one.ron", "../refs/panel.step", 2),
        ("two.ron", "refs/panel.step", 2),
        ("out/deep/three.ron", "../../refs/panel.step", 5),
    ] {
        let out = dir.join(out);
        assert_eq!(written(&out).as_deref(), Some(want), "{}", out.display());
        let back = document_io::load(&out).unwrap().reference.unwrap();
        assert_eq!(back.face, face);
        assert!(same_file(&back.path, &panel));
    }
    assert!(
        document_io::load_scene(&dir.join("out/one.ron"))
            .unwrap()
            .reference
            .is_some()
    );
    // negative control: a built-in scene has none, and its save says so
    assert_eq!(written(&dir.join("out/plain.ron")), None);
    assert!(
        document_io::load_scene(&design)
            .unwrap()
            .reference
            .is_some()
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_recovery_file_keeps_the_reference() {
    let (dir, panel, design) = project("recovery", &|l| v3_text(l));
    let doc = document_io::load(&design).unwrap();
    let dirs = EditorDirs {
        home: dir.join("home"),
    };
    write_recovery(&dirs, &doc, Some(&design)).unwrap();
    let back = document_io::load(&dirs.recovery_file()).unwrap();
    assert_eq!(back.reference, doc.reference);
    assert!(same_file(&back.reference.clone().unwrap().path, &panel));
    assert_eq!(back.to_file(), doc.to_file());
    // one patch: through the scene's save
    let scene = document_io::load_scene(&shipped("car1")).unwrap();
    let one = Document {
        reference: doc.reference.clone(),
        ..Document::from_scene(scene)
    };
    write_recovery(&dirs, &one, None).unwrap();
    let back = document_io::load_scene(&dirs.recovery_file()).unwrap();
    assert_eq!(back.reference, doc.reference);
    // negative control: without one, none is recovered
    write_recovery(&dirs, &Document::from_scene(builtin::default_scene()), None).unwrap();
    assert_eq!(
        document_io::load(&dirs.recovery_file()).unwrap().reference,
        None
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// Line and column (1-based) of the first `reference:` in `text`.
fn key_place(text: &str) -> (usize, usize) {
    let (i, line) = (text.lines().enumerate())
        .find(|(_, l)| l.contains("reference:"))
        .unwrap();
    (i + 1, line.find("reference:").unwrap() + 1)
}

#[test]
fn a_bad_reference_is_an_error_at_its_line_and_column() {
    let file = Path::new("bad/design.ron");
    for (line, says) in [
        (reference_line("", 0), "is empty"),
        (reference_line("a\0b.step", 0), "NUL"),
        (
            reference_line("panel.step", 1_000_001),
            "over the limit of 1000000",
        ),
        (reference_line("refs/..", 0), "names a folder"),
    ] {
        // version 2, version 3, and version 3 of one patch (its own reader)
        let three = v3_text(&line);
        for (form, text) in [
            ("v2", v2_text(&line)),
            ("v3", three.clone()),
            ("v3 one patch", v3_one_patch(&three)),
        ] {
            let mut errors = vec![Document::parse(&text, file).unwrap_err()];
            if form != "v3" {
                errors.push(Scene::parse(&text, file).unwrap_err());
            }
            for e in errors {
                assert!(e.message.contains(says), "{form} {line:?}: {e}");
                assert!(e.message.contains("`path`") || e.message.contains("`face`"));
                assert_eq!((e.line, e.col), key_place(&text), "{form} {line:?}: {e}");
                let place = format!("bad/design.ron:{}:{}: ", e.line, e.col);
                assert!(e.to_string().starts_with(&place), "{e}");
            }
        }
    }
    // the RON reader refuses a wrong shape on the reference's line
    for (bad, says) in [
        (
            "    reference: Some((path: \"a.step\", face: 0, edge: 1)),\n",
            "unknown field `edge`",
        ),
        ("    reference: Some((path: \"a.step\")),\n", "`face`"),
        ("    reference: Some((path: \"a.step\", face: -1)),\n", ""),
        ("    reference: Some((path: 3, face: 0)),\n", ""),
    ] {
        for text in [v2_text(bad), v3_text(bad)] {
            let e = Document::parse(&text, file).unwrap_err();
            assert!(e.message.contains(says), "{bad:?}: {e}");
            assert_eq!(e.line, key_place(&text).0, "{bad:?}: {e}");
        }
    }
    // negative controls: the largest face, `None`, a folder up and an
    // absolute path are good
    for good in [
        reference_line("panel.step", 1_000_000),
        "    reference: None,\n".to_string(),
        reference_line("../../x/panel.stl", 0),
        reference_line("/abs/panel.igs", 3),
    ] {
        for text in [v2_text(&good), v3_text(&good)] {
            Document::parse(&text, file).unwrap_or_else(|e| panic!("{good:?}: {e}"));
        }
    }
}

/// The first patch of a version-3 text alone (cut before the second).
fn v3_one_patch(text: &str) -> String {
    let start = text
        .find("\n        (\n            name: \"screen\"")
        .unwrap();
    let end = text.rfind("\n    ],").unwrap();
    format!("{}{}", &text[..start], &text[end..])
}
