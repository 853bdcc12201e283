//! The CPU time of the calling thread, for benchmarks on a shared machine:
//! unlike the wall clock, it does not count the time other processes hold
//! the core (caches are still shared).

use std::time::Duration;

/// The CPU time this thread has used so far.
pub fn thread_time() -> Duration {
    let mut time = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `clock_gettime` writes the `timespec` it is given and nothing
    // else; the thread CPU-time clock exists on every Linux.
    let status = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut time) };
    assert_eq!(status, 0, "CLOCK_THREAD_CPUTIME_ID");
    Duration::new(time.tv_sec as u64, time.tv_nsec as u32)
}

/// The CPU time of this thread that `run` takes, with its result.
pub fn thread_time_of<R>(run: impl FnOnce() -> R) -> (Duration, R) {
    let start = thread_time();
    let result = run();
    (thread_time() - start, result)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn busy_work_takes_cpu_time_and_sleeping_does_not() {
        let (busy, sum) = thread_time_of(|| {
            (0..20_000_000u64).fold(0u64, |s, k| std::hint::black_box(s.wrapping_add(k * k)))
        });
        assert!(sum > 0 && busy > Duration::ZERO, "{busy:?}");
        let (asleep, ()) = thread_time_of(|| std::thread::sleep(Duration::from_millis(200)));
        assert!(asleep < Duration::from_millis(100), "{asleep:?}");
    }
}
