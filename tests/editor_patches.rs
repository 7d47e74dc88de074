//! The handle room on several patches (docs/editor.md), headless. The
//! active patch's handles are placed, found and picked (a joined patch's on
//! its built stack, at the edit depth), every other patch's are dimmed and never
//! picked, a hidden patch's are not shown; a drag sends the same edits as
//! on the first patch; dragging a handle of `A` moves, in the same frame,
//! the handles of every patch that starts on `A`. Checked on the shipped
//! `scenes/hood-screen-wing.ron` (hood; screen: a G2 chain on the hood's
//! end; wing: a G1 side join on the hood's last streamline) against
//! `Document::build` (the scene library's build, an independent path).

mod common;

use bevy::prelude::*;
use common::headless_editor::{frame, handles, press, release, steer};
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_studio::ecs::joined::{ActivePatch, PatchHidden, PatchSlot};
use streamline_studio::ecs::patch::{Direction, Patch, PatchIndex};
use streamline_studio::ecs::{Edit, EditMessage, ModelPlugin};
use streamline_studio::editor::interaction::{
    DragKind, EditorSet, HandleId, HandleLayout, HandleSettings, InteractionPlugin, PatchRole,
    Placed, Selection,
};
use streamline_studio::scene::design::document::Document;
use streamline_studio::scene::design::document_io::load;

fn hood() -> Document {
    load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron")).unwrap()
}

/// The edits the drag state machine sent, in order.
#[derive(Resource, Default)]
struct Sent(Vec<EditMessage>);

fn record(mut r: MessageReader<EditMessage>, mut sent: ResMut<Sent>) {
    sent.0.extend(r.read().cloned());
}

/// The editor's interaction core on `doc` (its first patch as a one-patch
/// scene's world, the others joined, as `streamline-studio edit` opens it),
/// at edit depth `edit`; two frames run.
fn editor(doc: &Document, edit: u32) -> App {
    let mut scene = doc.patch_scene(0);
    scene.edit_depth = edit;
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .init_resource::<ButtonInput<MouseButton>>()
        .init_resource::<ButtonInput<KeyCode>>()
        .init_resource::<Sent>()
        .add_plugins(ModelPlugin::new(scene))
        .add_plugins(InteractionPlugin)
        .add_systems(
            Update,
            record
                .after(EditorSet::Drag)
                .before(streamline_studio::ecs::ModelSet::Edit),
        );
    frame(&mut app);
    let first = streamline_studio::ecs::patch::patch_entity(app.world()).unwrap();
    streamline_studio::ecs::joined::spawn_joined(app.world_mut(), doc, first);
    frame(&mut app);
    app
}

/// Each patch's entity, in the document's order.
fn patches(app: &mut App) -> Vec<Entity> {
    let w = app.world_mut();
    let mut q = w.query_filtered::<(Entity, &PatchSlot), With<Patch>>();
    let mut v: Vec<_> = q.iter(w).map(|(e, s)| (s.index, e)).collect();
    v.sort();
    v.into_iter().map(|(_, e)| e).collect()
}

fn activate(app: &mut App, e: Option<Entity>) {
    app.world_mut().resource_mut::<ActivePatch>().0 = e;
    frame(app);
}

/// Distance from `p` to the polyline `pts`.
fn to_polyline(p: DVec3, pts: &[DVec3]) -> f64 {
    pts.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let ab = b - a;
            let t = ((p - a).dot(ab) / ab.length_squared().max(1e-300)).clamp(0.0, 1.0);
            (a + ab * t).distance(p)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Every placed handle entity of patch `e`: `(id, place, role)`.
fn placed_of(app: &mut App, e: Entity) -> Vec<(HandleId, Placed, PatchRole)> {
    let w = app.world_mut();
    let mut q = w.query::<(&HandleId, &Placed, &PatchRole, &ChildOf)>();
    let mut v: Vec<_> = q
        .iter(w)
        .filter(|(.., c)| c.parent() == e)
        .map(|(h, p, r, _)| (*h, *p, *r))
        .collect();
    v.sort_by_key(|(h, ..)| (h.is_surface(), h.level(), h.row, h.col));
    v
}

/// A joined patch made active: its level-0 handles are the ones found and
/// picked, each on its streamline of `Document::build`'s level 0 and
/// pointing its designer's tangent; the screen's first column (the hood's
/// last, a G2 chain) is not its own; every other patch's handles are dimmed.
#[test]
fn the_active_joined_patch_is_placed_on_its_stack_and_picked() {
    let doc = hood();
    let mut app = editor(&doc, 0);
    let ids = patches(&mut app);
    let built = doc.build(doc.display_depth).unwrap();
    // negative control: by default the hood (the first patch) is active
    let (hood_picks, first) = handles(&mut app, |q| {
        (
            q.pickable(&HandleSettings::default()).count(),
            q.active_patch(),
        )
    });
    assert_eq!(first, Some(ids[0]));
    let hood_net = doc.patches[0].design.net();
    assert!(
        hood_picks > hood_net.rows() * hood_net.cols(),
        "the net and the initial curve"
    );
    for (i, &e) in ids.iter().enumerate().skip(1) {
        assert!(
            placed_of(&mut app, e)
                .iter()
                .all(|(.., r)| *r == PatchRole::Dimmed),
            "patch {i}"
        );
    }
    for (i, &e) in ids.iter().enumerate().skip(1) {
        activate(&mut app, Some(e));
        let net = doc.patches[i].design.net();
        let (rows, cols) = (net.rows(), net.cols());
        let own_first = i == 2; // the wing's side join owns its first column
        let placed = placed_of(&mut app, e);
        assert_eq!(
            placed.len(),
            rows * (cols - usize::from(!own_first)),
            "patch {i}: its level-0 handles, the shared seam column left out"
        );
        let pts = &built.patches[i].points[0];
        for (id, p, role) in &placed {
            assert_eq!(*role, PatchRole::Active);
            assert_eq!(id.level(), 0);
            let d = to_polyline(p.base, pts.row(id.row));
            assert!(d < 1e-9, "patch {i} {id:?}: {d} off its streamline");
            assert!((p.dir - net.get(id.row, id.col)).length() < 1e-12);
            assert!(p.length > 0.0 && p.length.is_finite());
        }
        // along each row the handles run in order of s
        for r in 0..rows {
            let row: Vec<_> = placed.iter().filter(|(h, ..)| h.row == r).collect();
            for w in row.windows(2) {
                let (a, b) = (w[0].1.base, w[1].1.base);
                assert!(a.distance(b) > 1e-6, "patch {i} row {r}");
            }
        }
        // found and picked: its own, no other patch's
        let (picks, found) = handles(&mut app, |q| {
            let picks: Vec<HandleId> = q
                .pickable(&HandleSettings::default())
                .map(|h| h.id)
                .collect();
            let found = q.find(HandleId::tangent(0, 1, 1)).map(|h| h.base);
            (picks, found)
        });
        assert_eq!(picks.len(), placed.len());
        assert!(
            picks.iter().all(|h| h.is_surface()),
            "no initial curve on an edge"
        );
        let own = placed
            .iter()
            .find(|(h, ..)| h.cell() == (1, 1))
            .unwrap()
            .1
            .base;
        assert_eq!(found, Some(own), "ids name the active patch's handles");
        // every other patch's handles are dimmed
        for (k, &o) in ids.iter().enumerate() {
            if k != i {
                let roles: Vec<_> = placed_of(&mut app, o)
                    .into_iter()
                    .map(|(.., r)| r)
                    .collect();
                assert!(!roles.is_empty() && roles.iter().all(|r| *r == PatchRole::Dimmed));
            }
        }
        let layout = app.world().resource::<HandleLayout>();
        assert_eq!((layout.active, layout.active_joined), (Some(e), true));
    }
    // back to the first patch: exactly as before
    activate(&mut app, None);
    let picks = handles(&mut app, |q| q.pickable(&HandleSettings::default()).count());
    assert_eq!(picks, hood_picks);
    assert!(
        placed_of(&mut app, ids[0])
            .iter()
            .all(|(.., r)| *r == PatchRole::Active)
    );
}

/// Picking on the screen finds the active patch's arrow under the pointer
/// and never another patch's, even right on it: whatever it picks is an
/// arrow of the active patch passing within the pick radius.
#[test]
fn picking_never_takes_a_dimmed_handle() {
    let doc = hood();
    let mut app = editor(&doc, 0);
    let ids = patches(&mut app);
    activate(&mut app, Some(ids[2]));
    let wing = placed_of(&mut app, ids[2]);
    let hood = placed_of(&mut app, ids[0]);
    // a projection that looks down z: screen = (x, y) × 100
    let project = |p: DVec3| Some(Vec2::new(p.x as f32 * 100.0, p.y as f32 * 100.0));
    let at = |p: DVec3| project(p).unwrap().extend(0.0).as_dvec3();
    // how far the wing's arrow `id` passes from `cursor` on the screen
    let off = |id: HandleId, cursor: DVec3| {
        let (_, p, _) = wing.iter().find(|(h, ..)| *h == id).unwrap();
        to_polyline(cursor, &[at(p.base), at(p.base + p.dir * p.length)])
    };
    let s = HandleSettings::default();
    let cursor = |p: DVec3| at(p).truncate().as_vec2();
    let (on_wing, on_hood) = handles(&mut app, |q| {
        let w = q.pick_on_screen(&s, cursor(wing[3].1.base), project, 0.5);
        let h: Vec<_> = hood
            .iter()
            .map(|(_, p, _)| (p.base, q.pick_on_screen(&s, cursor(p.base), project, 0.5)))
            .collect();
        (w, h)
    });
    let got = on_wing.expect("a wing handle under the pointer");
    assert!(off(got, at(wing[3].1.base)) <= 0.5);
    let mut nothing = 0;
    for (base, picked) in on_hood {
        match picked {
            Some(got) => assert!(
                off(got, at(base)) <= 0.5,
                "{got:?} is not under the pointer"
            ),
            None => nothing += 1,
        }
    }
    assert!(
        nothing > 0,
        "on the hood's arrows, mostly nothing is picked"
    );
}

/// A hidden patch's handles are not shown; a hidden active patch has none
/// to pick; shown again, they are back.
#[test]
fn hidden_patches_show_no_handles() {
    let doc = hood();
    let mut app = editor(&doc, 0);
    let ids = patches(&mut app);
    app.world_mut().entity_mut(ids[1]).insert(PatchHidden);
    frame(&mut app);
    assert!(
        placed_of(&mut app, ids[1])
            .iter()
            .all(|(.., r)| *r == PatchRole::Hidden)
    );
    assert!(
        placed_of(&mut app, ids[2])
            .iter()
            .all(|(.., r)| *r == PatchRole::Dimmed)
    );
    activate(&mut app, Some(ids[1]));
    assert_eq!(
        handles(&mut app, |q| q.pickable(&HandleSettings::default()).count()),
        0
    );
    app.world_mut().entity_mut(ids[1]).remove::<PatchHidden>();
    frame(&mut app);
    assert!(
        placed_of(&mut app, ids[1])
            .iter()
            .all(|(.., r)| *r == PatchRole::Active)
    );
    assert!(handles(&mut app, |q| q.pickable(&HandleSettings::default()).count()) > 0);
}

/// A drag on the active joined patch sends the same edits as on the first
/// patch (`SetDirection` of the drag's undo group: the edit stage acts on
/// the active patch); switching the patch ends the selection.
#[test]
fn a_drag_on_a_joined_patch_sends_set_direction() {
    let doc = hood();
    let mut app = editor(&doc, 0);
    let ids = patches(&mut app);
    activate(&mut app, Some(ids[2]));
    let h = HandleId::tangent(0, 2, 1);
    let start = app
        .world()
        .get::<Direction>(
            app.world()
                .get::<PatchIndex>(ids[2])
                .unwrap()
                .surface
                .get(2, 1),
        )
        .unwrap()
        .0;
    press(&mut app, Some(h), Some(DragKind::Sphere));
    let d = app
        .world()
        .resource::<streamline_studio::editor::interaction::Drag>()
        .0
        .expect("a drag of the wing's handle started");
    assert_eq!((d.handle, d.start_dir), (h, start));
    app.world_mut().resource_mut::<Sent>().0.clear();
    let dir = DVec3::new(0.2, 0.9, -0.3).normalize();
    steer(&mut app, dir);
    let sent = std::mem::take(&mut app.world_mut().resource_mut::<Sent>().0);
    assert_eq!(sent.len(), 1);
    match &sent[0].edit {
        Edit::SetDirection { row, col, dir: got } => {
            assert_eq!((*row, *col), (2, 1));
            assert_eq!(*got, dir);
        }
        other => panic!("sent {other:?}"),
    }
    assert_eq!(sent[0].group, Some(d.group));
    release(&mut app);
    // another active patch: nothing selected (the ids would name its handles)
    assert_eq!(app.world().resource::<Selection>().primary(), Some(h));
    activate(&mut app, None);
    assert!(app.world().resource::<Selection>().is_empty());
}

fn bits(p: &Placed) -> [u64; 7] {
    let [b, d] = [p.base, p.dir].map(|v| v.to_array().map(f64::to_bits));
    [b[0], b[1], b[2], d[0], d[1], d[2], p.length.to_bits()]
}

/// A world tick that every later system run is newer than.
fn tick(app: &mut App) -> bevy::ecs::change_detection::Tick {
    let w = app.world_mut();
    let t = w.change_tick();
    w.increment_change_tick();
    t
}

/// The handle entities of patch `e` whose `Placed` changed after `since`.
fn changed_of(app: &mut App, e: Entity, since: bevy::ecs::change_detection::Tick) -> Vec<HandleId> {
    let w = app.world_mut();
    let now = w.change_tick();
    let mut q = w.query::<(&HandleId, Ref<Placed>, &ChildOf)>();
    let mut v: Vec<HandleId> = q
        .iter(w)
        .filter(|(_, p, c)| c.parent() == e && p.last_changed().is_newer_than(since, now))
        .map(|(h, ..)| *h)
        .collect();
    v.sort_by_key(|h| (h.is_surface(), h.row, h.col));
    v
}

/// Dragging a hood handle near the seam moves, in that frame, the handles
/// of the patches that start on the hood (the screen on its end, the wing
/// on its last streamline) exactly where a fresh placement on the rebuilt
/// stacks puts them; only the handles that moved are marked changed; a
/// frame without an edit marks none (negative control).
#[test]
fn dragging_a_handle_of_a_moves_every_patch_on_a_live() {
    let doc = hood();
    let mut app = editor(&doc, 0);
    let ids = patches(&mut app);
    let before: Vec<_> = ids.iter().map(|&e| placed_of(&mut app, e)).collect();
    // the hood's last streamline, last column: the corner of both seams
    let h = HandleId::tangent(0, 4, 4);
    press(&mut app, Some(h), Some(DragKind::Sphere));
    let since = tick(&mut app);
    steer(&mut app, DVec3::new(0.7, -0.2, 0.68).normalize());
    for (k, &e) in ids.iter().enumerate().skip(1) {
        let after = placed_of(&mut app, e);
        let differ: Vec<HandleId> = before[k]
            .iter()
            .zip(&after)
            .filter(|(b, a)| bits(&b.1) != bits(&a.1))
            .map(|(b, _)| b.0)
            .collect();
        assert!(!differ.is_empty(), "patch {k} moved with the hood");
        assert_eq!(
            changed_of(&mut app, e, since),
            differ,
            "patch {k}: marked = moved"
        );
    }
    // where they are: on the stacks of a build of the edited document
    let scene = streamline_studio::ecs::patch::scene(app.world());
    let mut edited = doc.clone();
    edited.patches[0].design = scene.design.clone();
    // the screen's seam column is the hood's last (one handle, a G2 chain)
    let (a, last) = (scene.design.net(), scene.design.net().cols() - 1);
    for r in 0..a.rows() {
        edited.patches[1]
            .design
            .set_tangent(r, 0, a.get(r, last))
            .unwrap();
    }
    let built = edited.build(edited.display_depth).unwrap();
    for (k, &e) in ids.iter().enumerate().skip(1) {
        for (id, p, _) in placed_of(&mut app, e) {
            let d = to_polyline(p.base, built.patches[k].points[0].row(id.row));
            assert!(d < 1e-9, "patch {k} {id:?} {d}");
        }
    }
    // negative control: a frame without an edit moves nothing
    let since = tick(&mut app);
    frame(&mut app);
    for &e in &ids {
        assert!(changed_of(&mut app, e, since).is_empty());
    }
    release(&mut app);
}

/// At an edit depth above 0 a joined patch's handles are its refined ones
/// of that depth (its details, docs/math.md §5, §11.4), children of it;
/// the first patch's refined cells are gone while it is active; back on the
/// first patch, they are there again (`tests/editor_g2_placement.rs`
/// checks where they stand).
#[test]
fn a_joined_patch_shows_its_refined_handles_at_the_edit_depth() {
    let doc = hood();
    let mut app = editor(&doc, 2);
    let ids = patches(&mut app);
    let refined_parent = |app: &App| {
        let v = &app.world().resource::<HandleLayout>().refined.as_ref()?.1;
        app.world().get::<ChildOf>(*v.first()?).map(ChildOf::parent)
    };
    assert_eq!(refined_parent(&app), Some(ids[0]));
    activate(&mut app, Some(ids[1]));
    frame(&mut app);
    assert_eq!(app.world().resource::<HandleLayout>().edit_depth, 2);
    assert_eq!(refined_parent(&app), Some(ids[1]));
    let picks = handles(&mut app, |q| {
        q.pickable(&HandleSettings::default())
            .map(|h| h.id)
            .collect::<Vec<_>>()
    });
    assert!(!picks.is_empty() && picks.iter().all(|h| h.level() == 2));
    activate(&mut app, None);
    assert_eq!(app.world().resource::<HandleLayout>().edit_depth, 2);
    assert_eq!(refined_parent(&app), Some(ids[0]));
}

/// A turn of one of the active joined patch's tangents (its `Direction`
/// written, as the edit stage does for the active patch) moves only the
/// handles whose place changed: that patch's row, no other patch's; the
/// turned one points its new way.
#[test]
fn a_turn_on_a_joined_patch_moves_only_what_changed() {
    let doc = hood();
    let mut app = editor(&doc, 0);
    let ids = patches(&mut app);
    activate(&mut app, Some(ids[2]));
    frame(&mut app);
    let before: Vec<_> = ids.iter().map(|&e| placed_of(&mut app, e)).collect();
    let e = app
        .world()
        .get::<PatchIndex>(ids[2])
        .unwrap()
        .surface
        .get(3, 2);
    let dir = DVec3::new(0.1, 0.8, -0.59).normalize();
    let since = tick(&mut app);
    app.world_mut().get_mut::<Direction>(e).unwrap().0 = dir;
    frame(&mut app);
    for (k, &p) in ids.iter().enumerate() {
        let after = placed_of(&mut app, p);
        let differ: Vec<HandleId> = before[k]
            .iter()
            .zip(&after)
            .filter(|(b, a)| bits(&b.1) != bits(&a.1))
            .map(|(b, _)| b.0)
            .collect();
        assert_eq!(changed_of(&mut app, p, since), differ, "patch {k}");
        if k == 2 {
            assert!(differ.contains(&HandleId::tangent(0, 3, 2)));
            assert!(differ.iter().all(|h| h.row == 3), "{differ:?}");
            let turned = after.iter().find(|(h, ..)| h.cell() == (3, 2)).unwrap();
            assert_eq!(turned.1.dir, dir);
        } else {
            assert!(differ.is_empty(), "patch {k} moved: {differ:?}");
        }
    }
}

/// With the edit stage acting on the active patch: a drag of the wing's
/// handle turns the wing's tangent, leaves the hood's net as it was, moves
/// the wing's row of handles in that frame, and is one undo step.
#[test]
fn a_drag_on_the_active_joined_patch_turns_its_tangent() {
    let doc = hood();
    let mut app = editor(&doc, 0);
    let ids = patches(&mut app);
    // the editor chooses the patch with a SetPatch edit (not an undo step)
    app.world_mut().write_message(EditMessage::from(Edit::Patch(
        streamline_studio::scene::edits::patch_edit::PatchEdit::SetPatch("wing".into()),
    )));
    frame(&mut app);
    frame(&mut app);
    assert_eq!(app.world().resource::<ActivePatch>().0, Some(ids[2]));
    assert_eq!(app.world().resource::<HandleLayout>().active, Some(ids[2]));
    let hood_net = streamline_studio::ecs::patch::scene(app.world())
        .design
        .net()
        .clone();
    let undo = app
        .world()
        .resource::<streamline_studio::ecs::History>()
        .undo_len();
    let before = placed_of(&mut app, ids[2]);
    let h = HandleId::tangent(0, 2, 1);
    press(&mut app, Some(h), Some(DragKind::Sphere));
    let dir = DVec3::new(0.2, 0.9, -0.3).normalize();
    steer(&mut app, dir);
    release(&mut app);
    let e = app
        .world()
        .get::<PatchIndex>(ids[2])
        .unwrap()
        .surface
        .get(2, 1);
    assert!((app.world().get::<Direction>(e).unwrap().0 - dir).length() < 1e-12);
    assert_eq!(
        &streamline_studio::ecs::patch::scene(app.world())
            .design
            .net()
            .clone(),
        &hood_net
    );
    let after = placed_of(&mut app, ids[2]);
    let moved: Vec<HandleId> = before
        .iter()
        .zip(&after)
        .filter(|(b, a)| bits(&b.1) != bits(&a.1))
        .map(|(b, _)| b.0)
        .collect();
    assert!(
        moved.contains(&h) && moved.iter().all(|m| m.row == 2),
        "{moved:?}"
    );
    assert_eq!(
        app.world()
            .resource::<streamline_studio::ecs::History>()
            .undo_len(),
        undo + 1
    );
}
