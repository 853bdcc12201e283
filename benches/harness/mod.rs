//! The per-call timing method shared by the runtime benchmarks
//! (`benches/seed_examples.rs`, `generated/benches/chains.rs`): a fixed
//! table of pseudo-random states, one state per call inside the measured
//! loop, inputs and results through `std::hint::black_box`.

use std::hint::black_box;
use std::time::{Duration, Instant};

/// Number of states each benchmark cycles through.
pub const STATES: usize = 1000;

/// One state of a system with `NQ` coordinates and `NU` inputs.
#[derive(Clone, Copy)]
pub struct State<const NQ: usize, const NU: usize> {
    pub t: f64,
    pub q: [f64; NQ],
    pub qd: [f64; NQ],
    pub u: [f64; NU],
}

/// SplitMix64: a deterministic generator, so every run sees the same states.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }
}

/// `STATES` states: angles in `[-π, π)`, speeds in `[-3, 3)`, inputs in
/// `[-2, 2)`, time in `[0, 10)`.
pub fn states<const NQ: usize, const NU: usize>(seed: u64) -> Vec<State<NQ, NU>> {
    let mut rng = SplitMix64(seed);
    let pi = std::f64::consts::PI;
    (0..STATES)
        .map(|_| State {
            t: rng.uniform(0.0, 10.0),
            q: std::array::from_fn(|_| rng.uniform(-pi, pi)),
            qd: std::array::from_fn(|_| rng.uniform(-3.0, 3.0)),
            u: std::array::from_fn(|_| rng.uniform(-2.0, 2.0)),
        })
        .collect()
}

/// Times `iters` calls of `call`, one state per call, cycling through
/// `states`. Criterion divides by `iters`: its figure is the time per call.
pub fn per_call<T, R>(states: &[T], iters: u64, mut call: impl FnMut(&T) -> R) -> Duration {
    let mut i = 0;
    let start = Instant::now();
    for _ in 0..iters {
        black_box(call(black_box(&states[i])));
        i += 1;
        if i == states.len() {
            i = 0;
        }
    }
    start.elapsed()
}
