//! File ▸ Import surface… without a window: the dialog's job under
//! `MinimalPlugins` (the model, the File feature's state and the import
//! plugin; the egui window is not drawn). A file read, a face fitted on the
//! job's thread, the design opened through the unsaved-changes rules of
//! File ▸ New with its `reference` naming the file and face; Cancel and a
//! file that cannot be read leave the design as it was.

mod common;

use bevy::prelude::*;
use common::headless_editor::{app, frame};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use streamline_studio::ecs::patch::scene;
use streamline_studio::ecs::{Edit, EditMessage, Model};
use streamline_studio::editor::document::files::{Dialog, FileUi, Pending};
use streamline_studio::editor::document::import::{ImportForm, ImportPlugin, JobEnd};

fn reference(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/references")
        .join(name)
}

/// The headless editor (the car) with the File state and the import plugin.
fn editor() -> App {
    let mut a = app();
    a.init_resource::<FileUi>().add_plugins(ImportPlugin);
    frame(&mut a);
    a
}

fn form(app: &mut App) -> Mut<'_, ImportForm> {
    app.world_mut().resource_mut::<ImportForm>()
}

/// Frames until the fit has ended (its thread joined), then one more for
/// the edit it sends.
fn until_done(app: &mut App) {
    let start = Instant::now();
    while app.world().resource::<ImportForm>().busy() {
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "the fit did not end"
        );
        std::thread::sleep(Duration::from_millis(20));
        frame(app);
    }
    frame(app);
}

/// The design's control net, to tell whether it changed.
fn net_of(app: &App) -> (String, usize, usize) {
    let s = scene(app.world());
    (s.name, s.design.net().rows(), s.design.net().cols())
}

#[test]
fn a_fitted_face_replaces_the_design_with_its_reference() {
    let mut app = editor();
    let before = net_of(&app);
    let hood = reference("hood.step");
    form(&mut app).read(hood.clone());
    {
        let f = app.world().resource::<ImportForm>();
        assert!(f.open && f.error.is_none(), "{:?}", f.error);
        assert!(!f.faces.is_empty());
        assert_eq!(f.face, Some(0), "the first B-spline face is chosen");
        assert_eq!(f.problem(), None);
    }
    assert!(form(&mut app).start());
    assert!(!form(&mut app).start(), "one fit at a time");
    // the design is untouched while the fit runs
    assert_eq!(net_of(&app), before);
    until_done(&mut app);
    let f = app.world().resource::<ImportForm>();
    let Some(JobEnd::Fitted(fitted)) = &f.last else {
        panic!("the fit ended as {:?}", f.last);
    };
    assert!(fitted.fit.within, "{:?}", fitted.fit.why);
    assert!(f.opened);
    let s = scene(app.world());
    assert_eq!(s.name, "hood");
    assert_eq!(
        (s.design.net().rows(), s.design.net().cols()),
        fitted.fit.net
    );
    let link = s.reference.expect("the scene keeps its reference");
    assert_eq!(link.face, 0);
    assert_eq!(
        link.path.canonicalize().unwrap(),
        hood.canonicalize().unwrap()
    );
    // a scene of no file yet, with work to lose: quitting asks first
    let model = app.world().resource::<Model>();
    assert_eq!(model.path, None);
    assert!(model.unsaved, "an imported design is unsaved");
    assert!(app.world().resource::<FileUi>().errors.is_empty());
}

#[test]
fn unsaved_changes_are_asked_about_before_the_import() {
    let mut app = editor();
    app.world_mut()
        .write_message(EditMessage::from(Edit::SetDisplayDepth(1)));
    frame(&mut app);
    assert!(app.world().resource::<Model>().unsaved);
    let before = net_of(&app);
    form(&mut app).read(reference("roof.step"));
    assert!(form(&mut app).start());
    until_done(&mut app);
    assert!(
        matches!(
            &app.world().resource::<FileUi>().dialog,
            Some(Dialog::Unsaved(Pending::Import(_)))
        ),
        "the unsaved-changes question waits: {:?}",
        app.world().resource::<FileUi>().dialog
    );
    assert_eq!(net_of(&app), before, "nothing replaced before the answer");
}

#[test]
fn cancel_leaves_the_design_unchanged() {
    let mut app = editor();
    let before = net_of(&app);
    let undo = common::headless_editor::undo_steps(&app);
    form(&mut app).read(reference("hood.step"));
    // a tight tolerance keeps the fit busy for several nets
    form(&mut app).relative = 1e-7;
    assert!(form(&mut app).start());
    form(&mut app).cancel();
    until_done(&mut app);
    let f = app.world().resource::<ImportForm>();
    assert!(
        matches!(f.last, Some(JobEnd::Cancelled)),
        "ended as {:?}",
        f.last
    );
    assert!(!f.opened);
    assert_eq!(net_of(&app), before);
    assert_eq!(common::headless_editor::undo_steps(&app), undo);
    assert!(scene(app.world()).reference.is_none());
}

#[test]
fn a_file_that_cannot_be_read_leaves_the_design_unchanged() {
    let mut app = editor();
    let before = net_of(&app);
    let dir = std::env::temp_dir().join(format!("import-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in [
        ("broken.step", "ISO-10303-21;\nHEADER;\nthis is not STEP\n"),
        ("empty.igs", "   \n"),
    ] {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        form(&mut app).read(p);
        let f = app.world().resource::<ImportForm>();
        assert!(f.open, "the dialog shows why");
        assert!(f.error.is_some(), "{name} was read");
        assert!(f.faces.is_empty() && f.file.is_none());
        assert!(f.problem().is_some(), "Fit stays off");
        assert!(!form(&mut app).start());
        frame(&mut app);
        assert_eq!(net_of(&app), before);
    }
    form(&mut app).read(dir.join("missing.obj"));
    assert!(app.world().resource::<ImportForm>().error.is_some());
    frame(&mut app);
    assert_eq!(net_of(&app), before);
    let _ = std::fs::remove_dir_all(&dir);
}
