//! The kernel's only parallelism: a large job split in two halves, one of
//! them on a helper thread (std's scoped threads). Both halves do the same
//! operations per entry as one thread would, so results are bitwise equal.
//! The helper threads' busy time is counted for the editor's frame budget,
//! with a clock the application may provide ([`set_helper_clock`]; the kernel
//! itself knows only wall time).

use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

static HELPER_NANOS: AtomicU64 = AtomicU64::new(0);
static HELPER_CLOCK: OnceLock<fn() -> u64> = OnceLock::new();

/// Nanoseconds the helper threads have spent working since the program started.
pub fn helper_nanos() -> u64 {
    HELPER_NANOS.load(Ordering::Relaxed)
}

/// Measures helper threads with `clock` (nanoseconds of the calling
/// thread's CPU time, say) instead of wall time. The first call wins.
pub fn set_helper_clock(clock: fn() -> u64) {
    let _ = HELPER_CLOCK.set(clock);
}

/// Runs `first` on the calling thread and `second` on a helper thread, and
/// waits for both.
pub fn join(first: impl FnOnce() + Send, second: impl FnOnce() + Send) {
    std::thread::scope(|scope| {
        scope.spawn(|| {
            let spent = match HELPER_CLOCK.get() {
                Some(clock) => {
                    let t0 = clock();
                    second();
                    clock().saturating_sub(t0)
                }
                None => {
                    let t = Instant::now();
                    second();
                    t.elapsed().as_nanos() as u64
                }
            };
            HELPER_NANOS.fetch_add(spent, Ordering::Relaxed);
        });
        first();
    });
}
