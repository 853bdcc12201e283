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

use criterion::{Criterion, criterion_group, criterion_main};

use dalembert_fixtures::seeds::{DoublePendulum, RotatingBar};
use dalembert_fixtures::states::{per_call, states};

/// The four per-call benchmarks of one unconstrained system.
macro_rules! bench_system {
    ($c:expr, $group:literal, $sys:expr, $nq:literal, $nu:literal, $seed:literal) => {{
        let sys = $sys;
        let states = states::<$nq, $nu>($seed);
        // Every state must be solvable, or `accelerations` would time an early return.
        for s in &states {
            dalembert::__private::cholesky_accelerations(&sys, s.t, &s.q, &s.v, &s.u)
                .expect("solvable state");
        }
        let mut group = $c.benchmark_group($group);
        group.bench_function("mass_matrix", |b| {
            b.iter_custom(|iters| per_call(&states, iters, |s| black_box(&sys).mass_matrix(&s.q)))
        });
        group.bench_function("forcing", |b| {
            b.iter_custom(|iters| {
                per_call(&states, iters, |s| {
                    black_box(&sys).forcing(s.t, &s.q, &s.v, &s.u)
                })
            })
        });
        group.bench_function("mass_matrix+forcing", |b| {
            b.iter_custom(|iters| {
                per_call(&states, iters, |s| {
                    let sys = black_box(&sys);
                    (sys.mass_matrix(&s.q), sys.forcing(s.t, &s.q, &s.v, &s.u))
                })
            })
        });
        group.bench_function("accelerations", |b| {
            b.iter_custom(|iters| {
                per_call(&states, iters, |s| {
                    dalembert::__private::cholesky_accelerations(
                        black_box(&sys),
                        s.t,
                        &s.q,
                        &s.v,
                        &s.u,
                    )
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
