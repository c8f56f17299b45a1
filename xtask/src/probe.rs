//! The host's cross-core latency, for the bench's threads study: how long a cache line takes
//! to go from one thread to another and back. On a virtual machine it depends on where the
//! hypervisor places the two virtual cores and whether it holds one of them (on this
//! project's 2-core host it swings within seconds between about 55 ns, cores that share a
//! cache, and several hundred ns, up to 2 µs), and two-thread runs, which hand data from one
//! core to the other many times a layer, are slower when it is high. Printed beside the
//! study so that a ratio is read with the host's state at the time; nothing else uses it.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Round trips a probe times.
const ROUND_TRIPS: u64 = 20_000;

/// The mean time, in nanoseconds, for a counter written by this thread to be seen and
/// answered by another thread (both spinning), over [`ROUND_TRIPS`] round trips.
pub(crate) fn round_trip_ns() -> f64 {
    let counter = Arc::new(AtomicU64::new(0));
    let other = Arc::clone(&counter);
    let answer = std::thread::spawn(move || {
        for i in 0..=ROUND_TRIPS {
            wait_for(&other, 2 * i + 1);
            other.store(2 * i + 2, Ordering::Release);
        }
    });
    // the first round trip, untimed, waits for the other thread to start
    counter.store(1, Ordering::Release);
    wait_for(&counter, 2);
    let start = Instant::now();
    for i in 1..=ROUND_TRIPS {
        counter.store(2 * i + 1, Ordering::Release);
        wait_for(&counter, 2 * i + 2);
    }
    let ns = start.elapsed().as_secs_f64() * 1e9 / ROUND_TRIPS as f64;
    // (the other thread has answered every round trip: it has ended or is about to)
    let _ = answer.join();
    ns
}

/// Spins until `counter` holds `value`, yielding the core now and then (on a single core the
/// other thread must run for the value to come).
fn wait_for(counter: &AtomicU64, value: u64) {
    loop {
        for _ in 0..1024 {
            if counter.load(Ordering::Acquire) == value {
                return;
            }
            std::hint::spin_loop();
        }
        std::thread::yield_now();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_round_trip_takes_a_positive_finite_time() {
        let ns = round_trip_ns();
        assert!(ns.is_finite() && ns > 0.0, "{ns}");
    }
}
