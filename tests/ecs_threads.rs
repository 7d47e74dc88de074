//! The ECS pipeline with the kernel's helper thread on and off: what an
//! edit rebuilds in two halves on the helper equals one thread's numbers
//! and a fresh build's.

mod common;

use common::{points, scene};
use streamline_kernel::{DVec3, Grid, levels::presets};
use streamline_studio::ecs::{self, Edit, Stats, SurfaceData};
use streamline_studio::scene::Scene;

/// The streamlines an edit sums again from a point are integrated in two
/// halves on the kernel's helper thread when there are many (on the car at
/// depth 5, an interior edit re-integrates 161 rows of 258 points): the
/// surface and the row boxes are those of a fresh build, bit for bit, and
/// the same as on one thread.
#[test]
fn many_rows_summed_again_in_two_halves_equal_a_fresh_build() {
    let bits = |g: &Grid<DVec3>| -> Vec<[u64; 3]> {
        g.data()
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect()
    };
    let edits = [
        ((2, 4), 0.05),
        ((2, 4), -0.02),
        ((3, 1), 0.03),
        ((0, 0), 0.04),
    ];
    let mut runs = Vec::new();
    for helper in [true, false] {
        streamline_kernel::parallel::set_enabled(helper);
        let mut app = ecs::headless_app(Scene::from_design("car1", presets::car1(), 5));
        let mut after = Vec::new();
        for ((row, col), radians) in edits {
            ecs::apply(
                &mut app,
                Edit::Rotate {
                    row,
                    col,
                    axis: DVec3::Y,
                    radians,
                },
            )
            .unwrap();
            let stats = app.world().resource::<Stats>().clone();
            assert!(!stats.last.full_rebuild);
            let got = points(&app);
            if (row, col) == (2, 4) {
                // the case in point: enough rows and points for two halves
                let n = stats.last.streamlines_reintegrated;
                assert!(n >= 8 && n * got.cols() >= 16_384, "{n} rows");
            }
            let fresh = ecs::headless_app(scene(&app));
            assert!(
                bits(&got) == bits(&points(&fresh)),
                "edit at ({row}, {col})"
            );
            let surface = app.world().resource::<SurfaceData>();
            let (lo, hi) = got.data().iter().fold(
                (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                |(lo, hi), &p| (lo.min(p), hi.max(p)),
            );
            assert_eq!(surface.bounds(), Some([lo, hi]));
            after.push(bits(&got));
        }
        runs.push(after);
    }
    streamline_kernel::parallel::set_enabled(true);
    assert!(runs[0] == runs[1], "two halves against one thread");
}
