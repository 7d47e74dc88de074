//! Every patch owns its subdivision levels and display-depth streamlines as
//! entities (docs/architecture.md, "Several patches"; the values are its
//! stack's): one level per depth and one streamline per row, the first
//! patch's from its pipeline, a joined patch's from
//! `ecs::joined::entities`. An edit marks changed exactly the entities whose
//! values it may have moved: a streamline whose points moved is marked (with
//! the first point that moved), a level whose tangents or parameters moved
//! is marked with a window holding every row that moved; an untouched
//! patch's entities are not marked (negative control: the rows moved are
//! checked against the stacks before and after, bit for bit). The antipodal
//! warnings of every patch, rescanned in those windows, are a fresh build's.

mod common;

use bevy::ecs::change_detection::Tick;
use bevy::prelude::*;
use common::built::patches;
use proptest::prelude::*;
use streamline_kernel::joins::Stack;
use streamline_kernel::{DQuat, DVec3};
use streamline_studio::cli::bench::patches::{chained_cars, chained_cars_with};
use streamline_studio::ecs::census::census;
use streamline_studio::ecs::components::{
    LevelWindow, Streamline, StreamlinePoints, SubdivisionLevel,
};
use streamline_studio::ecs::joined::{JoinedChild, JoinedEntities, PatchSurface, document};
use streamline_studio::ecs::warnings::BuildWarnings;
use streamline_studio::ecs::{self, Edit, ModelConfig};
use streamline_studio::scene::design::document::Document;
use streamline_studio::scene::design::document_io;
use streamline_studio::scene::edits::patch_edit::PatchEdit;

fn hood() -> Document {
    document_io::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron"),
    )
    .unwrap()
}

fn app(doc: &Document) -> App {
    ecs::headless_document_app(doc, None, ModelConfig::default())
}

fn stack(app: &App, e: Entity) -> Option<Stack> {
    app.world().get::<PatchSurface>(e)?.stack().cloned()
}

/// Patch `e`'s level and streamline entities, checked to be its children,
/// one per depth and row, with their depth and row in order.
fn entities(app: &mut App, e: Entity) -> JoinedEntities {
    let w = app.world_mut();
    let have = w.get::<JoinedEntities>(e).cloned().unwrap_or_default();
    for (k, &l) in have.levels.iter().enumerate() {
        assert_eq!(
            w.get::<SubdivisionLevel>(l),
            Some(&SubdivisionLevel(k as u32))
        );
        assert_eq!(w.get::<ChildOf>(l).map(ChildOf::parent), Some(e));
        assert!(w.get::<JoinedChild>(l).is_some());
    }
    for (r, &l) in have.streamlines.iter().enumerate() {
        assert_eq!(w.get::<Streamline>(l), Some(&Streamline { row: r }));
        assert_eq!(w.get::<ChildOf>(l).map(ChildOf::parent), Some(e));
    }
    have
}

/// The change ticks of patch `e`'s levels and streamlines.
fn ticks(app: &App, have: &JoinedEntities) -> (Vec<Tick>, Vec<Tick>) {
    let w = app.world();
    let t = |l: Entity, level: bool| {
        let e = w.entity(l);
        match level {
            true => e.get_ref::<LevelWindow>().unwrap().last_changed(),
            false => e.get_ref::<StreamlinePoints>().unwrap().last_changed(),
        }
    };
    (
        have.levels.iter().map(|&l| t(l, true)).collect(),
        have.streamlines.iter().map(|&l| t(l, false)).collect(),
    )
}

fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

/// The rows of level `k` whose tangents or parameters differ.
fn level_rows_moved(a: &Stack, b: &Stack, k: usize) -> Vec<usize> {
    let (la, lb) = (&a.levels[k], &b.levels[k]);
    (0..la.tangents.rows())
        .filter(|&r| {
            (la.tangents.row(r).iter().zip(lb.tangents.row(r))).any(|(x, y)| bits(*x) != bits(*y))
                || (la.params.s.row(r).iter().zip(lb.params.s.row(r)))
                    .any(|(x, y)| x.to_bits() != y.to_bits())
                || la.params.t[r].to_bits() != lb.params.t[r].to_bits()
                || la.params.sigma[r].to_bits() != lb.params.sigma[r].to_bits()
        })
        .collect()
}

/// The first point of finest row `r` that differs (`None`: none).
fn first_moved(a: &Stack, b: &Stack, r: usize) -> Option<usize> {
    let (pa, pb) = (a.finest_points().row(r), b.finest_points().row(r));
    (pa.iter().zip(pb)).position(|(x, y)| bits(*x) != bits(*y))
}

/// Checks that patch `e`'s entities after an edit say what moved between
/// `was` and its stack now (module documentation); returns the number of
/// streamlines marked.
fn check_marks(
    app: &mut App,
    e: Entity,
    was: &Stack,
    before: &(Vec<Tick>, Vec<Tick>),
    label: &str,
) -> usize {
    let have = entities(app, e);
    let now = stack(app, e).expect("built");
    assert_eq!(have.levels.len(), now.levels.len(), "{label}");
    assert_eq!(
        have.streamlines.len(),
        now.finest_points().rows(),
        "{label}"
    );
    let after = ticks(app, &have);
    let reshaped = (was.levels.iter().zip(&now.levels)).any(|(a, b)| {
        a.tangents.rows() != b.tangents.rows() || a.tangents.cols() != b.tangents.cols()
    });
    if reshaped || was.levels.len() != now.levels.len() {
        return have.streamlines.len();
    }
    for k in 0..now.levels.len() {
        let moved = level_rows_moved(was, &now, k);
        let marked = after.0[k] != before.0[k];
        if !marked {
            assert!(
                moved.is_empty(),
                "{label}: level {k} moved rows {moved:?} unmarked"
            );
            continue;
        }
        let w = app.world().get::<LevelWindow>(have.levels[k]).unwrap().0;
        if let Some(w) = w {
            for r in &moved {
                assert!(
                    (w.rows.lo..=w.rows.hi).contains(r),
                    "{label}: level {k} row {r} outside {w:?}"
                );
            }
            assert_eq!(w.cols.hi + 1, now.levels[k].tangents.cols(), "{label}");
        }
    }
    let mut marked = 0;
    for r in 0..now.finest_points().rows() {
        let moved = first_moved(was, &now, r);
        if after.1[r] == before.1[r] {
            assert_eq!(moved, None, "{label}: streamline {r} moved unmarked");
            continue;
        }
        marked += 1;
        let from = app
            .world()
            .get::<StreamlinePoints>(have.streamlines[r])
            .unwrap()
            .moved_from;
        if let Some(c) = moved {
            assert!(
                from <= c,
                "{label}: row {r} moved at {c}, marked from {from}"
            );
        }
    }
    marked
}

/// Every patch of hood-screen-wing owns one level entity per depth and one
/// streamline entity per row; the census counts them per patch; a new
/// display depth makes them again for its rows; a patch removed takes its
/// entities with it.
#[test]
fn every_patch_owns_its_levels_and_streamlines() {
    let doc = hood();
    let mut app = app(&doc);
    let ids = patches(&mut app);
    let check = |app: &mut App, depth: u32| {
        let c = census(app.world_mut());
        for (i, p) in c.per_patch.iter().enumerate() {
            let s = stack(app, ids[i]).expect("built");
            assert_eq!(p.levels, depth as usize + 1, "{}", p.name);
            assert_eq!(p.streamlines, s.finest_points().rows(), "{}", p.name);
            if i > 0 {
                let have = entities(app, ids[i]);
                assert_eq!(have.levels.len(), p.levels);
                assert_eq!(have.streamlines.len(), p.streamlines);
            }
        }
        common::built::census_adds_up(&c);
    };
    check(&mut app, doc.display_depth);
    ecs::apply(&mut app, Edit::SetDisplayDepth(doc.display_depth + 1)).unwrap();
    check(&mut app, doc.display_depth + 1);
    ecs::apply(&mut app, Edit::SetDisplayDepth(2)).unwrap();
    check(&mut app, 2);
    let wing = entities(&mut app, ids[2]);
    assert!(!wing.streamlines.is_empty());
    ecs::apply(&mut app, Edit::Patch(PatchEdit::RemovePatch("wing".into()))).unwrap();
    let w = app.world();
    for e in wing.levels.iter().chain(&wing.streamlines) {
        assert!(w.get_entity(*e).is_err(), "the wing's entities are gone");
    }
    assert_eq!(census(app.world_mut()).per_patch.len(), 2);
}

/// One random edit: patch `p` (after the first), cell `(row, col)` of its
/// net turned by `angle` about `axis`.
#[derive(Debug, Clone)]
struct Turn {
    p: usize,
    row: usize,
    col: usize,
    axis: DVec3,
    angle: f64,
}

fn turns(patches: usize) -> impl Strategy<Value = Vec<Turn>> {
    let turn = (
        1..patches,
        0usize..5,
        // (column 0 of a chained patch is its seam, one handle of both,
        // turned on the earlier patch)
        1usize..4,
        (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
        -0.3f64..0.3,
    )
        .prop_filter_map("axis", |(p, row, col, (x, y, z), angle)| {
            let axis = DVec3::new(x, y, z).try_normalize()?;
            Some(Turn {
                p,
                row,
                col,
                axis,
                angle,
            })
        });
    prop::collection::vec(turn, 1..5)
}

/// Applies `t` to the world (through the active patch) and returns whether
/// the cell existed.
fn apply_turn(app: &mut App, doc: &Document, t: &Turn) -> bool {
    let net = doc.patches[t.p].design.net();
    if t.row >= net.rows() || t.col >= net.cols() {
        return false;
    }
    let name = doc.patches[t.p].name.clone();
    ecs::apply(app, Edit::Patch(PatchEdit::SetPatch(name))).unwrap();
    let dir = DQuat::from_axis_angle(t.axis, t.angle) * net.get(t.row, t.col);
    let done = ecs::apply(
        app,
        Edit::SetDirection {
            row: t.row,
            col: t.col,
            dir,
        },
    );
    done.is_ok()
}

/// Random edits of every later patch of three G1-chained cars (each kept
/// between edits) and of the hood-screen-wing (a G2 run's member, a side
/// join): each patch's entities say exactly what moved.
fn marks_say_what_moved(doc: Document, seq: Vec<Turn>) {
    let mut app = app(&doc);
    let ids = patches(&mut app);
    let mut applied = 0;
    for (i, t) in seq.iter().enumerate() {
        let was: Vec<Option<Stack>> = ids.iter().map(|&e| stack(&app, e)).collect();
        let before: Vec<_> = (ids.iter())
            .map(|&e| {
                let have = entities(&mut app, e);
                ticks(&app, &have)
            })
            .collect();
        let cur = document(app.world()).unwrap();
        if !apply_turn(&mut app, &cur, t) {
            continue;
        }
        applied += 1;
        for k in 1..ids.len() {
            let label = format!("step {i} {t:?}, patch {k}");
            if let Some(was) = &was[k] {
                let marked = check_marks(&mut app, ids[k], was, &before[k], &label);
                assert!(k != t.p || marked > 0, "{label}: the edited patch moved");
            }
        }
    }
    assert_eq!(applied, seq.len(), "every turn is a cell of its patch");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    #[test]
    fn chained_cars_entities_say_what_moved(seq in turns(3)) {
        marks_say_what_moved(chained_cars(3, 3), seq);
    }

    #[test]
    fn g2_cars_entities_say_what_moved(seq in turns(3)) {
        marks_say_what_moved(
            chained_cars_with(3, 3, streamline_kernel::joins::Continuity::G2),
            seq,
        );
    }

    #[test]
    fn hood_screen_wing_entities_say_what_moved(seq in turns(3)) {
        marks_say_what_moved(hood(), seq);
    }
}

/// A local edit of the last car marks only some of its streamlines and
/// none of the cars before it (control for the property above, which
/// allows any number).
#[test]
fn a_local_edit_marks_only_the_rows_it_moved() {
    let doc = chained_cars(3, 4);
    let mut app = app(&doc);
    let ids = patches(&mut app);
    let was: Vec<Stack> = ids.iter().map(|&e| stack(&app, e).unwrap()).collect();
    let before: Vec<_> = (ids.iter())
        .map(|&e| {
            let have = entities(&mut app, e);
            ticks(&app, &have)
        })
        .collect();
    let t = Turn {
        p: 2,
        row: 0,
        col: 4,
        axis: DVec3::Y,
        angle: 0.05,
    };
    assert!(apply_turn(&mut app, &doc, &t));
    let marked = check_marks(&mut app, ids[2], &was[2], &before[2], "last car");
    let rows = was[2].finest_points().rows();
    let span = app
        .world()
        .get::<streamline_studio::ecs::joined::PatchWork>(ids[2])
        .and_then(|w| w.rows)
        .expect("rows placed again");
    assert_eq!(
        marked,
        span.hi - span.lo + 1,
        "the rows placed again, {span:?}"
    );
    assert!(
        marked > 0 && marked < rows * 2 / 3,
        "{marked} of {rows} marked"
    );
    let have = entities(&mut app, ids[1]);
    assert_eq!(
        ticks(&app, &have),
        before[1],
        "the middle car is not marked"
    );
}

/// The antipodal warnings of every patch (docs/math.md §1), rescanned in
/// the windows an edit marked, are those of a fresh build of the document
/// as it stands; a later patch's sentences name it. Before the edits there
/// are none (control).
#[test]
fn every_patch_s_warnings_equal_a_fresh_build() {
    let lines = |app: &App| app.world().resource::<BuildWarnings>().lines.clone();
    for doc in [hood(), chained_cars(3, 3)] {
        let mut app = app(&doc);
        assert!(lines(&app).is_empty(), "{:?}", lines(&app));
        let names: Vec<String> = doc.patches.iter().map(|p| p.name.clone()).collect();
        let x = DVec3::new(1.0, 0.0, 0.5).normalize();
        let y = DVec3::new(0.2, 1.0, 0.1).normalize();
        let set = |p: usize, row: usize, col: usize, dir: DVec3| (p, row, col, dir);
        let steps = [
            set(2, 2, 2, x),
            set(2, 2, 3, -x),
            set(1, 3, 1, y),
            set(1, 3, 2, -y),
            set(1, 4, 1, -y),
            set(0, 1, 2, x),
            set(0, 1, 3, -x),
            set(2, 2, 3, y),
        ];
        let mut most = 0;
        let mut all = String::new();
        for (i, (p, row, col, dir)) in steps.into_iter().enumerate() {
            let label = format!("{}: step {i}", names[p]);
            ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch(names[p].clone()))).unwrap();
            ecs::apply(&mut app, Edit::SetDirection { row, col, dir })
                .unwrap_or_else(|e| panic!("{label}: {e}"));
            let now = document(app.world()).unwrap();
            let fresh = ecs::headless_document_app(&now, None, ModelConfig::default());
            assert_eq!(lines(&app), lines(&fresh), "{label}");
            most = most.max(lines(&app).len());
            all.push_str(&lines(&app).join("\n"));
        }
        assert!(
            most >= 3,
            "the steps made antipodal pairs ({most} lines at most)"
        );
        for n in &names {
            assert!(
                all.contains(&format!("patch `{n}`: antipodal blend between")),
                "{all}"
            );
        }
    }
}

/// While the editor defers a drag's work (`DeferNormals`) the warnings are
/// not scanned; the first frame after it scans whole every patch whose
/// levels changed meanwhile, and the warnings are a fresh build's (control:
/// during the drag they are not).
#[test]
fn warnings_deferred_by_a_drag_are_a_fresh_build_s_after_it() {
    use streamline_studio::ecs::DeferNormals;
    let lines = |app: &App| app.world().resource::<BuildWarnings>().lines.clone();
    let doc = hood();
    let mut app = app(&doc);
    let x = DVec3::new(1.0, 0.0, 0.5).normalize();
    let y = DVec3::new(0.2, 1.0, 0.1).normalize();
    app.insert_resource(DeferNormals(true));
    for (p, row, col, dir) in [
        (2, 2, 2, x),
        (2, 2, 3, -x),
        (1, 3, 1, y),
        (1, 3, 2, -y),
        (0, 1, 2, x),
        (0, 1, 3, -x),
    ] {
        let name = doc.patches[p].name.clone();
        ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch(name))).unwrap();
        ecs::apply(&mut app, Edit::SetDirection { row, col, dir }).unwrap();
    }
    let now = document(app.world()).unwrap();
    let fresh = ecs::headless_document_app(&now, None, ModelConfig::default());
    assert!(lines(&fresh).len() >= 3, "{:?}", lines(&fresh));
    assert!(lines(&app).is_empty(), "deferred: {:?}", lines(&app));
    app.insert_resource(DeferNormals(false));
    app.update();
    assert_eq!(lines(&app), lines(&fresh));
}

/// A G2 run's member reports its last build as a kept patch does
/// (`PatchWork`, which Stats shows for the active patch): an edit of the
/// screen re-blends part of the run's merged net in place and names the
/// rows it placed again; another display depth builds it whole (control).
#[test]
fn a_g2_member_reports_what_its_run_did() {
    use streamline_studio::ecs::joined::PatchWork;
    let doc = hood();
    let mut app = app(&doc);
    let ids = patches(&mut app);
    let t = Turn {
        p: 1,
        row: 2,
        col: 2,
        axis: DVec3::Y,
        angle: 0.05,
    };
    assert!(apply_turn(&mut app, &doc, &t));
    let w = app
        .world()
        .get::<PatchWork>(ids[1])
        .cloned()
        .expect("reported");
    // the run's whole build: every tangent of the hood's and the screen's
    // levels 1 ..= d (their shared seam columns once each, so at most this)
    let all: usize = (ids[..2].iter())
        .flat_map(|&e| stack(&app, e).unwrap().levels.into_iter().skip(1))
        .map(|l| l.tangents.data().len())
        .sum();
    assert!(!w.whole, "{w:?}");
    assert!(w.reblended > 0 && w.reblended < all, "{w:?} of {all}");
    let placed = app.world().get::<PatchSurface>(ids[1]).unwrap().placed;
    assert_eq!(w.rows, placed);
    ecs::apply(&mut app, Edit::SetDisplayDepth(doc.display_depth + 1)).unwrap();
    let w = app.world().get::<PatchWork>(ids[1]).cloned().unwrap();
    assert!(w.whole, "{w:?}");
}
