//! The kernel's only parallelism: a large job split in two halves, one of
//! them on a helper thread. Both halves do the same operations per entry as
//! one thread would, so results are bitwise equal.
//!
//! The helper is one long-lived thread (started on first use): starting a
//! thread per job costs 50–100 µs of CPU, a tenth of an edit's whole budget.
//! Between jobs it spins a little before it sleeps, and so does a caller
//! waiting for its half (`SPIN`): an edit hands it several jobs in a row.
//! [`join`] hands it the second half as a pointer to a closure on the
//! caller's stack and always waits for it before returning — also when the
//! first half panics — which is what makes lending the borrow sound (the same
//! contract as `std::thread::scope`). If the helper cannot be started, the
//! second half runs on a scoped thread instead.
//!
//! The helper's busy time is counted for the editor's frame budget, with a
//! clock the application may provide ([`set_helper_clock`]; the kernel itself
//! knows only wall time).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Sender, channel};
use std::sync::{Arc, Condvar, Mutex, OnceLock};
use std::time::Instant;

static HELPER_NANOS: AtomicU64 = AtomicU64::new(0);
static HELPER_CLOCK: OnceLock<fn() -> u64> = OnceLock::new();
static HELPER: OnceLock<Option<Mutex<Sender<Task>>>> = OnceLock::new();

thread_local! {
    /// Set on the helper thread: a `join` there runs both halves itself
    /// (handing work to itself would wait forever).
    static ON_HELPER: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

static DISABLED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether [`join`] uses the helper thread (on by default).
pub(crate) fn enabled() -> bool {
    !DISABLED.load(Ordering::Relaxed)
}

/// Turns the helper on or off for the whole program: off, both halves run on
/// the calling thread (same results, bitwise). An application that shares
/// few cores with other busy work (a software renderer) spends less CPU so.
pub fn set_enabled(on: bool) {
    DISABLED.store(!on, Ordering::Relaxed);
}

/// Nanoseconds the helper has spent working since the program started.
pub fn helper_nanos() -> u64 {
    HELPER_NANOS.load(Ordering::Relaxed)
}

/// Measures the helper with `clock` (nanoseconds of the calling thread's CPU
/// time, say) instead of wall time. The first call wins.
pub fn set_helper_clock(clock: fn() -> u64) {
    let _ = HELPER_CLOCK.set(clock);
}

/// How long a thread that waits for the other spins before it sleeps: the
/// helper for its next job, the caller for the helper's half. An edit hands
/// the helper a job every few dozen microseconds (each level's two passes,
/// then the normals); woken from sleep every time, the helper took 10–50 µs
/// to start, which cost an interior edit on a 20 × 20 net at depth 5 more
/// than its second core gave back.
const SPIN: std::time::Duration = std::time::Duration::from_micros(200);

/// Spins until `ready()` or [`SPIN`] has passed; whether it was ready.
fn spin_until(ready: impl Fn() -> bool) -> bool {
    let start = Instant::now();
    loop {
        for _ in 0..64 {
            if ready() {
                return true;
            }
            std::hint::spin_loop();
        }
        if start.elapsed() >= SPIN {
            return ready();
        }
        // the other thread may be waiting for this core
        std::thread::yield_now();
    }
}

/// Done, and whether the job panicked: `state` is 0 while running, then 1
/// (done) or 2 (panicked), set before the waiter is woken under `lock`.
#[derive(Default)]
struct Latch {
    state: std::sync::atomic::AtomicU8,
    lock: Mutex<()>,
    cv: Condvar,
}

impl Latch {
    fn set(&self, panicked: bool) {
        self.state.store(1 + panicked as u8, Ordering::Release);
        // under the lock: a waiter checks the state holding it, so it either
        // sees the new state or is asleep in `wait` when notified
        let _g = self.lock.lock().unwrap_or_else(|e| e.into_inner());
        self.cv.notify_all();
    }

    fn wait(&self) -> bool {
        let done = || self.state.load(Ordering::Acquire) != 0;
        if !spin_until(done) {
            let mut g = self.lock.lock().unwrap_or_else(|e| e.into_inner());
            while !done() {
                g = self.cv.wait(g).unwrap_or_else(|e| e.into_inner());
            }
        }
        self.state.load(Ordering::Acquire) == 2
    }
}

/// A job for the helper: a type-erased `&mut dyn FnMut()` living on the
/// caller's stack until the latch is set.
struct Task {
    data: *mut (),
    call: unsafe fn(*mut ()),
    latch: Arc<Latch>,
}

// SAFETY: the closure behind `data` is `Send` (checked in `join`), and the
// caller keeps it alive and untouched until the helper sets the latch.
unsafe impl Send for Task {}

fn helper() -> Option<&'static Mutex<Sender<Task>>> {
    HELPER
        .get_or_init(|| {
            let (tx, rx) = channel::<Task>();
            std::thread::Builder::new()
                .name("kernel-helper".into())
                .spawn(move || {
                    ON_HELPER.with(|h| h.set(true));
                    // the next job, spinning a while before sleeping
                    let next = || {
                        let ready = std::cell::Cell::new(None);
                        spin_until(|| match rx.try_recv() {
                            Ok(t) => {
                                ready.set(Some(t));
                                true
                            }
                            Err(e) => e == std::sync::mpsc::TryRecvError::Disconnected,
                        });
                        ready.into_inner().map_or_else(|| rx.recv().ok(), Some)
                    };
                    while let Some(task) = next() {
                        let t0 = HELPER_CLOCK.get().map(|c| c());
                        let start = Instant::now();
                        // SAFETY: see `Task`; the caller waits on the latch.
                        let r =
                            catch_unwind(AssertUnwindSafe(|| unsafe { (task.call)(task.data) }));
                        let spent = match (HELPER_CLOCK.get(), t0) {
                            (Some(c), Some(t0)) => c().saturating_sub(t0),
                            _ => start.elapsed().as_nanos() as u64,
                        };
                        HELPER_NANOS.fetch_add(spent, Ordering::Relaxed);
                        task.latch.set(r.is_err());
                    }
                })
                .ok()
                .map(|_| Mutex::new(tx))
        })
        .as_ref()
}

/// Waits for the helper's half when dropped (so also while unwinding).
struct WaitFor(Arc<Latch>);

impl Drop for WaitFor {
    fn drop(&mut self) {
        self.0.wait();
    }
}

/// Runs `first` on the calling thread and `second` on the helper thread, and
/// waits for both. A panic in either half reaches the caller.
pub fn join(first: impl FnOnce() + Send, second: impl FnOnce() + Send) {
    if ON_HELPER.with(|h| h.get()) || !enabled() {
        first();
        return second();
    }
    let Some(tx) = helper() else {
        return std::thread::scope(|s| {
            s.spawn(second);
            first();
        });
    };
    let mut second = Some(second);
    // `run` is `Send` because `second` is: the helper may call it
    let mut run = || {
        if let Some(f) = second.take() {
            f();
        }
    };
    unsafe fn trampoline<F: FnMut()>(p: *mut ()) {
        // SAFETY: `p` is the `&mut F` that `join` erased, still alive.
        unsafe { (*(p as *mut F))() }
    }
    fn erase<F: FnMut()>(f: &mut F) -> (*mut (), unsafe fn(*mut ())) {
        (f as *mut F as *mut (), trampoline::<F>)
    }
    let (data, call) = erase(&mut run);
    let latch = Arc::new(Latch::default());
    let sent = tx
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .send(Task {
            data,
            call,
            latch: latch.clone(),
        })
        .is_ok();
    if !sent {
        // the helper is gone: do both halves here
        first();
        run();
        return;
    }
    let guard = WaitFor(latch.clone());
    first();
    drop(guard); // waits for the helper's half
    if latch.wait() {
        panic!("the second half of a parallel job panicked");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn join_runs_both_halves_on_borrowed_data() {
        let mut data = vec![0u64; 100_000];
        for round in 0..50u64 {
            let (a, b) = data.split_at_mut(50_000);
            join(
                || a.iter_mut().for_each(|x| *x += round),
                || b.iter_mut().for_each(|x| *x += 2 * round),
            );
        }
        let s: u64 = (0..50).sum();
        assert!(data[..50_000].iter().all(|&x| x == s));
        assert!(data[50_000..].iter().all(|&x| x == 2 * s));
    }

    /// Jobs handed while the helper spins for the next one and after it has
    /// gone to sleep (and the caller's wait: spun, or asleep while the
    /// helper's half runs long) all run, each half exactly once.
    #[test]
    fn join_hands_jobs_to_a_spinning_and_to_a_sleeping_helper() {
        let mut hits = [0u32; 2];
        for round in 0..6 {
            let pause = match round % 3 {
                0 => std::time::Duration::ZERO,
                1 => SPIN * 3,
                _ => SPIN / 4,
            };
            std::thread::sleep(pause);
            let (a, b) = hits.split_at_mut(1);
            join(
                || a[0] += 1,
                || {
                    if round == 4 {
                        std::thread::sleep(SPIN * 2);
                    }
                    b[0] += 1
                },
            );
        }
        assert_eq!(hits, [6, 6]);
    }

    #[test]
    fn join_reports_a_panic_of_the_helper_half() {
        let r = std::panic::catch_unwind(|| join(|| {}, || panic!("boom")));
        assert!(r.is_err());
        // the helper survives and keeps working
        let mut hit = false;
        join(|| {}, || hit = true);
        assert!(hit);
    }
}
