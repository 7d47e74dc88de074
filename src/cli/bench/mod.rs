//! `bench`: a quick built-in benchmark for users who want their machine's figures.
//! For careful numbers use `cargo bench` (criterion), which runs the same workloads.

pub mod ecs_rows;
pub mod export_rows;
pub mod loop_rows;
pub mod patches;
pub mod reference_rows;
pub mod workloads;

use super::input::CliError;
use clap::Args;
use std::time::Instant;

/// Arguments of `bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// One JSON object per line: {"name", "median_ns", "runs"}.
    #[arg(long)]
    json: bool,
    /// Only rows whose name contains this text.
    #[arg(long)]
    filter: Option<String>,
    /// Approximate time spent per row, in milliseconds.
    #[arg(long, default_value_t = 300)]
    millis: u64,
}

/// The single-patch rows of the workload files, in the order `bench` reports
/// them (the several-patch, export and reference rows follow).
pub fn all() -> Vec<workloads::Workload> {
    let mut rows = workloads::table1();
    rows.extend(ecs_rows::car_drag(6));
    rows.extend(workloads::car_surface([3, 5]));
    rows.extend(workloads::car_builder(5));
    rows.extend(ecs_rows::incremental());
    rows.extend(ecs_rows::fine_tuning());
    rows.extend(loop_rows::loop_rows());
    rows.extend(ecs_rows::authoring());
    rows.extend(workloads::fit_rows());
    rows
}

/// Bytes of other memory a cold row's run follows ([`Workload::cold`]).
/// The editor's software-rendered frame moves more than that between two
/// of its frames (on the car at depth 6 the mesh's vertex and index
/// buffers, about 9 MB, are copied four or five times on their way to
/// llvmpipe, then read to draw), so an edit's frame there finds little of
/// its 15 MB of levels, points and staging buffers in the 32 MB L3 cache.
/// A headless experiment writing 0, 16, 32 or 64 MB between frames put the
/// drag's edit, blend, integrate and mesh stages at 1.73, 1.86, 2.11 and 2.34 ms
/// together; the editor's drag report puts them at 2.1–2.2 ms.
pub const EVICT_BYTES: usize = 48 << 20;

/// Writes [`EVICT_BYTES`] of `other` (grown to that the first time): a
/// line each, so that what was in the caches before is written back and
/// gone.
pub fn evict_caches(other: &mut Vec<u64>) {
    other.resize(EVICT_BYTES / 8, 0);
    for (k, v) in other.iter_mut().enumerate().step_by(8) {
        *v = v.wrapping_add(k as u64);
    }
    std::hint::black_box(&other);
}

/// `bench`.
pub fn bench(a: BenchArgs) -> Result<(), CliError> {
    let budget = std::time::Duration::from_millis(a.millis.max(1));
    let rows = all()
        .into_iter()
        .chain(patches::rows())
        .chain(export_rows::document_export_rows())
        .chain(reference_rows::rows());
    for mut w in rows {
        if a.filter.as_deref().is_some_and(|f| !w.name.contains(f)) {
            continue;
        }
        // The first call sets the row up (`Workload::lazy`) and warms it;
        // the second sizes the batch so one sample takes about 1/50 of the budget.
        let mut sink = (w.run)();
        let t0 = Instant::now();
        sink += (w.run)();
        let once = t0.elapsed().max(std::time::Duration::from_nanos(20));
        let batch = match w.cold {
            true => 1,
            false => ((budget / 50).as_nanos() / once.as_nanos()).clamp(1, 1_000_000) as u32,
        };
        let mut samples = Vec::new();
        let mut other = Vec::new();
        let start = Instant::now();
        while start.elapsed() < budget || samples.len() < 5 {
            if w.cold {
                evict_caches(&mut other);
            }
            let t = Instant::now();
            for _ in 0..batch {
                sink += (w.run)();
            }
            samples.push(t.elapsed().as_nanos() as f64 / f64::from(batch));
        }
        samples.sort_by(f64::total_cmp);
        let median = samples[samples.len() / 2];
        let runs = samples.len() as u64 * u64::from(batch);
        std::hint::black_box(sink);
        if a.json {
            println!(
                "{}",
                serde_json::json!({"name": w.name, "median_ns": median.round(), "runs": runs})
            );
        } else {
            println!("{:<36} {:>14.0} ns  ({runs} runs)", w.name, median);
        }
    }
    Ok(())
}
