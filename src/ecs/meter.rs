//! CPU time of our systems, summed over a frame (they may run on several
//! threads): each system holds a [`CpuMeter::start`] guard while it runs,
//! which counts the *thread's CPU time* (`CLOCK_THREAD_CPUTIME_ID`), so time
//! the thread spends preempted (by a software renderer, say) is not counted.
//! The kernel's helper threads count their own time with the same clock
//! ([`streamline_kernel::parallel::helper_nanos`]).

//!
//! With `STREAMLINE_STUDIO_METER_DETAIL=1` the meter also keeps each
//! system's share (keyed by where it started the meter), which the
//! screenshot report lists: how the frame budget of issue 4 was found.

use bevy::prelude::*;
use std::collections::HashMap;
use std::panic::Location;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Nanoseconds of CPU spent in our systems since the last [`CpuMeter::take`].
#[derive(Resource, Debug)]
pub struct CpuMeter {
    ns: AtomicU64,
    helper_seen: AtomicU64,
    /// Per call site (`file:line`), when asked for.
    detail: Option<Mutex<HashMap<&'static Location<'static>, u64>>>,
}

/// The calling thread's CPU time in nanoseconds.
pub fn thread_cpu_ns() -> u64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a constant
    // every Linux and macOS libc provides.
    let ok = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) } == 0;
    if ok {
        ts.tv_sec as u64 * 1_000_000_000 + ts.tv_nsec as u64
    } else {
        0
    }
}

impl FromWorld for CpuMeter {
    fn from_world(_: &mut World) -> Self {
        streamline_kernel::parallel::set_helper_clock(thread_cpu_ns);
        let detail = std::env::var_os("STREAMLINE_STUDIO_METER_DETAIL")
            .is_some_and(|v| v == "1")
            .then(|| Mutex::new(HashMap::new()));
        CpuMeter {
            ns: AtomicU64::new(0),
            helper_seen: AtomicU64::new(streamline_kernel::parallel::helper_nanos()),
            detail,
        }
    }
}

impl CpuMeter {
    /// Counts the thread's CPU time until the guard is dropped.
    #[track_caller]
    pub fn start(&self) -> MeterGuard<'_> {
        let caller = Location::caller();
        let at = self.detail.as_ref().map(|_| caller);
        MeterGuard(self, thread_cpu_ns(), at)
    }

    /// Each call site's nanoseconds since the last call (empty unless
    /// `STREAMLINE_STUDIO_METER_DETAIL=1`); starts again from 0.
    pub fn take_detail(&self) -> Vec<(String, u64)> {
        let Some(m) = &self.detail else {
            return Vec::new();
        };
        let Ok(mut m) = m.lock() else {
            return Vec::new();
        };
        m.drain()
            .map(|(at, ns)| (format!("{}:{}", at.file(), at.line()), ns))
            .collect()
    }

    /// Milliseconds counted since the last call (with the kernel's helper
    /// threads' time over the same span); starts again from 0.
    pub fn take(&self) -> f64 {
        let helper = streamline_kernel::parallel::helper_nanos();
        let before = self.helper_seen.swap(helper, Ordering::Relaxed);
        let ours = self.ns.swap(0, Ordering::Relaxed);
        (ours + helper.saturating_sub(before)) as f64 * 1e-6
    }
}

/// Adds its thread's CPU time to the meter when dropped.
pub struct MeterGuard<'a>(&'a CpuMeter, u64, Option<&'static Location<'static>>);

impl Drop for MeterGuard<'_> {
    fn drop(&mut self) {
        let d = thread_cpu_ns().saturating_sub(self.1);
        self.0.ns.fetch_add(d, Ordering::Relaxed);
        if let (Some(at), Some(m)) = (self.2, &self.0.detail)
            && let Ok(mut m) = m.lock()
        {
            *m.entry(at).or_default() += d;
        }
    }
}
