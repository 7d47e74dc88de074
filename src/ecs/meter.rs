//! CPU time of our systems, summed over a frame (they may run on several
//! threads): each system holds a [`CpuMeter::start`] guard while it runs,
//! which counts the *thread's CPU time* (`CLOCK_THREAD_CPUTIME_ID`), so time
//! the thread spends preempted (by a software renderer, say) is not counted.
//! The kernel's helper threads count their own time with the same clock
//! ([`streamline_kernel::parallel::helper_nanos`]).

use bevy::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Nanoseconds of CPU spent in our systems since the last [`CpuMeter::take`].
#[derive(Resource, Debug)]
pub struct CpuMeter {
    ns: AtomicU64,
    helper_seen: AtomicU64,
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
        CpuMeter {
            ns: AtomicU64::new(0),
            helper_seen: AtomicU64::new(streamline_kernel::parallel::helper_nanos()),
        }
    }
}

impl CpuMeter {
    /// Counts the thread's CPU time until the guard is dropped.
    pub fn start(&self) -> MeterGuard<'_> {
        MeterGuard(&self.ns, thread_cpu_ns())
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
pub struct MeterGuard<'a>(&'a AtomicU64, u64);

impl Drop for MeterGuard<'_> {
    fn drop(&mut self) {
        self.0
            .fetch_add(thread_cpu_ns().saturating_sub(self.1), Ordering::Relaxed);
    }
}
