//! Edits of a design of several patches (docs/math.md §11): the patch edits are
//! applied by the edit stage as the editor sends them; handle edits act on the
//! active patch; undo and redo restore the whole document bit for bit (every
//! patch's name, start, design and hidden flag, and the points each builds);
//! saving, loading and recovering keep every patch.

mod common;

use bevy::prelude::*;
use std::path::{Path, PathBuf};
use streamline_kernel::{DVec3, Grid};
use streamline_studio::ecs::joined::{
    ActivePatch, DocState, PatchHidden, PatchSlot, PatchSurface, doc_state, document,
};
use streamline_studio::ecs::patch::Patch;
use streamline_studio::ecs::{self, Edit, EditError, History, Model, ModelConfig, SurfaceData};
use streamline_studio::scene::design::builtin;
use streamline_studio::scene::design::document::Document;
use streamline_studio::scene::design::document_io;
use streamline_studio::scene::edits::patch_edit::PatchEdit;
use streamline_studio::scene::files::format::Finite;
use streamline_studio::scene::files::format_v3::{ContinuitySpec, EdgeSpec};

fn hood() -> Document {
    document_io::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron"))
        .unwrap()
}

fn app(doc: &Document) -> App {
    ecs::headless_document_app(doc, None, ModelConfig::default())
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("streamline-docedits-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

fn patch(app: &mut App, e: PatchEdit) -> Result<String, EditError> {
    ecs::apply(app, Edit::Patch(e))
}

fn rotate(row: usize, col: usize, degrees: f64) -> Edit {
    Edit::Rotate {
        row,
        col,
        axis: DVec3::Y,
        radians: degrees.to_radians(),
    }
}

/// Each patch's entity, in the document's order.
fn entities(app: &mut App) -> Vec<Entity> {
    let w = app.world_mut();
    let first = ecs::patch::patch_entity(w).unwrap();
    let mut q = w.query_filtered::<(Entity, &PatchSlot), With<Patch>>();
    let mut v: Vec<_> = q
        .iter(w)
        .filter(|(e, _)| *e != first)
        .map(|(e, s)| (s.index, e))
        .collect();
    v.sort();
    std::iter::once(first)
        .chain(v.into_iter().map(|(_, e)| e))
        .collect()
}

fn bits(g: &Grid<DVec3>) -> Vec<[u64; 3]> {
    g.data()
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect()
}

/// What the world shows: the document's state, and every patch's built
/// points (the first patch's surface, and each patch's joined build at
/// every depth), bit for bit.
#[derive(Debug, Clone)]
struct Shown {
    state: DocState,
    points: Vec<Vec<Vec<[u64; 3]>>>,
}

fn shown(app: &mut App) -> Shown {
    let state = doc_state(app.world()).unwrap();
    let ids = entities(app);
    let w = app.world();
    let mut points = vec![vec![bits(&w.resource::<SurfaceData>().points)]];
    for (i, &e) in ids.iter().enumerate() {
        let stack = w.get::<PatchSurface>(e).and_then(|s| s.stack());
        let built: Vec<_> = stack.map_or_else(Vec::new, |s| s.points.iter().map(bits).collect());
        if i == 0 {
            points[0].extend(built);
        } else {
            assert!(!built.is_empty(), "patch {i} is built");
            points.push(built);
        }
    }
    Shown { state, points }
}

/// `got` is `want`: the same document and the same points.
fn same(got: &Shown, want: &Shown) -> bool {
    got.state.same(&want.state) && got.points == want.points
}

/// Adds a patch, edits a later patch, renames, hides, edits the first
/// patch's seam column, removes a patch; then undoes all the way and redoes
/// all the way: every step restores the recorded document and points bit
/// for bit. The negative control: a restore that skipped the later patches
/// (the first patch's state with the later patches left as they were) is
/// told apart at every step that changed a later patch.
#[test]
fn undo_and_redo_restore_every_patch_bit_for_bit() {
    let mut app = app(&hood());
    let mut states = vec![shown(&mut app)];
    let add = PatchEdit::AddPatch {
        name: "tail".into(),
        from: ("screen".into(), EdgeSpec::End),
        continuity: ContinuitySpec::G1,
        rows: 5,
        cols: 3,
        length: Finite(0.5),
    };
    let steps: Vec<(Option<PatchEdit>, Edit)> = vec![
        (None, Edit::Patch(add)),
        (Some(PatchEdit::SetPatch("tail".into())), rotate(2, 1, 15.0)),
        (
            Some(PatchEdit::SetPatch("wing".into())),
            rotate(1, 1, -10.0),
        ),
        (
            None,
            Edit::Patch(PatchEdit::RenamePatch("tail".into(), "spoiler".into())),
        ),
        (None, Edit::Patch(PatchEdit::HidePatch("wing".into(), true))),
        (Some(PatchEdit::SetPatch("hood".into())), rotate(2, 4, 8.0)),
        (None, Edit::Patch(PatchEdit::RemovePatch("spoiler".into()))),
    ];
    for (choose, edit) in steps {
        if let Some(c) = choose {
            let before = app.world().resource::<History>().undo_len();
            patch(&mut app, c).unwrap();
            // choosing the patch to edit is not an undo step
            assert_eq!(app.world().resource::<History>().undo_len(), before);
        }
        let label = edit.label();
        ecs::apply(&mut app, edit).unwrap_or_else(|e| panic!("{label}: {e}"));
        states.push(shown(&mut app));
    }
    let n = states.len();
    assert_eq!(app.world().resource::<History>().undo_len(), n - 1);
    // every step changed what is shown
    for k in 1..n {
        assert!(
            !same(&states[k], &states[k - 1]),
            "step {k} changed nothing"
        );
    }
    // the later patches were hidden, renamed, turned: a restore of the
    // first patch alone would be told apart
    for k in 1..n {
        let skipped = Shown {
            state: DocState {
                first: states[k - 1].state.first.clone(),
                first_name: states[k - 1].state.first_name.clone(),
                first_hidden: states[k - 1].state.first_hidden,
                joined: states[k].state.joined.clone(),
            },
            points: states[k].points.clone(),
        };
        let later_changed = !states[k]
            .state
            .joined
            .iter()
            .zip(&states[k - 1].state.joined)
            .all(|(a, b)| a.name == b.name && a.hidden == b.hidden)
            || states[k].state.joined.len() != states[k - 1].state.joined.len()
            || states[k].points[1..] != states[k - 1].points[1..];
        if later_changed {
            assert!(!same(&skipped, &states[k - 1]), "step {k}: control");
        }
    }
    for k in (0..n - 1).rev() {
        ecs::apply(&mut app, Edit::Undo).unwrap();
        assert!(same(&shown(&mut app), &states[k]), "undo to step {k}");
    }
    assert!(matches!(
        ecs::apply(&mut app, Edit::Undo),
        Err(EditError::NothingToUndo)
    ));
    for (k, want) in states.iter().enumerate().skip(1) {
        ecs::apply(&mut app, Edit::Redo).unwrap();
        assert!(same(&shown(&mut app), want), "redo to step {k}");
    }
}

/// Undoing a rename or a hide writes only what differs: no patch is
/// rebuilt, and the renamed patch keeps its entity.
#[test]
fn undoing_a_rename_or_a_hide_rebuilds_nothing() {
    let mut app = app(&hood());
    let ids = entities(&mut app);
    let ticks = |app: &App| -> Vec<_> {
        ids.iter()
            .map(|&e| {
                app.world()
                    .entity(e)
                    .get_ref::<PatchSurface>()
                    .unwrap()
                    .last_changed()
            })
            .collect()
    };
    let before = ticks(&app);
    patch(
        &mut app,
        PatchEdit::RenamePatch("wing".into(), "fin".into()),
    )
    .unwrap();
    patch(&mut app, PatchEdit::HidePatch("screen".into(), true)).unwrap();
    assert!(app.world().get::<PatchHidden>(ids[1]).is_some());
    assert_eq!(app.world().get::<PatchSlot>(ids[2]).unwrap().name, "fin");
    ecs::apply(&mut app, Edit::Undo).unwrap();
    assert!(app.world().get::<PatchHidden>(ids[1]).is_none());
    ecs::apply(&mut app, Edit::Undo).unwrap();
    assert_eq!(entities(&mut app), ids, "the same entities");
    assert_eq!(app.world().get::<PatchSlot>(ids[2]).unwrap().name, "wing");
    assert_eq!(ticks(&app), before, "nothing rebuilt");
}

/// SetPatch sets the active patch; handle edits then change that patch's
/// net alone; edits a later patch cannot take are errors naming it.
#[test]
fn handle_edits_act_on_the_active_patch() {
    let mut app = app(&hood());
    let ids = entities(&mut app);
    let start = doc_state(app.world()).unwrap();
    patch(&mut app, PatchEdit::SetPatch("wing".into())).unwrap();
    assert_eq!(app.world().resource::<ActivePatch>().0, Some(ids[2]));
    ecs::apply(
        &mut app,
        Edit::SetLength {
            row: 1,
            col: 1,
            coefficient: 1.5,
        },
    )
    .unwrap();
    ecs::apply(
        &mut app,
        Edit::RotateMany {
            handles: vec![(0, 1), (1, 2)],
            axis: DVec3::Z,
            radians: 0.1,
        },
    )
    .unwrap();
    let now = doc_state(app.world()).unwrap();
    assert!(
        now.first.to_file() == start.first.to_file(),
        "hood unchanged"
    );
    assert!(streamline_studio::ecs::joined::same_design(
        &now.joined[0].design,
        &start.joined[0].design
    ));
    assert!(!streamline_studio::ecs::joined::same_design(
        &now.joined[1].design,
        &start.joined[1].design
    ));
    // what a later patch cannot take: the scheme, the blend order and the
    // initial curve are the first patch's
    let e = ecs::apply(
        &mut app,
        Edit::SetBlendOrder(streamline_kernel::levels::surface::BlendOrder::TFirst),
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("acts on the first patch only; on `wing`"),
        "{e}"
    );
    // above edit depth 0 a handle edit of a later patch is a detail of it
    let e = ecs::apply(&mut app, Edit::ClearDetail { row: 0, col: 1 }).unwrap_err();
    assert!(e.to_string().contains("detail"), "{e}");
    ecs::apply(&mut app, Edit::SetEditDepth(1)).unwrap();
    let said = ecs::apply(&mut app, rotate(0, 1, 5.0)).unwrap();
    assert!(
        said.contains("detail (0, 1) at level 1") && said.contains("`wing`"),
        "{said}"
    );
    let wing = &doc_state(app.world()).unwrap().joined[1];
    assert_eq!(
        wing.details.keys().copied().collect::<Vec<_>>(),
        vec![(1, 0, 1)]
    );
    ecs::apply(&mut app, Edit::ClearDetail { row: 0, col: 1 }).unwrap();
    assert!(doc_state(app.world()).unwrap().joined[1].details.is_empty());
    ecs::apply(&mut app, Edit::SetEditDepth(0)).unwrap();
    // a G2 chain's seam column is the hood's last: turned there
    patch(&mut app, PatchEdit::SetPatch("screen".into())).unwrap();
    let e = ecs::apply(&mut app, rotate(2, 0, 5.0)).unwrap_err();
    assert!(e.to_string().contains("turn it on `hood`"), "{e}");
    let e = patch(&mut app, PatchEdit::SetPatch("nowhere".into())).unwrap_err();
    assert!(
        e.to_string()
            .contains("no patch `nowhere`; the patches are `hood`, `screen`, `wing`")
    );
    // turning the hood's last column turns the screen's first with it, so
    // the design still saves and reads back (docs/math.md §11.1)
    patch(&mut app, PatchEdit::SetPatch("hood".into())).unwrap();
    ecs::apply(&mut app, rotate(2, 4, 12.0)).unwrap();
    let s = doc_state(app.world()).unwrap();
    let (a, b) = (s.first.design.net(), s.joined[0].design.net());
    for r in 0..a.rows() {
        assert!(a.get(r, a.cols() - 1).abs_diff_eq(b.get(r, 0), 1e-15));
    }
    let path = tmp("turned.ron");
    ecs::apply(&mut app, Edit::Save(path.clone())).unwrap();
    document_io::load(&path).unwrap();
}

/// A first-patch edit that would make a design the file checks refuse is
/// refused, naming the patch, and nothing changes.
#[test]
fn an_edit_of_the_first_patch_that_breaks_a_join_is_refused() {
    let mut app = app(&hood());
    let before = doc_state(app.world()).unwrap();
    let e = ecs::apply(
        &mut app,
        Edit::Author(streamline_studio::scene::edits::edit::AuthorEdit::InsertRow { at: 1 }),
    )
    .unwrap_err();
    assert!(e.to_string().contains("refused"), "{e}");
    assert!(doc_state(app.world()).unwrap().same(&before));
    assert_eq!(app.world().resource::<History>().undo_len(), 0);
}

/// Saving writes version 3 for several patches (read back as the same
/// document) and, for one patch, the very bytes a scene's save writes.
#[test]
fn save_writes_every_patch_and_one_patch_as_version_2() {
    let mut app = app(&hood());
    let path = tmp("hood.ron");
    ecs::apply(&mut app, Edit::Save(path.clone())).unwrap();
    let back = document_io::load(&path).unwrap();
    assert_eq!(back.to_file(), document(app.world()).unwrap().to_file());
    assert!(
        std::fs::read_to_string(&path)
            .unwrap()
            .contains("version: 3")
    );
    let m = app.world().resource::<Model>();
    assert!(!m.unsaved && m.path.as_deref() == Some(path.as_path()));

    let scene = builtin::scene("car1").unwrap();
    let mut one = ecs::headless_app(scene.clone());
    let (a, b) = (tmp("car-ecs.ron"), tmp("car-io.ron"));
    ecs::apply(&mut one, Edit::Save(a.clone())).unwrap();
    document_io::save_scene(&scene, &b).unwrap();
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    // one renamed patch: still version 2 (one patch saves as version 2), and the save
    // says that the name is not kept
    let said = ecs::apply(&mut one, Edit::Save(a.clone())).unwrap();
    assert_eq!(said, format!("saved {}", a.display()));
    patch(
        &mut one,
        PatchEdit::RenamePatch("main".into(), "body".into()),
    )
    .unwrap();
    let said = ecs::apply(&mut one, Edit::Save(a.clone())).unwrap();
    assert!(
        said.contains("as version 2") && said.contains("`body` opens again as `main`"),
        "{said}"
    );
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}

/// Loading a version-3 file replaces every patch (and the history); a
/// failed load keeps the design; recovering brings back every patch, unsaved.
#[test]
fn load_and_recover_replace_every_patch_and_a_failed_load_keeps_the_design() {
    let doc = hood();
    let path = tmp("load.ron");
    document_io::save(&doc, &path).unwrap();
    let mut app = ecs::headless_app(builtin::scene("car1").unwrap());
    ecs::apply(&mut app, rotate(2, 2, 5.0)).unwrap();
    ecs::apply(&mut app, Edit::Load(path.clone())).unwrap();
    app.update();
    assert!(
        doc_state(app.world())
            .unwrap()
            .same(&DocState::of_document(&doc))
    );
    assert_eq!(app.world().resource::<History>().undo_len(), 0);
    assert_eq!(entities(&mut app).len(), 3);
    let loaded = shown(&mut app);
    // a file that does not read: nothing changes
    let bad = tmp("bad.ron");
    std::fs::write(&bad, "(version: 3, patches: [").unwrap();
    let e = ecs::apply(&mut app, Edit::Load(bad)).unwrap_err();
    assert!(e.to_string().contains("the current scene is kept"), "{e}");
    assert!(same(&shown(&mut app), &loaded));
    // loading a one-patch scene over it leaves one patch
    let car = tmp("car.ron");
    document_io::save_scene(&builtin::scene("car1").unwrap(), &car).unwrap();
    ecs::apply(&mut app, Edit::Load(car)).unwrap();
    app.update();
    assert_eq!(entities(&mut app).len(), 1);
    assert!(doc_state(app.world()).unwrap().joined.is_empty());
    // recovering the three patches
    let origin = tmp("origin.ron");
    ecs::apply(
        &mut app,
        Edit::Recover {
            document: Box::new(doc.clone()),
            origin: Some(origin.clone()),
        },
    )
    .unwrap();
    app.update();
    assert!(same(&shown(&mut app), &loaded));
    let m = app.world().resource::<Model>();
    assert!(m.unsaved && m.path.as_deref() == Some(origin.as_path()));
}

/// The census counts every patch, and says per patch what it owns as
/// entities: its handles (a joined patch its net's), a level per depth and
/// a streamline per row of its display depth (a joined patch's values are
/// its built stack's, `tests/joined_entities.rs`).
#[test]
fn the_census_counts_every_patch_and_what_each_owns() {
    let doc = hood();
    let mut app = app(&doc);
    let c = streamline_studio::ecs::census::census(app.world_mut());
    assert_eq!(c.patches, 3);
    let names: Vec<&str> = c.per_patch.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["hood", "screen", "wing"]);
    let first = &c.per_patch[0];
    assert!(!first.joined);
    assert_eq!(first.levels, doc.display_depth as usize + 1);
    common::built::census_adds_up(&c);
    let curve = match &doc.patches[0].start {
        streamline_studio::scene::design::document::Start::Curve(c) => c.tangents.len(),
        _ => unreachable!(),
    };
    assert_eq!(
        first.handles,
        doc.patches[0].design.net().data().len() + curve
    );
    let ids = common::built::patches(&mut app);
    for (i, (p, d)) in c.per_patch.iter().zip(&doc.patches).enumerate().skip(1) {
        assert!(p.joined);
        let rows = (app.world().get::<PatchSurface>(ids[i]))
            .and_then(|s| s.stack())
            .map(|s| s.finest_points().rows());
        assert_eq!((p.levels, Some(p.streamlines)), (p.stack_depths, rows));
        assert_eq!(p.handles, d.design.net().data().len());
        assert_eq!(p.stack_depths, doc.display_depth as usize + 1);
    }
    let total: usize = c.per_patch.iter().map(|p| p.handles).sum();
    assert_eq!(
        total,
        c.handles.surface + c.handles.initial + c.handles.detail
    );
}

/// The first patch is found before any system has run (the editor spawns
/// a document's later patches then): the census of the editor's world once
/// said `patches 1` because it was not.
#[test]
fn the_first_patch_is_found_before_the_first_update() {
    let doc = hood();
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .add_plugins(ecs::ModelPlugin::new(doc.patch_scene(0)));
    let first = ecs::patch::patch_entity(app.world()).expect("found before any update");
    streamline_studio::ecs::joined::spawn_joined(app.world_mut(), &doc, first);
    app.update();
    let c = streamline_studio::ecs::census::census(app.world_mut());
    assert_eq!(c.patches, 3);
}

/// Exporting a design of several patches writes every patch, as `build
/// --export` does (one `o <name>` object per patch in OBJ).
#[test]
fn export_writes_every_patch() {
    let mut app = app(&hood());
    let path = tmp("hood.obj");
    let done = ecs::apply(&mut app, Edit::Export(path.clone())).unwrap();
    assert!(done.contains("3 patches"), "{done}");
    let text = std::fs::read_to_string(&path).unwrap();
    for name in ["hood", "screen", "wing"] {
        assert!(text.lines().any(|l| l == format!("o {name}")), "{name}");
    }
}

/// A drag on a later patch is one undo step, and Esc (CancelGroup) puts
/// the document back as it was, with no undo step left.
#[test]
fn a_drag_on_a_later_patch_is_one_step_and_cancels_whole() {
    let mut app = app(&hood());
    patch(&mut app, PatchEdit::SetPatch("wing".into())).unwrap();
    let before = shown(&mut app);
    for k in 1..=3 {
        let msg = ecs::EditMessage {
            edit: rotate(1, 1, 4.0 * k as f64),
            group: Some(7),
        };
        app.world_mut().write_message(msg);
        app.update();
    }
    assert_eq!(app.world().resource::<History>().undo_len(), 1);
    assert!(!same(&shown(&mut app), &before));
    ecs::apply(&mut app, Edit::CancelGroup(7)).unwrap();
    assert!(same(&shown(&mut app), &before));
    assert_eq!(app.world().resource::<History>().undo_len(), 0);
}
