//! The ECS layer: random edit sequences through the pipeline equal a full
//! rebuild from scratch; single edits stay local; multiresolution details;
//! bounded undo.

mod common;

use bevy::prelude::*;
use common::{max_diff, points, scene};
use proptest::prelude::*;
use streamline_kernel::levels::incremental::{place_row, reference_levels};
use streamline_kernel::levels::multires;
use streamline_kernel::{BlendOrder, DVec3, Design, Grid, SurfaceScheme, levels::presets};
use streamline_studio::ecs::{self, Edit, ModelConfig, Stats, SurfaceData};
use streamline_studio::scene::Scene;

fn design(rows: usize, cols: usize, scheme: SurfaceScheme, order: BlendOrder, seed: f64) -> Design {
    let net = Grid::new(
        rows,
        cols,
        (0..rows * cols)
            .map(|i| {
                let (r, c) = ((i / cols) as f64, (i % cols) as f64);
                DVec3::new(
                    1.0,
                    0.25 * (0.7 * r + seed).sin(),
                    0.35 * (0.9 * c - seed).cos(),
                )
                .normalize()
            })
            .collect(),
    )
    .unwrap();
    let s = Grid::new(
        rows,
        cols,
        (0..rows * cols).map(|i| (i % cols) as f64 * 0.5).collect(),
    )
    .unwrap();
    let t = (0..rows).map(|r| r as f64 * 0.3).collect();
    Design::new(
        &net,
        s,
        t,
        cols / 3,
        scheme,
        order,
        presets::car1().initial().clone(),
    )
    .unwrap()
}

/// The surface of `scene` from scratch, by the kernel's plain path.
fn reference_points(scene: &Scene) -> Grid<DVec3> {
    let levels = reference_levels(&scene.design, &scene.details, scene.display_depth).unwrap();
    let l = levels.last().unwrap();
    let mut data = Vec::new();
    let mut buf = Vec::new();
    for r in 0..l.tangents.rows() {
        place_row(scene.design.initial(), &l.tangents, &l.params, r, &mut buf);
        data.extend_from_slice(&buf);
    }
    Grid::new(l.tangents.rows(), l.tangents.cols() + 1, data).unwrap()
}

#[derive(Debug, Clone)]
enum Op {
    Dir(usize, usize, DVec3),
    Rot(usize, usize, DVec3, f64),
    Len(usize, usize, f64),
    Clear(usize, usize),
    EditDepth(u32),
    Undo,
    Redo,
}

fn unit() -> impl Strategy<Value = DVec3> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
        .prop_filter("non-zero", |(x, y, z)| x * x + y * y + z * z > 1e-6)
        .prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        4 => (0usize..64, 0usize..64, unit()).prop_map(|(r, c, v)| Op::Dir(r, c, v)),
        2 => (0usize..64, 0usize..64, unit(), -3.0f64..3.0).prop_map(|(r, c, a, t)| Op::Rot(r, c, a, t)),
        1 => (0usize..64, 1usize..64, 0.7f64..1.4).prop_map(|(r, c, k)| Op::Len(r, c, k)),
        1 => (0usize..64, 0usize..64).prop_map(|(r, c)| Op::Clear(r, c)),
        1 => (0u32..3).prop_map(Op::EditDepth),
        1 => Just(Op::Undo),
        1 => Just(Op::Redo),
    ]
}

fn scheme() -> impl Strategy<Value = (SurfaceScheme, BlendOrder)> {
    (
        prop_oneof![
            (0.0f64..2.0).prop_map(|omega| SurfaceScheme::Kobbelt { omega }),
            Just(SurfaceScheme::CatmullClark),
            Just(SurfaceScheme::DooSabin),
        ],
        prop_oneof![Just(BlendOrder::SFirst), Just(BlendOrder::TFirst)],
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// docs/architecture.md: the result of any edit sequence equals a rebuild from scratch to 1e-12.
    #[test]
    fn ecs_edits_equal_full_rebuild(
        (sch, order) in scheme(),
        seed in -2.0f64..2.0,
        ops in proptest::collection::vec(op(), 1..12),
    ) {
        let mut s = Scene::from_design("random", design(5, 6, sch, order, seed), 2);
        s.edit_depth = 0;
        let mut app = ecs::headless_app(s);
        for o in &ops {
            let (rows, cols) = {
                let sc = scene(&app);
                let c = sc.design.scheme().curve();
                let (mut r, mut k) = (sc.design.net().rows(), sc.design.net().cols());
                for _ in 0..sc.edit_depth { r = c.refined_len(r); k = c.refined_len(k); }
                (r, k)
            };
            let edit = match *o {
                Op::Dir(r, c, v) => Edit::SetDirection { row: r % rows, col: c % cols, dir: v },
                Op::Rot(r, c, a, t) => Edit::Rotate { row: r % rows, col: c % cols, axis: a, radians: t },
                Op::Len(r, c, k) => Edit::SetLength { row: r % 5, col: c % 6, coefficient: k },
                Op::Clear(r, c) => Edit::ClearDetail { row: r % rows, col: c % cols },
                Op::EditDepth(d) => Edit::SetEditDepth(d),
                Op::Undo => Edit::Undo,
                Op::Redo => Edit::Redo,
            };
            let _ = ecs::apply(&mut app, edit); // refusals are fine; the model must stay consistent
        }
        let sc = scene(&app);
        let got = points(&app);
        let want = reference_points(&sc);
        let d = max_diff(&got, &want);
        prop_assert!(d <= 1e-12, "incremental vs kernel reference: {d:e}");
        let fresh = ecs::headless_app(sc);
        let d2 = max_diff(&got, &points(&fresh));
        prop_assert!(d2 <= 1e-12, "incremental vs fresh ECS build: {d2:e}");
        // windows re-blended and streamlines summed again from a column on
        // give the very bits of a build from scratch
        let bits = |g: &Grid<DVec3>| g.data().iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>();
        prop_assert!(bits(&got) == bits(&points(&fresh)), "incremental vs fresh ECS build differ in their bits");
        // The mesh follows the points: the normals patched row by row are
        // those of a mesh made afresh from them, and so are the triangles and
        // the bounding box kept row by row.
        let surface = app.world().resource::<SurfaceData>();
        let fresh_mesh = streamline_kernel::streamline::surface_mesh::SurfaceMesh::from_points(&got);
        prop_assert_eq!(&surface.mesh(), &fresh_mesh);
        prop_assert!(surface.normals.iter().all(|n| n.is_finite()));
        let (lo, hi) = got.data().iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        prop_assert_eq!(surface.bounds(), Some([lo, hi]));
    }
}

/// On a 20×20 net at depth 3 (Kobbelt), one interior edit re-blends
/// at most 20 % of the tangents and re-integrates at most 30 % of the streamlines.
#[test]
fn single_edit_is_local_20x20_depth_3() {
    let s = Scene::from_design(
        "grid20",
        design(20, 20, SurfaceScheme::default(), BlendOrder::SFirst, 0.3),
        3,
    );
    let mut app = ecs::headless_app(s);
    ecs::apply(
        &mut app,
        Edit::SetDirection {
            row: 10,
            col: 9,
            dir: DVec3::new(0.4, 0.8, 0.2),
        },
    )
    .unwrap();
    let stats = app.world().resource::<Stats>().clone();
    let blendable: usize = stats.levels[1..].iter().map(|(r, c)| r * c).sum();
    let frac = stats.last.tangents_reblended as f64 / blendable as f64;
    let lines = stats.last.streamlines_reintegrated as f64 / stats.streamlines as f64;
    println!(
        "20x20 d3: re-blended {} of {blendable} ({:.1} %), re-integrated {} of {} ({:.1} %)",
        stats.last.tangents_reblended,
        100.0 * frac,
        stats.last.streamlines_reintegrated,
        stats.streamlines,
        100.0 * lines
    );
    assert!(!stats.last.full_rebuild);
    assert!(frac <= 0.20, "re-blended {:.3} of the tangents", frac);
    assert!(
        lines <= 0.30,
        "re-integrated {:.3} of the streamlines",
        lines
    );
    assert!(stats.last.streamlines_reintegrated > 0);
}

fn car_app(edit_depth: u32, display: u32) -> App {
    let mut s = Scene::from_design("car1", presets::car1(), display);
    s.edit_depth = edit_depth;
    ecs::headless_app(s)
}

fn level_tangent_and_base(app: &mut App, level: u32, r: usize, c: usize) -> (DVec3, DVec3) {
    let w = app.world_mut();
    let mut q = w.query::<&ecs::components::LevelData>();
    let l = q
        .iter(w)
        .find(|l| l.0.level == level)
        .expect("level exists");
    (l.0.tangents.get(r, c), l.0.base().get(r, c))
}

/// docs/math.md §5: a detail is kept (as a rotation from its subdivided tangent) when a
/// coarse edit changes the surface; undoing the coarse edit gives back the
/// exact surface; details survive save/load; depth down and up restores the surface.
#[test]
fn multiresolution_details() {
    let mut app = car_app(2, 3);
    let (r, c) = (10, 16);
    let (t0, b0) = level_tangent_and_base(&mut app, 2, r, c);
    assert_eq!(t0, b0, "no detail yet");
    let target = (b0 + DVec3::new(0.0, 0.0, 0.5)).normalize();
    ecs::apply(
        &mut app,
        Edit::SetDirection {
            row: r,
            col: c,
            dir: target,
        },
    )
    .unwrap();
    let (t1, b1) = level_tangent_and_base(&mut app, 2, r, c);
    assert!(
        (t1 - target).length() < 1e-12,
        "detail applied: {t1} vs {target}"
    );
    let angle_before = t1.angle_between(b1);
    let with_detail = points(&app);
    let local_before = scene(&app).details[&(2, r, c)];

    // A coarse edit nearby: the detail is carried along.
    ecs::apply(&mut app, Edit::SetEditDepth(0)).unwrap();
    ecs::apply(
        &mut app,
        Edit::Rotate {
            row: 2,
            col: 4,
            axis: DVec3::Y,
            radians: 0.3,
        },
    )
    .unwrap();
    let (t2, b2) = level_tangent_and_base(&mut app, 2, r, c);
    assert!(
        (b2 - b1).length() > 1e-3,
        "the coarse edit moved the base tangent"
    );
    assert!(
        (t2.angle_between(b2) - angle_before).abs() < 1e-12,
        "the detail's angle to its base is kept: {} vs {angle_before}",
        t2.angle_between(b2)
    );
    assert_eq!(
        scene(&app).details[&(2, r, c)],
        local_before,
        "the stored detail is unchanged"
    );
    let expected = multires::from_local(
        &{
            let w = app.world_mut();
            let mut q = w.query::<&ecs::components::LevelData>();
            q.iter(w).find(|l| l.0.level == 2).unwrap().0.base().clone()
        },
        r,
        c,
        local_before,
    );
    assert!((t2 - expected).length() < 1e-15);

    // Undo the coarse edit: exactly the previous surface.
    ecs::apply(&mut app, Edit::Undo).unwrap();
    assert_eq!(
        max_diff(&points(&app), &with_detail),
        0.0,
        "undo restores the exact surface"
    );

    // Depth down and up.
    ecs::apply(&mut app, Edit::SetDisplayDepth(1)).unwrap();
    assert_ne!(points(&app).rows(), with_detail.rows());
    ecs::apply(&mut app, Edit::SetDisplayDepth(3)).unwrap();
    assert_eq!(
        max_diff(&points(&app), &with_detail),
        0.0,
        "depth down and up restores the surface"
    );

    // Save and load.
    let dir = std::env::temp_dir().join(format!("ss-multires-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("detail.ron");
    ecs::apply(&mut app, Edit::Save(path.clone())).unwrap();
    let loaded = streamline_studio::scene::design::document_io::load_scene(&path).unwrap();
    assert_eq!(loaded.details.len(), 1);
    let app2 = ecs::headless_app(loaded);
    assert_eq!(
        max_diff(&points(&app2), &with_detail),
        0.0,
        "details survive save/load"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Undo history is bounded by the configured length.
#[test]
fn undo_history_is_bounded() {
    let s = Scene::from_design("car1", presets::car1(), 2);
    let mut app = ecs::headless_app_with(s, ModelConfig { history_limit: 3 });
    for i in 0..5 {
        ecs::apply(
            &mut app,
            Edit::Rotate {
                row: 1,
                col: i,
                axis: DVec3::Z,
                radians: 0.1,
            },
        )
        .unwrap();
    }
    for _ in 0..3 {
        ecs::apply(&mut app, Edit::Undo).unwrap();
    }
    let e = ecs::apply(&mut app, Edit::Undo).unwrap_err().to_string();
    assert!(e.contains("nothing to undo"), "{e}");
}

/// A drag (edits of one group) is one undo step.
#[test]
fn grouped_edits_are_one_undo_step() {
    let mut app = car_app(0, 2);
    let start = points(&app);
    for k in 0..10 {
        app.world_mut().write_message(ecs::EditMessage {
            edit: Edit::Rotate {
                row: 3,
                col: 3,
                axis: DVec3::Y,
                radians: 0.02 * k as f64,
            },
            group: Some(7),
        });
        app.update();
    }
    assert_eq!(app.world().resource::<ecs::History>().undo_len(), 1);
    ecs::apply(&mut app, Edit::Undo).unwrap();
    assert_eq!(max_diff(&points(&app), &start), 0.0);
}

/// Esc during a drag: `CancelGroup` restores the scene from before the drag and
/// leaves the history as it was (the earlier step is still undoable, redo is kept).
#[test]
fn cancelled_drag_restores_and_leaves_history() {
    let mut app = car_app(0, 3);
    ecs::apply(
        &mut app,
        Edit::Rotate {
            row: 1,
            col: 1,
            axis: DVec3::Z,
            radians: 0.3,
        },
    )
    .unwrap();
    let before = points(&app);
    for k in 1..6 {
        app.world_mut().write_message(ecs::EditMessage {
            edit: Edit::Rotate {
                row: 4,
                col: 2,
                axis: DVec3::X,
                radians: 0.05 * k as f64,
            },
            group: Some(11),
        });
        app.update();
    }
    assert!(max_diff(&points(&app), &before) > 1e-3);
    assert_eq!(app.world().resource::<ecs::History>().undo_len(), 2);
    ecs::apply(&mut app, Edit::CancelGroup(11)).unwrap();
    assert_eq!(max_diff(&points(&app), &before), 0.0);
    assert!(max_diff(&points(&app), &reference_points(&scene(&app))) < 1e-12);
    assert_eq!(app.world().resource::<ecs::History>().undo_len(), 1);
    assert_eq!(app.world().resource::<ecs::History>().redo_len(), 0);
    // a second cancel, or one of another group, is refused
    assert!(ecs::apply(&mut app, Edit::CancelGroup(11)).is_err());
    assert!(
        app.world().resource::<ecs::Model>().unsaved,
        "the earlier edit is still unsaved"
    );
    // on a fresh scene, a cancelled drag leaves it saved
    let mut fresh = car_app(0, 2);
    fresh.world_mut().write_message(ecs::EditMessage {
        edit: Edit::Rotate {
            row: 2,
            col: 2,
            axis: DVec3::Z,
            radians: 0.2,
        },
        group: Some(5),
    });
    fresh.update();
    assert!(fresh.world().resource::<ecs::Model>().unsaved);
    ecs::apply(&mut fresh, Edit::CancelGroup(5)).unwrap();
    assert!(!fresh.world().resource::<ecs::Model>().unsaved);
    ecs::apply(&mut app, Edit::Undo).unwrap();
    assert_eq!(app.world().resource::<ecs::History>().undo_len(), 0);
}

/// Edits with unusable values are refused with a message and change nothing.
#[test]
fn bad_edits_are_refused() {
    let mut app = car_app(0, 2);
    let start = points(&app);
    for (edit, text) in [
        (
            Edit::SetDirection {
                row: 0,
                col: 0,
                dir: DVec3::ZERO,
            },
            "zero or not finite",
        ),
        (
            Edit::SetDirection {
                row: 0,
                col: 0,
                dir: DVec3::new(f64::NAN, 1.0, 0.0),
            },
            "zero or not finite",
        ),
        (
            Edit::Rotate {
                row: 0,
                col: 0,
                axis: DVec3::ZERO,
                radians: 1.0,
            },
            "rotation axis",
        ),
        (
            Edit::Rotate {
                row: 0,
                col: 0,
                axis: DVec3::X,
                radians: f64::INFINITY,
            },
            "not finite",
        ),
        (
            Edit::SetLength {
                row: 0,
                col: 1,
                coefficient: f64::NAN,
            },
            "positive finite",
        ),
        (
            Edit::SetScheme(SurfaceScheme::Kobbelt { omega: 3.0 }),
            "omega",
        ),
        (Edit::SetEditDepth(14), "choose a smaller depth"),
        (
            Edit::Load("/nonexistent/x.ron".into()),
            "the current scene is kept",
        ),
    ] {
        let e = ecs::apply(&mut app, edit.clone())
            .expect_err(&format!("{edit:?} must be refused"))
            .to_string();
        assert!(e.contains(text), "{edit:?}: {e}");
        assert_eq!(
            max_diff(&points(&app), &start),
            0.0,
            "{edit:?} changed the surface"
        );
    }
    assert_eq!(app.world().resource::<ecs::History>().undo_len(), 0);
}

/// An edit of the initial curve is "place every streamline again,
/// re-blend nothing": no tangent is re-blended, every streamline is
/// integrated again, and the surface has the very bits of a build from
/// scratch of the new scene. The initial curve's length and start point are
/// written into the patch's component directly: change detection alone
/// decides what is redone.
#[test]
fn replacing_the_streamlines_equals_a_fresh_build() {
    let mut app = car_app(0, 3);
    let c = scene(&app).design.initial().clone();
    let moved = streamline_kernel::streamline::initial_curve::InitialCurve::new(
        c.qi().tangents(),
        c.qi().order(),
        c.length() * 1.3,
        c.origin() + DVec3::new(0.5, -0.2, 0.1),
    )
    .expect("a valid initial curve");
    {
        let w = app.world_mut();
        let patch = ecs::patch::patch_entity(w).expect("a patch");
        let mut p = w.get_mut::<ecs::patch::PatchPlacement>(patch).unwrap();
        p.initial_length = moved.length();
        p.initial_origin = moved.origin();
        w.resource_mut::<Stats>().last = Default::default();
    }
    app.update();
    let stats = app.world().resource::<Stats>().clone();
    assert_eq!(stats.last.tangents_reblended, 0, "{:?}", stats.last);
    assert!(!stats.last.full_rebuild);
    assert_eq!(stats.last.streamlines_reintegrated, stats.streamlines);
    let fresh = ecs::headless_app(scene(&app));
    let bits = |g: &Grid<DVec3>| {
        g.data()
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect::<Vec<_>>()
    };
    let (got, want) = (points(&app), points(&fresh));
    assert!(
        bits(&got) == bits(&want),
        "re-placed streamlines differ from a fresh build"
    );
    let before = points(&car_app(0, 3));
    assert!(max_diff(&got, &before) > 1e-3, "the surface moved");
    assert_eq!(
        app.world().resource::<SurfaceData>().mesh(),
        fresh.world().resource::<SurfaceData>().mesh()
    );
}
