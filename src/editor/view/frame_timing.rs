//! What our systems cost per frame, for the Stats panel and the screenshot
//! report: the model's stages (edit → mesh) and all our systems
//! ([`crate::ecs::meter`]), over the last 120 frames with an edit. With
//! `STREAMLINE_STUDIO_METER_DETAIL=1` it also keeps each system's share, the
//! page faults and preemptions taken in our systems, and a speed probe at four
//! points of each frame (a frame that is dear because the machine ran slow
//! shows a slow probe too).

use crate::ecs::{EditLog, Stats};
use bevy::prelude::*;

/// The last 120 figures of a kind, for their maximum.
#[derive(Debug, Default)]
pub struct Recent(pub std::collections::VecDeque<f64>);

impl Recent {
    /// Adds `ms` (dropping the oldest past 120) and returns the largest kept.
    fn push(&mut self, ms: f64) -> f64 {
        self.0.push_back(ms);
        while self.0.len() > 120 {
            self.0.pop_front();
        }
        self.0.iter().copied().fold(0.0, f64::max)
    }
}

/// CPU time of the model's systems in recent frames (for the Stats panel).
#[derive(Resource, Debug, Default)]
pub struct FrameTiming {
    /// Milliseconds of the last frame with an edit (edit → mesh).
    pub last_ms: f64,
    /// The largest of the last 120 frames with an edit.
    pub max_ms: f64,
    /// CPU milliseconds of all our systems (the model's stages and the
    /// editor's systems, summed over threads; [`crate::ecs::meter`]) in the
    /// last frame with an edit.
    pub ours_last_ms: f64,
    /// The largest of the last 120 such frames.
    pub ours_max_ms: f64,
    /// With `STREAMLINE_STUDIO_METER_DETAIL=1`: per system (where it starts
    /// the meter), over frames with an edit: total and largest ms, frames.
    pub detail: std::collections::BTreeMap<String, (f64, f64, u32)>,
    /// With the detail: the dearest frame with an edit, system by system (ms).
    pub worst_frame: Vec<(String, f64)>,
    recent: Recent,
    /// "Our systems" of the last 120 frames with an edit (ms), oldest first.
    pub recent_frames: Recent,
    /// With the detail: the same frames as `recent_frames`, what else they saw.
    pub recent_detail: std::collections::VecDeque<FrameDetail>,
    probe_now: Vec<f64>,
    seen: u64,
    seen_frame: u64,
}

/// What a frame with an edit saw besides our work (with the detail).
#[derive(Debug, Clone, Default)]
pub struct FrameDetail {
    /// Page faults and involuntary context switches in our systems.
    pub faults: [u64; 2],
    /// [`crate::ecs::meter::speed_probe_us`] at four points of the frame
    /// (First, after the model's stages, PostUpdate, Last).
    pub probe: Vec<f64>,
}

pub struct FrameTimingPlugin;

impl Plugin for FrameTimingPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<FrameTiming>()
            .add_systems(Update, track_timing.after(crate::ecs::ModelSet::Output))
            .add_systems(First, probe_speed.run_if(detail_on))
            .add_systems(
                Update,
                probe_speed
                    .run_if(detail_on)
                    .after(crate::ecs::ModelSet::Output),
            )
            .add_systems(PostUpdate, probe_speed.run_if(detail_on))
            .add_systems(Last, track_frame);
    }
}

fn track_timing(
    meter: Res<crate::ecs::meter::CpuMeter>,
    stats: Res<Stats>,
    log: Res<EditLog>,
    mut t: ResMut<FrameTiming>,
) {
    let _meter = meter.start();
    if log.frame == t.seen {
        return;
    }
    t.seen = log.frame;
    let ms = stats.last.us_total() / 1000.0;
    t.last_ms = ms;
    t.max_ms = t.recent.push(ms);
}

fn detail_on(meter: Res<crate::ecs::meter::CpuMeter>) -> bool {
    meter.has_detail()
}

/// With the detail: how fast the machine is at this point of the frame.
fn probe_speed(mut t: ResMut<FrameTiming>) {
    t.probe_now.push(crate::ecs::meter::speed_probe_us());
}

/// At the end of a frame: the CPU time of all our systems (the model's and
/// the editor's, with the kernel's helper threads), kept for frames with an edit.
fn track_frame(
    log: Res<EditLog>,
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut t: ResMut<FrameTiming>,
) {
    let ms = meter.take();
    let detail = meter.take_detail();
    let faults = meter.take_faults();
    let mut probe = std::mem::take(&mut t.probe_now);
    if log.frame == t.seen_frame {
        return;
    }
    t.seen_frame = log.frame;
    let dearest = ms > t.ours_max_ms; // the largest of the frames kept so far
    if dearest && !detail.is_empty() {
        t.worst_frame = detail
            .iter()
            .map(|(at, ns)| (at.clone(), *ns as f64 * 1e-6))
            .collect();
        t.worst_frame
            .push(("all, with the kernel's helper thread".into(), ms));
        t.worst_frame.sort_by(|a, b| b.1.total_cmp(&a.1));
    }
    for (at, ns) in detail {
        let e = t.detail.entry(at).or_default();
        let ms = ns as f64 * 1e-6;
        e.0 += ms;
        e.1 = e.1.max(ms);
        e.2 += 1;
    }
    t.ours_last_ms = ms;
    t.ours_max_ms = t.recent_frames.push(ms);
    if meter.has_detail() {
        probe.push(crate::ecs::meter::speed_probe_us());
        t.recent_detail.push_back(FrameDetail { faults, probe });
        while t.recent_detail.len() > t.recent_frames.0.len() {
            t.recent_detail.pop_front();
        }
    }
}
