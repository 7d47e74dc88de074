//! File ▸ Import surface… without a window: the dialog's job under
//! `MinimalPlugins` (the model, the File feature's state and the import
//! plugin; the egui window is not drawn). A file read, a face fitted on the
//! job's thread, the design imported in one undo step (as a new design,
//! its `reference` naming the file and face; or as a new patch of the
//! current design, unjoined, the first patch untouched), and one Undo
//! bringing back the design before it bit for bit; Cancel and a file that
//! cannot be read leave the design as it was.

mod common;

use bevy::prelude::*;
use common::headless_editor::{app, frame};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use streamline_studio::ecs::joined::DocState;
use streamline_studio::ecs::joined::world_io::doc_state;
use streamline_studio::ecs::patch::scene;
use streamline_studio::ecs::{Edit, EditMessage, Model};
use streamline_studio::editor::files::import::{ImportForm, ImportPlugin, JobEnd};
use streamline_studio::editor::files::open_save::FileUi;
use streamline_studio::editor::files::reference::ReferencePlugin;

fn reference(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/references")
        .join(name)
}

/// The headless editor (the car) with the File state and the import plugin.
fn editor() -> App {
    let mut a = app();
    a.init_resource::<FileUi>()
        .add_plugins((ImportPlugin, ReferencePlugin));
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

/// The whole document, to compare bit for bit.
fn doc(app: &App) -> DocState {
    doc_state(app.world()).expect("the document is read")
}

/// Undo, one frame.
fn undo(app: &mut App) {
    app.world_mut().write_message(EditMessage::from(Edit::Undo));
    frame(app);
}

#[test]
fn a_fitted_face_replaces_the_design_with_its_reference() {
    let mut app = editor();
    let before = net_of(&app);
    let before_doc = doc(&app);
    let steps = common::headless_editor::undo_steps(&app);
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
    assert_eq!(
        common::headless_editor::undo_steps(&app),
        steps + 1,
        "one undo step"
    );
    // one Undo: the design before the import, bit for bit
    undo(&mut app);
    assert!(doc(&app).same(&before_doc), "undo brings the car back");
    assert_eq!(net_of(&app), before);
    assert!(scene(app.world()).reference.is_none());
}

#[test]
fn a_fitted_face_as_a_new_patch_keeps_the_first_patch() {
    let mut app = editor();
    let before = doc(&app);
    assert_eq!(before.len(), 1);
    let steps = common::headless_editor::undo_steps(&app);
    let roof = reference("roof.step");
    form(&mut app).read(roof.clone());
    form(&mut app).as_patch = true;
    assert!(form(&mut app).start());
    until_done(&mut app);
    let f = app.world().resource::<ImportForm>();
    let Some(JobEnd::Fitted(fitted)) = &f.last else {
        panic!("the fit ended as {:?}", f.last);
    };
    assert!(fitted.fit.within, "{:?}", fitted.fit.why);
    let fitted_net = fitted.fit.net;
    let errors = &app.world().resource::<FileUi>().errors;
    assert!(errors.is_empty(), "{errors:?}");
    let after = doc(&app);
    assert_eq!(after.len(), before.len() + 1, "one more patch");
    assert_eq!(after.name(1), "roof");
    assert_eq!(
        (after.design(1).net().rows(), after.design(1).net().cols()),
        fitted_net
    );
    // unjoined: it starts on its own initial curve
    assert!(matches!(
        after.joined[0].start,
        streamline_studio::ecs::joined::StartState::Curve(_)
    ));
    // the first patch's surface is unchanged, bit for bit
    assert!(streamline_studio::ecs::joined::same_design(
        &before.first.design,
        &after.first.design
    ));
    let mut first = after.first.clone();
    first.reference = None;
    assert!(
        first.to_file() == before.first.to_file(),
        "only the reference is new"
    );
    // the car had no reference: it takes the imported face
    let link = after.first.reference.clone().expect("the imported face");
    assert_eq!(
        link.path.canonicalize().unwrap(),
        roof.canonicalize().unwrap()
    );
    assert_eq!(common::headless_editor::undo_steps(&app), steps + 1);
    assert!(app.world().resource::<Model>().unsaved);
    // saved as a design of two patches, and read back so
    let dir = std::env::temp_dir().join(format!("import-patch-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("car-and-roof.ron");
    app.world_mut()
        .write_message(EditMessage::from(Edit::Save(file.clone())));
    frame(&mut app);
    frame(&mut app);
    let back = streamline_studio::scene::design::document_io::load(&file).expect("read back");
    assert_eq!(back.patches.len(), 2);
    assert!(matches!(
        back.patches[1].start,
        streamline_studio::scene::design::document::Start::Curve(_)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    undo(&mut app);
    assert!(
        doc(&app).same(&before),
        "undo: the design before, bit for bit"
    );
}

#[test]
fn unsaved_changes_stay_one_undo_away() {
    let mut app = editor();
    app.world_mut()
        .write_message(EditMessage::from(Edit::SetDisplayDepth(1)));
    frame(&mut app);
    assert!(app.world().resource::<Model>().unsaved);
    let before = doc(&app);
    form(&mut app).read(reference("roof.step"));
    assert!(form(&mut app).start());
    until_done(&mut app);
    // no question: the import is one undo step, nothing is lost
    assert!(app.world().resource::<FileUi>().dialog.is_none());
    assert_eq!(scene(app.world()).name, "roof");
    undo(&mut app);
    assert!(doc(&app).same(&before), "the edited design, bit for bit");
    assert_eq!(scene(app.world()).display_depth, 1);
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
