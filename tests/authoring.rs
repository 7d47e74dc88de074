//! Authoring through the ECS (`docs/math.md §9`): an initial-curve
//! or anchor edit places every streamline again, moved rigidly, re-blending no
//! tangent, and equals a fresh build; every authoring edit is one undo step
//! that restores the scene bit for bit; structure edits drop the details and
//! say so; the mirror's halves come out of one doubled build.

mod common;

use common::{max_diff, points, scene};
use proptest::prelude::*;
use streamline_kernel::authoring::{Axis, Template};
use streamline_kernel::{DVec3, levels::presets};
use streamline_studio::ecs::authoring::AuthorEdit;
use streamline_studio::ecs::{self, Edit, Stats};
use streamline_studio::scene::Scene;

fn car(depth: u32) -> bevy::prelude::App {
    ecs::headless_app(Scene::from_design("car", presets::car1(), depth))
}

fn author(app: &mut bevy::prelude::App, e: AuthorEdit) -> Result<String, ecs::EditError> {
    ecs::apply(app, Edit::Author(e))
}

/// The scene's file form and its design's bits.
fn bits(s: &Scene) -> (String, Vec<u64>) {
    let d = &s.design;
    let mut v: Vec<u64> = d
        .net()
        .data()
        .iter()
        .flat_map(|t| t.to_array().map(f64::to_bits))
        .collect();
    v.extend(d.params().s.data().iter().map(|x| x.to_bits()));
    v.extend(
        d.params()
            .t
            .iter()
            .chain(&d.params().sigma)
            .map(|x| x.to_bits()),
    );
    v.push(d.anchor() as u64);
    (s.to_ron(), v)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Eq. 1: an initial-curve edit moves every streamline rigidly by the
    /// curve's change at its `t`; nothing is re-blended; the result is a
    /// fresh build's; undo restores the scene bit for bit.
    #[test]
    fn initial_curve_edit_replaces_rigidly(which in 0usize..6, k in 0usize..4, x in -1.0f64..1.0) {
        let mut app = car(3);
        let before = points(&app);
        let start = bits(&scene(&app));
        let old = scene(&app).design;
        let e = match which {
            0 => AuthorEdit::SetInitialDirection { index: k, dir: DVec3::new(0.0, 1.0, x) },
            1 => AuthorEdit::RotateInitial { index: k, axis: DVec3::X, radians: 0.3 * x },
            2 => AuthorEdit::SetInitialLength(2.0 + x),
            3 => AuthorEdit::SetInitialOrigin(DVec3::new(x, 0.5 * x, 1.0)),
            4 => AuthorEdit::SetInitialOrder(2 + k % 3),
            _ => AuthorEdit::SetAnchor(k * 2),
        };
        author(&mut app, e).unwrap();
        let stats = app.world().resource::<Stats>().last.clone();
        prop_assert_eq!(stats.tangents_reblended, 0, "an initial-curve edit re-blends nothing");
        prop_assert!(!stats.full_rebuild);
        // an edit that sets what is already there (the anchor or order it
        // has) changes no component, so redoes nothing
        let noop = bits(&scene(&app)) == start;
        let placed = if noop { 0 } else { before.rows() };
        prop_assert_eq!(stats.streamlines_replaced, placed, "every streamline placed again, unless nothing changed");
        let after = points(&app);
        for r in 0..after.rows() {
            let shift = after.get(r, 0) - before.get(r, 0);
            for c in 0..after.cols() {
                let e = (after.get(r, c) - before.get(r, c) - shift).length();
                prop_assert!(e < 1e-12, "row {r} point {c}: not rigid ({e:e})");
            }
        }
        let new = scene(&app).design;
        if which < 5 {
            // the row's start moved with the curve at its t
            let lv = new.level(3).unwrap();
            for r in [0, after.rows() / 2, after.rows() - 1] {
                let t = lv.params.t[r];
                let moved = new.initial().point(t) - old.initial().point(t);
                let got = after.get(r, 0) - before.get(r, 0);
                prop_assert!((moved - got).length() < 1e-12, "row {r}: moved {got:?}, the curve {moved:?}");
            }
        }
        let fresh = ecs::headless_app(scene(&app));
        prop_assert!(max_diff(&points(&fresh), &after) == 0.0, "re-placing equals a fresh build, bit for bit");
        ecs::apply(&mut app, Edit::Undo).unwrap();
        prop_assert!(bits(&scene(&app)) == start, "undo restores the scene bit for bit");
        prop_assert!(max_diff(&points(&app), &before) == 0.0, "and the surface");
    }
}

#[test]
fn structure_edits_are_one_undo_step_and_drop_details() {
    let mut app = car(3);
    ecs::apply(&mut app, Edit::SetEditDepth(1)).unwrap();
    ecs::apply(
        &mut app,
        Edit::Rotate {
            row: 4,
            col: 6,
            axis: DVec3::Z,
            radians: 0.3,
        },
    )
    .unwrap();
    let start = bits(&scene(&app));
    let surface = points(&app);
    for (e, rows, cols) in [
        (AuthorEdit::insert(Axis::Row, 2), 7, 9),
        (AuthorEdit::insert(Axis::Column, 9), 6, 10),
        (AuthorEdit::delete(Axis::Row, 0), 5, 9),
        (AuthorEdit::delete(Axis::Column, 4), 6, 8),
        (
            AuthorEdit::SetStreamlineLength {
                row: 3,
                length: 5.0,
            },
            6,
            9,
        ),
    ] {
        let structural = !matches!(e, AuthorEdit::SetStreamlineLength { .. });
        let msg = author(&mut app, e.clone()).unwrap();
        let s = scene(&app);
        assert_eq!(
            (s.design.net().rows(), s.design.net().cols()),
            (rows, cols),
            "{e:?}"
        );
        if structural {
            assert!(
                s.details.is_empty() && msg.contains("1 multiresolution detail dropped"),
                "{e:?}: {msg}"
            );
        } else {
            assert_eq!(s.details.len(), 1, "a length edit keeps the details");
        }
        let fresh = ecs::headless_app(s);
        assert_eq!(
            max_diff(&points(&fresh), &points(&app)),
            0.0,
            "{e:?}: equals a fresh build"
        );
        ecs::apply(&mut app, Edit::Undo).unwrap();
        assert!(
            bits(&scene(&app)) == start,
            "{e:?}: undo restores the scene bit for bit"
        );
        assert_eq!(
            max_diff(&points(&app), &surface),
            0.0,
            "{e:?}: and the surface"
        );
    }
}

#[test]
fn new_design_replaces_the_scene_unsaved() {
    let mut app = car(3);
    author(
        &mut app,
        AuthorEdit::NewDesign {
            rows: 3,
            cols: 4,
            length: 2.0,
            template: Template::Flat { width: 1.0 },
            scheme: Default::default(),
        },
    )
    .unwrap();
    let m = app.world().resource::<ecs::Model>();
    assert!(
        m.unsaved && m.path.is_none(),
        "a new design is unsaved and has no file"
    );
    assert_eq!(ecs::patch::scene(app.world()).design.net().rows(), 3);
    assert_eq!(app.world().resource::<ecs::History>().undo_len(), 0);
    let p = points(&app);
    let [lo, hi] = streamline_kernel::streamline::surface_mesh::bounds(p.data().iter().copied());
    assert!(
        lo.length() < 1e-12 && (hi - DVec3::new(2.0, 1.0, 0.0)).length() < 1e-12,
        "{lo:?} {hi:?}"
    );
}

#[test]
fn mirror_toggle_restores_exactly_and_rotate_many_is_one_step() {
    let mut app = car(3);
    let plain = points(&app);
    author(&mut app, AuthorEdit::SetMirror(true)).unwrap();
    let on = points(&app);
    assert_eq!(on.rows(), 2 * plain.rows() - 1, "both halves");
    let plane = scene(&app).design.mirror_plane();
    for &v in scene(&app).design.net().row(0) {
        assert!(
            v.dot(plane.normal).abs() < 1e-14,
            "seam tangent in the plane"
        );
    }
    author(&mut app, AuthorEdit::SetMirror(false)).unwrap();
    author(&mut app, AuthorEdit::SetMirror(true)).unwrap();
    assert_eq!(
        max_diff(&points(&app), &on),
        0.0,
        "off and on again: the same surface"
    );
    // a seam edit stays in the plane
    ecs::apply(
        &mut app,
        Edit::SetDirection {
            row: 0,
            col: 3,
            dir: DVec3::new(1.0, 0.5, 0.2),
        },
    )
    .unwrap();
    let v = scene(&app).design.net().get(0, 3);
    assert!(
        v.dot(plane.normal).abs() < 1e-14,
        "the edited seam tangent stays in the plane: {v:?}"
    );
    // several handles, one undo step
    let before = bits(&scene(&app));
    ecs::apply(
        &mut app,
        Edit::RotateMany {
            handles: vec![(1, 1), (2, 2), (4, 7)],
            axis: DVec3::Z,
            radians: 0.2,
        },
    )
    .unwrap();
    ecs::apply(&mut app, Edit::Undo).unwrap();
    assert!(bits(&scene(&app)) == before, "RotateMany is one undo step");
    for _ in 0..4 {
        ecs::apply(&mut app, Edit::Undo).unwrap();
    }
    assert_eq!(
        max_diff(&points(&app), &plain),
        0.0,
        "undo back to the plain car"
    );
    assert!(!scene(&app).mirror);
}

/// With the mirror on, a tangent edit is dirty in both copies of the doubled
/// net and re-blends only there: each result equals a fresh build of the
/// same scene bit for bit and stays symmetric, and it re-blends fewer
/// tangents than a full build.
#[test]
fn mirrored_edits_are_incremental_and_exact() {
    let mut app = car(4);
    author(&mut app, AuthorEdit::SetMirror(true)).unwrap();
    let total = app.world().resource::<Stats>().last.tangents_reblended;
    for (row, col, deg) in [
        (0, 4, 12.0),
        (2, 4, -8.0),
        (5, 8, 20.0),
        (3, 0, 5.0),
        (1, 6, -15.0),
    ] {
        ecs::apply(
            &mut app,
            Edit::Rotate {
                row,
                col,
                axis: DVec3::new(0.2, 0.1, 1.0),
                radians: f64::to_radians(deg),
            },
        )
        .unwrap();
        let stats = app.world().resource::<Stats>().last.clone();
        assert!(!stats.full_rebuild, "({row}, {col}): incremental");
        assert!(
            stats.tangents_reblended < total,
            "({row}, {col}): re-blended {} of {total}",
            stats.tangents_reblended
        );
        let got = points(&app);
        let fresh = ecs::headless_app(scene(&app));
        assert_eq!(
            max_diff(&points(&fresh), &got),
            0.0,
            "({row}, {col}): equals a fresh build"
        );
        let plane = scene(&app).design.mirror_plane();
        let n = got.rows();
        let worst = (0..n)
            .flat_map(|r| (0..got.cols()).map(move |k| (r, k)))
            .map(|(r, k)| (plane.reflect_point(got.get(r, k)) - got.get(n - 1 - r, k)).length())
            .fold(0.0, f64::max);
        assert!(worst < 1e-12, "({row}, {col}): symmetric to {worst:e}");
    }
}
