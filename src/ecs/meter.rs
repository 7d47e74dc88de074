//! CPU time of our systems, summed over a frame (they may run on several
//! threads): each system holds a [`CpuMeter::start`] guard while it runs,
//! which counts the *thread's CPU time* (`CLOCK_THREAD_CPUTIME_ID`), so time
//! the thread spends preempted (by a software renderer, say) is not counted.
//! The kernel's helper threads count their own time with the same clock
//! ([`streamline_kernel::parallel::helper_nanos`]).

//!
//! With `STREAMLINE_STUDIO_METER_DETAIL=1` the meter also keeps each
//! system's share (keyed by where it started the meter), which the
//! screenshot report lists: where a frame's time goes, system by system
//! (docs/editor.md, "Frame cost").

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
    /// With the detail: page faults and involuntary context switches taken
    /// while our systems ran (what makes a frame dear besides our work).
    faults: AtomicU64,
    switches: AtomicU64,
}

/// The calling thread's minor + major page faults and involuntary context
/// switches so far (`getrusage(RUSAGE_THREAD)`; zeros where it is missing).
pub fn thread_faults() -> [u64; 2] {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: an all-zero rusage is a valid value of this plain C struct.
        let mut r: libc::rusage = unsafe { std::mem::zeroed() };
        // SAFETY: `r` is valid and writable; RUSAGE_THREAD is Linux's.
        if unsafe { libc::getrusage(libc::RUSAGE_THREAD, &mut r) } == 0 {
            return [(r.ru_minflt + r.ru_majflt) as u64, r.ru_nivcsw as u64];
        }
    }
    [0, 0]
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
            faults: AtomicU64::new(0),
            switches: AtomicU64::new(0),
        }
    }
}

impl CpuMeter {
    /// Counts the thread's CPU time until the guard is dropped.
    #[track_caller]
    pub fn start(&self) -> MeterGuard<'_> {
        let caller = Location::caller();
        let at = self.detail.as_ref().map(|_| caller);
        let faults = if at.is_some() {
            thread_faults()
        } else {
            [0, 0]
        };
        MeterGuard(self, thread_cpu_ns(), at, faults)
    }

    /// With the detail: page faults and involuntary context switches in our
    /// systems since the last call; starts again from 0.
    pub fn take_faults(&self) -> [u64; 2] {
        [
            self.faults.swap(0, Ordering::Relaxed),
            self.switches.swap(0, Ordering::Relaxed),
        ]
    }

    /// Whether the meter keeps each system's share
    /// (`STREAMLINE_STUDIO_METER_DETAIL=1`).
    pub fn has_detail(&self) -> bool {
        self.detail.is_some()
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

/// CPU microseconds of a fixed piece of work (arithmetic and reads over
/// 64 KiB): run at four points of a frame with the detail, it tells a frame
/// that was dear because the machine was slow from one that was dear because
/// of our work (the same work, the same time, on a steady machine).
pub fn speed_probe_us() -> f64 {
    let t0 = thread_cpu_ns();
    let mut buf = [0u64; 8192];
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let mut acc = 0.0f64;
    for round in 0..4 {
        for (i, b) in buf.iter_mut().enumerate() {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            *b = b.wrapping_add(x ^ i as u64 ^ round);
            acc = acc.mul_add(0.999_999, (*b >> 11) as f64 * 1e-16);
        }
    }
    std::hint::black_box((&buf, acc));
    thread_cpu_ns().saturating_sub(t0) as f64 * 1e-3
}

/// Adds its thread's CPU time to the meter when dropped.
pub struct MeterGuard<'a>(
    &'a CpuMeter,
    u64,
    Option<&'static Location<'static>>,
    [u64; 2],
);

impl Drop for MeterGuard<'_> {
    fn drop(&mut self) {
        let d = thread_cpu_ns().saturating_sub(self.1);
        self.0.ns.fetch_add(d, Ordering::Relaxed);
        if let (Some(at), Some(m)) = (self.2, &self.0.detail)
            && let Ok(mut m) = m.lock()
        {
            *m.entry(at).or_default() += d;
            let [f, c] = thread_faults();
            self.0
                .faults
                .fetch_add(f.saturating_sub(self.3[0]), Ordering::Relaxed);
            self.0
                .switches
                .fetch_add(c.saturating_sub(self.3[1]), Ordering::Relaxed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_probe_and_the_counters_read_this_thread() {
        let us = speed_probe_us();
        assert!(us.is_finite() && us > 0.0, "{us}");
        let [f0, _] = thread_faults();
        // touching fresh pages faults them in, on this thread
        let v = std::hint::black_box(vec![1u8; 8 << 20]);
        let [f1, _] = thread_faults();
        assert_eq!(v.len(), 8 << 20);
        if cfg!(target_os = "linux") {
            assert!(f1 > f0, "{f0} → {f1}");
        }
    }
}
