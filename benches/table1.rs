//! The paper's Table 1 side by side (subdivision vs QI curves, 5 control tangents)
//! and full builds of the 9×6 car surface at depths 0–5 (fresh, and into a
//! kept `Builder` on one thread with and without the vector path, and on two). The workloads are the
//! ones `streamline-studio bench` runs (`src/cli/bench/workloads.rs`); the `incremental`
//! group times one edit through the ECS against a full rebuild (issue 3), and
//! one fine-tuning value edit on the car at depth 3 (issue 6); the
//! `authoring` group an insert, an initial-curve edit and the mirrored car (issue 20).
//!
//! Run: `cargo bench --bench table1`. Figures and ratios: docs/benchmarks.md.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use streamline_studio::cli::bench::workloads;

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
    for mut w in workloads::incremental()
        .into_iter()
        .chain(workloads::fine_tuning())
    {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

/// Issue 20: an insert, an initial-curve edit and the mirrored car, at depth 5.
fn authoring(c: &mut Criterion) {
    let mut g = c.benchmark_group("authoring");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    for mut w in workloads::authoring() {
        g.bench_function(&w.name, |b| b.iter(|| black_box((w.run)())));
    }
    g.finish();
}

criterion_group!(benches, table1, surface, incremental, authoring);
criterion_main!(benches);
