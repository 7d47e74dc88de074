//! The paper's Table 1 side by side (subdivision vs QI curves, 5 control tangents)
//! and full builds of the 9×6 car surface at depths 0–5 (fresh, and into a
//! kept `Builder` on one thread with and without the vector path, and on two). The workloads are the
//! ones `streamline-studio bench` runs (`src/cli/bench/workloads.rs`); the `incremental`
//! group times one edit through the ECS against a full rebuild (docs/math.md §5), and
//! one fine-tuning value edit on the car at depth 3 (docs/math.md §6); the `loop` group
//! Loop subdivision of a ~20k-vertex open mesh under each boundary rule (docs/math.md §7);
//! the `authoring` group an insert, an initial-curve edit and the mirrored car (docs/math.md §9);
//! the `fit` group the B-spline fit of CAD export (docs/math.md §10).
//!
//! Run: `cargo bench --bench table1`. Figures and ratios: docs/benchmarks.md.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use streamline_studio::cli::bench::{ecs_rows, export_rows, loop_rows, workloads};

fn table1(c: &mut Criterion) {
    let mut g = c.benchmark_group("table1");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(40);
    for mut w in workloads::table1() {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

fn surface(c: &mut Criterion) {
    let mut g = c.benchmark_group("surface");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(20);
    for mut w in workloads::car_surface(0..=5)
        .into_iter()
        .chain(workloads::car_builder(5))
    {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

fn incremental(c: &mut Criterion) {
    let mut g = c.benchmark_group("incremental");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    for mut w in ecs_rows::incremental()
        .into_iter()
        .chain(ecs_rows::fine_tuning())
    {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

/// Loop subdivision of a ~20k-vertex open mesh, each boundary rule, levels 1–3 (docs/math.md §7).
fn loop_subdivision(c: &mut Criterion) {
    let mut g = c.benchmark_group("loop");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    for mut w in loop_rows::loop_20k_rows() {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

/// The B-spline fit of CAD export (docs/math.md §10, docs/cad.md; target: the
/// car at depth 5 within 1e-4 of its diagonal in at most 10 ms on one thread).
fn fit(c: &mut Criterion) {
    let mut g = c.benchmark_group("fit");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(30);
    for mut w in workloads::fit_rows() {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

/// The export of the three-patch scene (STEP shell, its fit, IGES, glTF; docs/cad.md).
fn export(c: &mut Criterion) {
    let mut g = c.benchmark_group("export");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    for mut w in export_rows::document_export_rows() {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

/// Authoring (docs/math.md §9): an insert, an initial-curve edit and the mirrored car, at depth 5.
fn authoring(c: &mut Criterion) {
    let mut g = c.benchmark_group("authoring");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    for mut w in ecs_rows::authoring() {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

criterion_group!(
    benches,
    table1,
    surface,
    incremental,
    loop_subdivision,
    authoring,
    fit,
    export
);
criterion_main!(benches);
