//! File ▸ Reference… and View ▸ Reference without a window, under
//! `MinimalPlugins` (the model, the interaction core, the import plugin
//! with the Reference dialog's state, the ghost's plugin; no renderer, so
//! the ghost is checked as the geometry it keeps). Attach is one undo step
//! and is saved with the design, relative to the scene file; Detach too;
//! the ghost's vertices lie on the face the reference names and not on
//! another; a dialog's chosen face (Reference…, Import surface…) is drawn
//! instead while it is open; a
//! file that cannot be read is an error, not a panic.

mod common;

use bevy::prelude::*;
use common::headless_editor::{app, frame, undo_steps};
use std::path::{Path, PathBuf};
use streamline_kernel::DVec3;
use streamline_kernel::fit::ClosestPoints;
use streamline_studio::ecs::patch::scene;
use streamline_studio::ecs::{Edit, EditMessage, Model};
use streamline_studio::editor::files::import::{ImportForm, ImportPlugin};
use streamline_studio::editor::files::open_save::FileUi;
use streamline_studio::editor::files::reference::{ReferenceForm, ReferencePlugin};
use streamline_studio::editor::{GHOST_SAMPLES, ReferenceGhost, ReferenceGhostPlugin};
use streamline_studio::scene::files::reference_link::ReferenceLink;

fn reference(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/references")
        .join(name)
}

/// The headless editor (the car) with the dialogs' state and the ghost.
fn editor() -> App {
    let mut a = app();
    a.init_resource::<FileUi>()
        .add_plugins((ImportPlugin, ReferencePlugin))
        .add_plugins(ReferenceGhostPlugin);
    frame(&mut a);
    a
}

fn send(app: &mut App, edit: Edit) {
    app.world_mut().write_message(EditMessage::from(edit));
    frame(app);
}

fn link_of(app: &App) -> Option<ReferenceLink> {
    scene(app.world()).reference
}

#[test]
fn attach_is_one_undo_step_and_is_saved_relative_to_the_scene() {
    let mut app = editor();
    assert_eq!(link_of(&app), None);
    let steps = undo_steps(&app);
    let hood = reference("hood.step");
    let mut form = app.world_mut().resource_mut::<ReferenceForm>();
    form.read(hood.clone());
    assert!(form.open && form.error.is_none(), "{:?}", form.error);
    assert_eq!(form.face, Some(0));
    let edit = form.attach().expect("Attach is on");
    send(&mut app, edit);
    let link = link_of(&app).expect("the reference is attached");
    assert_eq!(link.face, 0);
    assert_eq!(
        link.path.canonicalize().unwrap(),
        hood.canonicalize().unwrap()
    );
    assert_eq!(undo_steps(&app), steps + 1, "one undo step");
    assert!(app.world().resource::<Model>().unsaved);
    // saved with the design, relative to the scene file's folder
    let dir = std::env::temp_dir().join(format!("attach-ref-{}", std::process::id()));
    let sub = dir.join("designs");
    std::fs::create_dir_all(&sub).unwrap();
    let copy = dir.join("hood.step");
    std::fs::copy(&hood, &copy).unwrap();
    send(&mut app, Edit::SetReference(None));
    let mut form = app.world_mut().resource_mut::<ReferenceForm>();
    form.read(copy.clone());
    let edit = form.attach().unwrap();
    send(&mut app, edit);
    let file = sub.join("car.ron");
    send(&mut app, Edit::Save(file.clone()));
    frame(&mut app);
    let text = std::fs::read_to_string(&file).expect("saved");
    let flat: String = text.split_whitespace().collect();
    assert!(
        flat.contains(r#"reference:Some((path:"../hood.step",face:0,))"#),
        "{text}"
    );
    let back = streamline_studio::scene::design::document_io::load(&file).unwrap();
    let l = back.reference.expect("read back");
    assert_eq!(l.path.canonicalize().unwrap(), copy.canonicalize().unwrap());
    // undo: the reference before (none after the detach), then hood, …
    send(&mut app, Edit::Undo);
    assert_eq!(link_of(&app), None);
    send(&mut app, Edit::Undo);
    assert_eq!(link_of(&app).map(|l| l.face), Some(0));
    send(&mut app, Edit::Undo);
    assert_eq!(link_of(&app), None, "the car had none");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn detach_is_one_undo_step() {
    let mut app = editor();
    let link = ReferenceLink {
        path: reference("roof.step"),
        face: 0,
    };
    send(&mut app, Edit::SetReference(Some(link.clone())));
    let steps = undo_steps(&app);
    send(&mut app, Edit::SetReference(None));
    assert_eq!(link_of(&app), None);
    assert_eq!(undo_steps(&app), steps + 1);
    send(&mut app, Edit::Undo);
    assert_eq!(link_of(&app), Some(link));
}

/// The largest distance from `points` to face 0 of `file`.
fn largest_distance(points: &[DVec3], file: &str) -> f64 {
    let f = streamline_reference::read(&reference(file)).unwrap();
    let s = f.surface(0).unwrap();
    ClosestPoints::new(s)
        .unwrap()
        .distances(points)
        .into_iter()
        .fold(0.0, f64::max)
}

fn ghost(app: &App) -> &ReferenceGhost {
    app.world().resource::<ReferenceGhost>()
}

#[test]
fn the_ghost_lies_on_the_reference_face() {
    let mut app = editor();
    let link = ReferenceLink {
        path: reference("hood.step"),
        face: 0,
    };
    send(&mut app, Edit::SetReference(Some(link)));
    assert!(ghost(&app).positions.is_empty(), "View ▸ Reference is off");
    app.world_mut().resource_mut::<ReferenceGhost>().shown = true;
    frame(&mut app);
    let g = ghost(&app);
    assert_eq!(g.error, None);
    assert_eq!(g.positions.len(), GHOST_SAMPLES * GHOST_SAMPLES);
    assert_eq!(
        g.indices.len(),
        6 * (GHOST_SAMPLES - 1) * (GHOST_SAMPLES - 1)
    );
    assert!(g.indices.iter().all(|&i| (i as usize) < g.positions.len()));
    let on = largest_distance(&g.positions, "hood.step");
    assert!(on <= 1e-12, "the vertices lie on the face: {on:e}");
    // negative control: another face
    let off = largest_distance(&g.positions, "roof.step");
    assert!(off > 1e-3, "not on the roof: {off:e}");
    // built once: frames and edits of the design leave it
    let generation = g.generation;
    send(&mut app, Edit::SetDisplayDepth(1));
    frame(&mut app);
    assert_eq!(ghost(&app).generation, generation);
}

#[test]
fn the_face_chosen_in_a_dialog_is_drawn_while_it_is_open() {
    let mut app = editor();
    let hood = ReferenceLink {
        path: reference("hood.step"),
        face: 0,
    };
    send(&mut app, Edit::SetReference(Some(hood)));
    app.world_mut().resource_mut::<ReferenceGhost>().shown = true;
    frame(&mut app);
    app.world_mut()
        .resource_mut::<ReferenceForm>()
        .read(reference("roof.step"));
    frame(&mut app);
    let g = ghost(&app);
    assert!(g.key.as_ref().is_some_and(|k| k.preview));
    let on = largest_distance(&g.positions, "roof.step");
    assert!(on <= 1e-12, "the roof is previewed: {on:e}");
    app.world_mut().resource_mut::<ReferenceForm>().open = false;
    frame(&mut app);
    let g = ghost(&app);
    assert!(g.key.as_ref().is_some_and(|k| !k.preview));
    assert!(largest_distance(&g.positions, "hood.step") <= 1e-12);
    // File ▸ Import surface… previews its chosen face too
    app.world_mut()
        .resource_mut::<ImportForm>()
        .read(reference("roof.step"));
    frame(&mut app);
    let g = ghost(&app);
    assert!(g.key.as_ref().is_some_and(|k| k.preview));
    assert!(largest_distance(&g.positions, "roof.step") <= 1e-12);
    app.world_mut().resource_mut::<ImportForm>().open = false;
    frame(&mut app);
    assert!(largest_distance(&ghost(&app).positions, "hood.step") <= 1e-12);
}

#[test]
fn a_reference_that_cannot_be_read_is_an_error_not_a_panic() {
    let mut app = editor();
    app.world_mut().resource_mut::<ReferenceGhost>().shown = true;
    let missing = ReferenceLink {
        path: std::env::temp_dir().join("no-such-reference.step"),
        face: 0,
    };
    send(&mut app, Edit::SetReference(Some(missing)));
    let g = ghost(&app);
    assert!(g.error.is_some());
    assert!(g.positions.is_empty());
    // a face past the end
    let past = ReferenceLink {
        path: reference("hood.step"),
        face: 7,
    };
    send(&mut app, Edit::SetReference(Some(past)));
    let g = ghost(&app);
    assert!(
        g.error.as_ref().is_some_and(|e| e.contains("face 7")),
        "{:?}",
        g.error
    );
    send(&mut app, Edit::SetReference(None));
    let g = ghost(&app);
    assert!(g.error.is_none() && g.positions.is_empty());
}

/// A triangle-mesh reference (an STL) is drawn as its own triangles.
#[test]
fn a_mesh_reference_is_drawn_as_its_triangles() {
    let mut app = editor();
    let stl =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/reference/tests/data/tent-binary.stl");
    let file = streamline_reference::read(&stl).unwrap();
    let mesh = file.mesh(0).unwrap().expect("the STL is a mesh");
    // Reference… offers the mesh (attached, not fitted)
    app.world_mut()
        .resource_mut::<ReferenceForm>()
        .read(stl.clone());
    let offered = app.world().resource::<ReferenceForm>().link();
    assert_eq!(offered.map(|l| l.face), Some(0));
    app.world_mut().resource_mut::<ReferenceForm>().open = false;
    send(
        &mut app,
        Edit::SetReference(Some(ReferenceLink {
            path: stl.clone(),
            face: 0,
        })),
    );
    app.world_mut().resource_mut::<ReferenceGhost>().shown = true;
    frame(&mut app);
    let g = ghost(&app);
    assert_eq!(g.error, None);
    assert_eq!(g.positions, mesh.positions().to_vec());
    let indices: Vec<u32> = mesh.triangles().iter().flatten().copied().collect();
    assert_eq!(g.indices, indices);
}
