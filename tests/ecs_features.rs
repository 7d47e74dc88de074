//! ECS features beyond the pipeline: fine tuning (docs/math.md §6) re-integrates only
//! the streamlines its edit reaches and equals a fresh build; interpolated
//! control tangents (docs/math.md §7) are reached at the limit and saved; the
//! antipodal warnings, rescanned in the re-blended windows only, are a fresh
//! build's.

mod common;

use common::{max_diff, points, scene};
use streamline_kernel::{BlendOrder, DVec3, Grid, SurfaceScheme, levels::presets};
use streamline_studio::ecs::{self, Edit, Stats};
use streamline_studio::scene::Scene;

/// Fine tuning (docs/math.md §6) through the ECS: an edit of one control value
/// re-blends nothing and re-integrates only the streamlines inside that
/// value's support across the rows; the result equals a fresh build of the
/// same scene, and undo gives back the exact surface.
#[test]
fn tuning_edit_is_local_and_equals_a_fresh_build() {
    use streamline_kernel::finetune::bspline::TensorBSpline;
    use streamline_kernel::finetune::{Constraint, SurfaceTuning};
    let mut s = Scene::from_design("car", presets::car1(), 3);
    s.tuning = Some(SurfaceTuning {
        function: TensorBSpline::new(2, 2, Grid::filled(6, 4, 1.0)).unwrap(),
        constraint: Constraint::Free,
    });
    let mut app = ecs::headless_app(s);
    let before = points(&app);
    ecs::apply(
        &mut app,
        Edit::SetTuningValue {
            row: 0,
            col: 1,
            value: 1.7,
        },
    )
    .unwrap();
    let stats = app.world().resource::<Stats>().last.clone();
    let rows = before.rows();
    // M_0 of a quadratic with 6 values lives on the first of 4 spans: a quarter of the rows
    assert_eq!(stats.tangents_reblended, 0, "fine tuning re-blends nothing");
    assert!(
        stats.streamlines_reintegrated <= rows / 4 + 1 && stats.streamlines_reintegrated > 0,
        "re-integrated {} of {rows} streamlines",
        stats.streamlines_reintegrated
    );
    let after = points(&app);
    assert!(
        max_diff(&before, &after) > 1e-3,
        "the value changed the surface"
    );
    let fresh = ecs::headless_app(scene(&app));
    assert!(
        max_diff(&points(&fresh), &after) < 1e-12,
        "incremental fine tuning equals a fresh build"
    );
    ecs::apply(&mut app, Edit::SetTuningConstraint(Constraint::KeepEnds)).unwrap();
    let kept = points(&app);
    let last = kept.cols() - 1;
    for r in 0..rows {
        for c in [0, last] {
            let d = (kept.get(r, c) - before.get(r, c)).length();
            assert!(d < 1e-10, "end ({r}, {c}) moved by {d:e} under keep-ends");
        }
    }
    ecs::apply(&mut app, Edit::Undo).unwrap();
    ecs::apply(&mut app, Edit::Undo).unwrap();
    assert_eq!(
        max_diff(&points(&app), &before),
        0.0,
        "undo restores exactly"
    );
}

/// docs/math.md §7, on the Gaussian sphere: with "interpolate control tangents" the level-0 net
/// the ECS subdivides has limit tangents (Catmull–Clark and Doo–Sabin, both
/// blend orders) equal to the designer's interior control tangents within
/// 1e-9 rad; the border is kept; the option survives save → load.
#[test]
fn interpolated_control_tangents_are_reached_at_the_limit() {
    use streamline_kernel::levels::tangent_interpolation::limit_tangent;
    use streamline_studio::ecs::components::{LevelData, SubdivisionLevel};
    for scheme in [SurfaceScheme::CatmullClark, SurfaceScheme::DooSabin] {
        for order in [BlendOrder::SFirst, BlendOrder::TFirst] {
            let mut d = presets::car1();
            d.set_scheme(scheme).unwrap();
            d.set_order(order);
            let mut s = Scene::from_design("car", d, 2);
            s.interpolate_tangents = true;
            let mut app = ecs::headless_app(s.clone());
            let w = app.world_mut();
            let mut q = w.query::<(&SubdivisionLevel, &LevelData)>();
            let root = q
                .iter(w)
                .find(|(l, _)| l.0 == 0)
                .map(|(_, d)| d.0.tangents.clone())
                .unwrap();
            let design = &s.design.net();
            let mut moved = 0.0f64;
            for r in 0..design.rows() {
                for c in 0..design.cols() {
                    match limit_tangent(scheme, order, &root, r, c) {
                        Some(l) => {
                            let a = l.cross(design.get(r, c)).length();
                            assert!(a < 1e-9, "{scheme:?} {order:?} ({r},{c}): {a:e}");
                            moved = moved.max((root.get(r, c) - design.get(r, c)).length());
                        }
                        None => assert_eq!(root.get(r, c), design.get(r, c), "border kept"),
                    }
                }
            }
            assert!(
                moved > 1e-3,
                "the interior control tangents moved ({moved})"
            );
            let dir = std::env::temp_dir().join(format!("streamline-pi-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            let path = dir.join("s.ron");
            streamline_studio::scene::design::document_io::save_scene(&s, &path).unwrap();
            assert!(
                streamline_studio::scene::design::document_io::load_scene(&path)
                    .unwrap()
                    .interpolate_tangents
            );
            let _ = std::fs::remove_dir_all(&dir);
        }
    }
}

/// The antipodal warnings (docs/math.md §1) after each edit, found by
/// rescanning only the windows the blend stage re-blended, are those of a
/// fresh build of the same scene: pairs made and undone on the control net,
/// pairs of details at level 1, and edits that move a pair's neighbour only.
#[test]
fn warnings_after_edits_equal_a_fresh_build() {
    use streamline_studio::ecs::patch::scene as scene_of;
    use streamline_studio::ecs::warnings::BuildWarnings;
    let lines = |app: &bevy::prelude::App| app.world().resource::<BuildWarnings>().lines.clone();
    let mut app = ecs::headless_app(Scene::from_design("car", presets::car1(), 3));
    let (x, y) = (DVec3::new(1.0, 0.0, 0.5), DVec3::new(0.2, 1.0, 0.1));
    let set = |row, col, dir| Edit::SetDirection { row, col, dir };
    let steps = [
        set(2, 4, x),
        set(2, 5, -x),
        set(3, 4, -x),
        set(0, 0, y),
        set(0, 1, -y),
        set(1, 0, -y),
        set(2, 6, x),
        Edit::Undo,
        Edit::Undo,
        set(5, 3, y),
        Edit::SetEditDepth(1),
        set(4, 6, y),
        set(4, 7, -y),
        set(5, 6, -y),
        Edit::ClearDetail { row: 4, col: 7 },
        Edit::Undo,
        Edit::SetEditDepth(0),
        set(2, 5, y),
    ];
    let mut most = 0;
    for (i, e) in steps.into_iter().enumerate() {
        let label = format!("step {i} ({e:?})");
        ecs::apply(&mut app, e).unwrap_or_else(|err| panic!("{label}: {err}"));
        let fresh = ecs::headless_app(scene_of(app.world()));
        assert_eq!(lines(&app), lines(&fresh), "{label}");
        most = most.max(lines(&app).len());
    }
    assert!(
        most >= 3,
        "the steps made antipodal pairs ({most} lines at most)"
    );
}
