//! Per-call cost of the generated equations of seed examples 1 and 2.
//!
//! Every benchmark walks a fixed table of 1000 pseudo-random states, one
//! state per call, inside the measured loop (through `iter_custom`): the
//! figure criterion reports is the time of **one call**, averaged over the
//! states, loop overhead included (see `harness_overhead`). Inputs and
//! results pass through `std::hint::black_box`, so nothing is hoisted out of
//! the loop or folded with the parameters.
//!
//! Run with `cargo bench --bench seed_examples`; see BENCHMARKS.md.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};

#[path = "../tests/seeds/mod.rs"]
mod seeds;
use seeds::{DoublePendulum, RotatingBar};

/// Number of states each benchmark cycles through.
const STATES: usize = 1000;

/// One state of a system with `NQ` coordinates and `NU` inputs.
#[derive(Clone, Copy)]
struct State<const NQ: usize, const NU: usize> {
    t: f64,
    q: [f64; NQ],
    qd: [f64; NQ],
    u: [f64; NU],
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
fn states<const NQ: usize, const NU: usize>(seed: u64) -> Vec<State<NQ, NU>> {
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
fn per_call<T, R>(states: &[T], iters: u64, mut call: impl FnMut(&T) -> R) -> Duration {
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

/// The four per-call benchmarks of one unconstrained system.
macro_rules! bench_system {
    ($c:expr, $group:literal, $sys:expr, $nq:literal, $nu:literal, $seed:literal) => {{
        let sys = $sys;
        let states = states::<$nq, $nu>($seed);
        // Every state must be solvable, or `accelerations` would time an early return.
        for s in &states {
            dalembert::accelerations(&sys, s.t, &s.q, &s.qd, &s.u).expect("solvable state");
        }
        let mut group = $c.benchmark_group($group);
        group.bench_function("mass_matrix", |b| {
            b.iter_custom(|iters| per_call(&states, iters, |s| black_box(&sys).mass_matrix(&s.q)))
        });
        group.bench_function("forcing", |b| {
            b.iter_custom(|iters| {
                per_call(&states, iters, |s| {
                    black_box(&sys).forcing(s.t, &s.q, &s.qd, &s.u)
                })
            })
        });
        group.bench_function("mass_matrix+forcing", |b| {
            b.iter_custom(|iters| {
                per_call(&states, iters, |s| {
                    let sys = black_box(&sys);
                    (sys.mass_matrix(&s.q), sys.forcing(s.t, &s.q, &s.qd, &s.u))
                })
            })
        });
        group.bench_function("accelerations", |b| {
            b.iter_custom(|iters| {
                per_call(&states, iters, |s| {
                    dalembert::accelerations(black_box(&sys), s.t, &s.q, &s.qd, &s.u)
                })
            })
        });
        group.finish();
    }};
}

fn seed_examples(c: &mut Criterion) {
    // Parameters of tests/reference/seed_examples.json.
    bench_system!(
        c,
        "seed1_double_pendulum",
        DoublePendulum {
            m: 1.3,
            L: 0.7,
            g: 9.81
        },
        2,
        0,
        1
    );
    bench_system!(
        c,
        "seed2_rotating_bar",
        RotatingBar {
            m: 2.1,
            l: 0.9,
            d: 0.35
        },
        2,
        2,
        2
    );
}

/// The loop alone (state load, index wrap, `black_box`): subtract it for
/// the cost of the function by itself.
fn harness_overhead(c: &mut Criterion) {
    let states = states::<2, 2>(3);
    c.bench_function("harness_overhead", |b| {
        b.iter_custom(|iters| per_call(&states, iters, |s| s.q[0]))
    });
}

criterion_group!(benches, seed_examples, harness_overhead);
criterion_main!(benches);
