//! The fine-tuning figures (docs/math.md §6, docs/finetune.md): the largest second
//! difference across the streamlines of the fine-tuned cars at depths 3–5,
//! with every constraint and with random tuning functions; the largest end
//! error; the export's fit (depth 4, checked at depth 5); the time of one
//! solve for every streamline's function.
//!
//! `cargo run -p streamline-kernel --release --example tune_smoothness`

use std::time::Instant;
use streamline_kernel::finetune::bspline::TensorBSpline;
use streamline_kernel::finetune::{Constraint, SurfaceTuning};
use streamline_kernel::grid::Grid;
use streamline_kernel::levels::incremental::{surface_rows, tuned_points};
use streamline_kernel::levels::presets;
use streamline_kernel::nurbs::{FitOptions, Samples, fit};
use streamline_kernel::{DVec3, Design, Level};

fn points(design: &Design, depth: u32, tuning: Option<&SurfaceTuning>) -> (Grid<DVec3>, Level) {
    let level = design.level(depth).expect("depth within the cap");
    let points = tuned_points(design.initial(), &level.tangents, &level.params, tuning);
    (points, level)
}

/// The largest `|P[r−1][c] − 2 P[r][c] + P[r+1][c]|` and its row.
fn second_difference(p: &Grid<DVec3>) -> (f64, usize) {
    let mut best = (0.0, 0);
    for r in 1..p.rows() - 1 {
        for c in 0..p.cols() {
            let d = (p.get(r - 1, c) - 2.0 * p.get(r, c) + p.get(r + 1, c)).length();
            if d > best.0 {
                best = (d, r);
            }
        }
    }
    best
}

/// The largest distance between the first or last points of two surfaces' rows.
fn end_error(a: &Grid<DVec3>, b: &Grid<DVec3>) -> f64 {
    let n = a.cols() - 1;
    (0..a.rows())
        .flat_map(|r| [0, n].map(|c| (a.get(r, c) - b.get(r, c)).length()))
        .fold(0.0, f64::max)
}

fn car1_tuned(constraint: Constraint) -> SurfaceTuning {
    SurfaceTuning {
        function: TensorBSpline::new(
            2,
            2,
            Grid::from_rows(&[
                vec![1.0, 0.8, 1.0, 1.0],
                vec![1.0, 1.0, 1.5, 1.0],
                vec![1.0, 0.8, 1.0, 1.0],
            ])
            .expect("3×4"),
        )
        .expect("quadratic"),
        constraint,
    }
}

fn main() {
    for (name, design) in [("car1", presets::car1()), ("car2", presets::car2())] {
        let constraints = [
            None,
            Some(Constraint::Free),
            Some(Constraint::KeepEnds),
            Some(Constraint::KeepClosed),
        ];
        for c in constraints {
            let t = c.map(car1_tuned);
            let mut line = format!("{name} {:>12}:", c.map_or("untuned", |c| c.name()));
            for d in 3..=5 {
                let (p, _) = points(&design, d, t.as_ref());
                let (sd, r) = second_difference(&p);
                line += &format!("  d{d} {sd:.2e} (row {r}/{})", p.rows());
                if c == Some(Constraint::KeepEnds) {
                    let (p0, _) = points(&design, d, None);
                    line += &format!(" ends {:.1e}", end_error(&p, &p0));
                }
            }
            println!("{line}");
        }
        // random functions, 4–6 values along, 3–4 across, quadratic, keep ends
        let mut seed = 12345u64;
        let mut rnd = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..4 {
            let (along, across) = (4 + k % 3, 3 + k % 2);
            let values: Vec<Vec<f64>> = (0..across)
                .map(|_| (0..along).map(|_| 0.6 + 0.8 * rnd()).collect())
                .collect();
            let f = SurfaceTuning {
                function: TensorBSpline::new(2, 2, Grid::from_rows(&values).expect("rows"))
                    .expect("quadratic"),
                constraint: Constraint::KeepEnds,
            };
            let mut line = format!("{name} random {k} ({across}×{along}) keep-ends:");
            for d in 3..=5 {
                let (p, _) = points(&design, d, Some(&f));
                let (p0, _) = points(&design, d, None);
                line += &format!(
                    "  d{d} {:.2e} (ends {:.1e})",
                    second_difference(&p).0,
                    end_error(&p, &p0)
                );
            }
            println!("{line}");
        }
        // the export's fit: depth 4, checked at depth 5, bicubic, 1e-4 of the diagonal
        for c in [None, Some(Constraint::KeepEnds)] {
            let t = c.map(car1_tuned);
            let (p4, l4) = points(&design, 4, t.as_ref());
            let (p5, l5) = points(&design, 5, t.as_ref());
            let data = Samples::from_level(&l4, p4).expect("samples");
            let check = Samples::from_level(&l5, p5).expect("samples");
            match fit(&data, &check, &FitOptions::DEFAULT) {
                Ok(f) => println!(
                    "{name} {:>9} fit d4: poles {:?}, largest deviation {:.3e} (tolerance {:.3e})",
                    c.map_or("untuned", |c| c.name()),
                    f.report.poles,
                    f.report.deviation.max,
                    f.report.tolerance
                ),
                Err(e) => println!("{name} {c:?} fit d4: {e}"),
            }
        }
    }
    // one solve for every streamline's function (car1, keep ends)
    let design = presets::car1();
    let t = car1_tuned(Constraint::KeepEnds);
    for d in 3..=5 {
        let level = design.level(d).expect("depth");
        let rows = surface_rows(&level.tangents, &level.params);
        let start = Instant::now();
        let n = 20;
        for _ in 0..n {
            std::hint::black_box(t.row_functions(rows));
        }
        let f = t.row_function(0.5);
        let start2 = Instant::now();
        let mut out = Vec::new();
        for _ in 0..n {
            for r in 0..rows.len() {
                streamline_kernel::finetune::fine_tune_into(
                    level.tangents.row(r),
                    level.params.s.row(r),
                    level.params.sigma[r],
                    DVec3::ZERO,
                    &f,
                    Constraint::KeepEnds,
                    &mut out,
                );
            }
        }
        println!(
            "  (streamline by streamline, solve and integrate: {:.3} ms)",
            start2.elapsed().as_secs_f64() * 1e3 / n as f64
        );
        println!(
            "car1 keep-ends d{d}: every streamline's function in {:.3} ms ({} streamlines)",
            start.elapsed().as_secs_f64() * 1e3 / n as f64,
            rows.len()
        );
    }
}
