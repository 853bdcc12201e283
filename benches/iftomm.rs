//! Time of a whole IFToMM A02 simulation (the N-four-bar mechanism with
//! N = 10, 20 s, through every singular position) at the cheapest settings
//! found to reach the benchmark's "high precision", `1e-3` m on the
//! reference point `B0` at the final time; the setup checks that error
//! against the one-coordinate parallelogram reference before timing.
//!
//! Run with `cargo bench --bench iftomm`; see BENCHMARKS.md.

use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};

use dalembert::integrate::{
    AdaptiveOptions, AugmentedLagrangian, ExplicitPair, adaptive, augmented_lagrangian, rk4,
};
use dalembert::{Constrained, Stabilisation, State, Unconstrained};
use dalembert_fixtures::iftomm::{FourBars10, Parallelogram, four_bar_start};

const DURATION: f64 = 20.0;
const HIGH_PRECISION: f64 = 1e-3;
const SYSTEM: FourBars10 = FourBars10 {
    m: 1.0,
    L: 1.0,
    g: 9.81,
};
const PROJECTION: Stabilisation = Stabilisation::Projection {
    tolerance: 1e-12,
    max_iterations: 10,
};

/// The error of `B0` at the final time against the parallelogram.
fn error(end: &State<21, 21>) -> f64 {
    let reduced = Parallelogram {
        m: 1.0,
        L: 1.0,
        g: 9.81,
        n: 10.0,
    };
    let first = State {
        t: 0.0,
        q: [FRAC_PI_2],
        v: [-1.0],
    };
    let options = AdaptiveOptions::with_tolerance(1e-13);
    let dynamics = Unconstrained::without_inputs(&reduced);
    let phi = adaptive(
        &dynamics,
        first,
        DURATION,
        ExplicitPair::Dop853,
        options,
        |_| {},
    )
    .expect("reference")
    .end
    .q[0];
    let b0 = end.q[0];
    (b0.cos() - phi.cos())
        .abs()
        .max((b0.sin() - phi.sin()).abs())
}

fn four_bars(c: &mut Criterion) {
    let dynamics = Constrained::without_inputs(&SYSTEM, PROJECTION);
    let alf_steps = 10_000;
    let rk4_steps = 1_000;
    let tolerance = 1e-6;
    let h = DURATION / alf_steps as f64;
    let alf = || {
        augmented_lagrangian(
            &dynamics,
            four_bar_start(),
            DURATION,
            alf_steps,
            AugmentedLagrangian::for_step(h),
            |_| {},
        )
        .map(|s| s.end)
        .map_err(|e| e.to_string())
    };
    let runge_kutta = || {
        rk4(&dynamics, four_bar_start(), DURATION, rk4_steps, |_| {})
            .map(|s| s.end)
            .map_err(|e| e.to_string())
    };
    let options = AdaptiveOptions::with_tolerance(tolerance);
    let dop853 = || {
        adaptive(
            &dynamics,
            four_bar_start(),
            DURATION,
            ExplicitPair::Dop853,
            options,
            |_| {},
        )
        .map(|s| s.end)
        .map_err(|e| e.to_string())
    };
    for (name, end) in [
        ("augmented Lagrangian", alf()),
        ("RK4", runge_kutta()),
        ("DOP853", dop853()),
    ] {
        let end = end.expect("the run crosses every singular position");
        let error = error(&end);
        assert!(error < HIGH_PRECISION, "{name}: B0 off by {error:e}");
        eprintln!("{name}: B0 off by {error:.1e} m at {DURATION} s");
    }
    let mut group = c.benchmark_group("a02_ten_four_bars_20s");
    group.sample_size(10);
    group.bench_function(
        format!(
            "augmented_lagrangian_h{}ms",
            1e3 * DURATION / alf_steps as f64
        ),
        |b| b.iter(|| black_box(alf())),
    );
    group.bench_function(
        format!("rk4_projection_h{}ms", 1e3 * DURATION / rk4_steps as f64),
        |b| b.iter(|| black_box(runge_kutta())),
    );
    group.bench_function(format!("dop853_projection_tol{tolerance:e}"), |b| {
        b.iter(|| black_box(dop853()))
    });
    group.finish();
}

criterion_group!(benches, four_bars);
criterion_main!(benches);
