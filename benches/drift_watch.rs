//! The drift watch's cost per step: RK4 runs of constrained systems with
//! the default `DriftLimits` (the residual and velocity form of every row
//! after every step, and, for the runs that do not project, the rows'
//! conditioning) against the same runs with `DriftLimits::UNWATCHED`.
//! Seed example 3 (three coordinates, two rows) and the IFToMM A02
//! mechanism of ten four-bars (21 coordinates, 20 rows, 10 redundant);
//! unstabilised and projected. One iteration is a run of `STEPS` steps
//! (of 1 ms; of 0.5 ms for the four-bars, flat at 0.72 s).
//!
//! ```sh
//! cargo bench --bench drift_watch
//! ```

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use dalembert::constrained::DriftLimits;
use dalembert::integrate::{Integration, Rk4};
use dalembert::{Constrained, ConstrainedSystem, Stabilisation, State};
use dalembert_fixtures::cpu_time::thread_time_of;
use dalembert_fixtures::iftomm::{FourBars10, four_bar_start};
use dalembert_fixtures::slider_crank::SEED_3;

/// Steps of each run.
const STEPS: u64 = 1000;

const PROJECTION: Stabilisation = Stabilisation::Projection {
    tolerance: 1e-12,
    max_iterations: 5,
};

/// RK4 runs of `system` from `start` over `STEPS` steps of `h`, watched
/// and unwatched, unstabilised and projected.
fn runs<S, const NQ: usize, const NU: usize, const NC: usize>(
    c: &mut Criterion,
    name: &str,
    system: &S,
    start: State<NQ, NQ>,
    h: f64,
) where
    S: ConstrainedSystem<NQ, NQ, NU, NC>,
{
    let mut group = c.benchmark_group(format!("drift_watch/{name}"));
    let stabilisations = [
        ("unstabilised", Stabilisation::None),
        ("projected", PROJECTION),
    ];
    let watches = [
        ("watched", DriftLimits::default()),
        ("unwatched", DriftLimits::UNWATCHED),
    ];
    for (stabilised, stabilisation) in stabilisations {
        for (watched, limits) in watches {
            let dynamics =
                Constrained::without_inputs(system, stabilisation).with_drift_limits(limits);
            let end = start.t + h * STEPS as f64;
            group.bench_function(format!("{stabilised}/{watched}"), |b| {
                // Thread CPU time, as the other benches: the machine is shared.
                b.iter_custom(|iters| {
                    (0..iters)
                        .map(|_| {
                            thread_time_of(|| {
                                Integration::new(
                                    &dynamics,
                                    black_box(start),
                                    end,
                                    Rk4 { steps: STEPS },
                                )
                                .run()
                                .unwrap()
                            })
                            .0
                        })
                        .sum()
                })
            });
        }
    }
    group.finish();
}

fn drift_watch(c: &mut Criterion) {
    runs(c, "seed_3", &SEED_3, SEED_3.assembled(0.4, 1.0), 1e-3);
    // Half a second: the cranks fall flat (a singular position) at 0.72 s.
    runs(c, "four_bars_10", &four_bars_10(), four_bar_start(), 5e-4);
}

/// The A02 mechanism of ten four-bars, as `benches/iftomm.rs` builds it.
fn four_bars_10() -> FourBars10 {
    FourBars10 {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = drift_watch
}
criterion_main!(benches);
