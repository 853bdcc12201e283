//! Where integrators fail, measured: the energy drift of
//! RK4 and DOP853 on the chaotic double pendulum against the bounded energy
//! error of the symmetric Gauss method; the constraint drift of the adaptive
//! pair with and without projection; a stiff joint that forces explicit
//! methods to tiny steps; a singular mass matrix that stops every
//! integrator with an error naming time and configuration; and how soon two
//! chaotic trajectories 1e-10 apart part. The charts for people come from
//! `cargo run --release --example work_precision`.
//!
//! The energy test runs 10³ s in debug builds (CI) and the full 10⁴ s with
//! `cargo test --release --test suite stability::`; its bands hold for both.

use std::f64::consts::FRAC_PI_2;

use dalembert::constrained::constraint_drift;
use dalembert::integrate::{self, ExplicitPair, Failure, GaussLegendre};
use dalembert::{
    Constrained, DynamicsError, IntegrationError, Solution, Stabilisation, State, Unconstrained,
    energy,
};
use dalembert_fixtures::seeds::{CHAOTIC, CHAOTIC_START};
use dalembert_fixtures::stability::{
    ON_AXIS, STIFF, STIFF_START, StiffDoublePendulum, TOWARDS_AXIS,
};
use dalembert_lab::state_error;

/// Horizon of the long-time energy test: 10⁴ s optimised, 10³ s in debug.
const HORIZON: f64 = if cfg!(debug_assertions) { 1e3 } else { 1e4 };

/// The largest relative energy error of the chaotic pendulum over the first
/// tenth of the horizon and over all of it, as observed by `integrate`.
fn energy_errors(
    integrate: impl FnOnce(&mut dyn FnMut(&State<2, 2>)) -> Result<Solution<2, 2>, IntegrationError<2>>,
) -> (f64, f64) {
    let initial = energy(&CHAOTIC, &CHAOTIC_START.q, &CHAOTIC_START.v);
    let (mut first_tenth, mut all) = (0.0f64, 0.0f64);
    let mut observe = |s: &State<2, 2>| {
        let error = ((energy(&CHAOTIC, &s.q, &s.v) - initial) / initial).abs();
        all = all.max(error);
        if s.t <= HORIZON / 10.0 {
            first_tenth = first_tenth.max(error);
        }
    };
    let end = integrate(&mut observe).unwrap();
    assert!((end.end.t - HORIZON).abs() < 1e-6 * HORIZON, "{end:?}");
    (first_tenth, all)
}

#[test]
fn gauss_keeps_the_chaotic_pendulums_energy_bounded_while_rk4_and_dop853_drift() {
    let dynamics = Unconstrained::without_inputs(&CHAOTIC);
    let steps = |h: f64| (HORIZON / h).round() as u64;
    let rk4 = energy_errors(|observe| {
        integrate::Integration::new(
            &dynamics,
            CHAOTIC_START,
            CHAOTIC_START.t + HORIZON,
            integrate::Rk4 { steps: steps(5e-3) },
        )
        .observe(observe)
        .run()
    });
    let dop853 = energy_errors(|observe| {
        integrate::Integration::new(
            &dynamics,
            CHAOTIC_START,
            HORIZON,
            integrate::Adaptive::dop853(1e-8),
        )
        .observe(observe)
        .run()
    });
    let gauss = energy_errors(|observe| {
        let method = GaussLegendre::Order4;
        integrate::Integration::new(
            &dynamics,
            CHAOTIC_START,
            CHAOTIC_START.t + HORIZON,
            integrate::Gauss {
                rule: method,
                steps: steps(1e-2),
            },
        )
        .observe(observe)
        .run()
    });
    // Measured (10³ s | 10⁴ s): RK4 3.8e-4 → 3.8e-3 | 3.8e-3 → 3.9e-2;
    // DOP853 3.3e-6 → 3.3e-5 | 3.3e-5 → 3.2e-4 (2.6e-6 → 3.7e-5 with the
    // L D Lᵀ solver, whose rounding takes the chaotic motion on another path):
    // linear drifts, about tenfold over ten times the time. The window tells
    // a linear drift (×10) from a bounded error (×1) and a quadratic one (×100).
    // Gauss 4: 9.9e-5 | 1.4e-4 over the whole horizon.
    for (name, (first_tenth, all)) in [("RK4", rk4), ("DOP853", dop853)] {
        let growth = all / first_tenth;
        assert!(
            (5.0..20.0).contains(&growth),
            "{name}: {first_tenth:e} → {all:e}"
        );
    }
    let (first_tenth, all) = gauss;
    assert!(
        all < 2e-4 && all / first_tenth < 2.0,
        "Gauss 4: {first_tenth:e} → {all:e}"
    );
    assert!(rk4.1 > 10.0 * all, "RK4 {:e} vs Gauss {all:e}", rk4.1);
}

#[test]
fn projection_holds_the_drift_of_the_adaptive_pair_on_the_slider_crank() {
    let crank = dalembert_fixtures::slider_crank::SLIDER_CRANK;
    let start = crank.assembled(0.0, dalembert_fixtures::slider_crank::CRANK_SPEED);
    let drift_after_two_seconds = |stabilisation| {
        let dynamics = Constrained::new(&crank, |_, _, _| [0.0], stabilisation);
        let end =
            integrate::Integration::new(&dynamics, start, 2.0, integrate::Adaptive::dop853(1e-8))
                .run();
        constraint_drift(&crank, &end.unwrap().end)
    };
    let free = drift_after_two_seconds(Stabilisation::None);
    let projected = drift_after_two_seconds(Stabilisation::Projection {
        tolerance: 1e-13,
        max_iterations: 8,
    });
    // Measured: 7.3e-9 unstabilised, 1.1e-16 projected.
    assert!(free > 1e-9, "unstabilised drift {free:e}");
    assert!(projected <= 1e-13, "projected drift {projected:e}");
}

/// The stiff pendulum with its spring removed.
const SOFT: StiffDoublePendulum = StiffDoublePendulum { k: 0.0, ..STIFF };

#[test]
fn a_stiff_joint_forces_explicit_methods_to_tiny_steps_but_not_the_l_stable_sdirk() {
    let stiff = Unconstrained::without_inputs(&STIFF);
    let soft = Unconstrained::without_inputs(&SOFT);
    let dop853 = |dynamics: &_| {
        integrate::Integration::new(
            dynamics,
            STIFF_START,
            1.0,
            integrate::Adaptive::dop853(1e-6),
        )
        .run()
        .unwrap()
    };
    let explicit = dop853(&stiff);
    let relaxed = dop853(&soft);
    // Measured: 1325 accepted steps with the spring, 25 without.
    let ratio =
        explicit.statistics.accepted_steps as f64 / relaxed.statistics.accepted_steps as f64;
    assert!(
        ratio > 20.0,
        "{:?} vs {:?}",
        explicit.statistics,
        relaxed.statistics
    );

    // RK4 is stable below h ≈ 2.8/ω and blows up above it.
    let rk4 = |h: f64| {
        integrate::Integration::new(
            &stiff,
            STIFF_START,
            STIFF_START.t + 1.0,
            integrate::Rk4 {
                steps: (1.0 / h).round() as u64,
            },
        )
        .run()
    };
    // Stable, it follows the slow motion, as SDIRK below: the fast mode
    // (≈ 1e-3 rad/s in the speeds) is resolved by neither RK4 at this step
    // nor DOP853 at 1e-6, whose final speeds are both ≈ 8e-4 off a run at
    // 1e-12 and 1.6e-4 apart.
    let stable = rk4(5e-4).unwrap();
    assert!(state_error(&stable.end, &explicit.end) < 1e-3, "{stable:?}");
    let unstable = rk4(2e-3).unwrap_err();
    assert!(unstable.t < 0.1, "{unstable}");

    // SDIRK at a twentieth of the steps stays on the slow motion.
    let implicit = integrate::Integration::new(
        &stiff,
        STIFF_START,
        STIFF_START.t + 1.0,
        integrate::Sdirk { steps: 100 },
    )
    .run()
    .unwrap();
    assert!(
        state_error(&implicit.end, &explicit.end) < 1e-3,
        "{implicit:?}"
    );
    assert!(implicit.statistics.rhs_evaluations * 5 < explicit.statistics.rhs_evaluations);
}

#[test]
fn every_integrator_that_meets_the_singular_mass_matrix_stops_naming_time_and_configuration() {
    let dynamics = Unconstrained::without_inputs(&ON_AXIS);
    let finite = |s: &State<2, 2>| assert!(s.q.iter().chain(&s.v).all(|x| x.is_finite()), "{s:?}");
    // Each schedule puts an evaluation at t = 0.5: a step end for RK4 and
    // SDIRK (whose Jacobian is taken at each step's start), the final time of
    // the adaptive pairs, the first stage of the fifth step for Gauss.
    let gauss = |method, first_node: f64| {
        let h = 0.5 / (4.0 + first_node);
        integrate::Integration::new(
            &dynamics,
            TOWARDS_AXIS,
            TOWARDS_AXIS.t + 10.0 * h,
            integrate::Gauss {
                rule: method,
                steps: 10,
            },
        )
        .observe(finite)
        .run()
    };
    let adaptive = |pair| {
        let options = integrate::AdaptiveOptions::with_tolerance(1e-8);
        integrate::Integration::new(
            &dynamics,
            TOWARDS_AXIS,
            0.5,
            integrate::Adaptive { pair, options },
        )
        .observe(finite)
        .run()
    };
    let failures = [
        (
            "RK4",
            integrate::Integration::new(
                &dynamics,
                TOWARDS_AXIS,
                TOWARDS_AXIS.t + 1.0,
                integrate::Rk4 { steps: 8 },
            )
            .observe(finite)
            .run(),
        ),
        ("DOPRI5", adaptive(ExplicitPair::DormandPrince54)),
        ("DOP853", adaptive(ExplicitPair::Dop853)),
        ("midpoint", gauss(GaussLegendre::Midpoint, 0.5)),
        (
            "Gauss 4",
            gauss(GaussLegendre::Order4, 0.5 - 3f64.sqrt() / 6.0),
        ),
        (
            "Gauss 6",
            gauss(GaussLegendre::Order6, 0.5 - 15f64.sqrt() / 10.0),
        ),
        (
            "SDIRK",
            integrate::Integration::new(
                &dynamics,
                TOWARDS_AXIS,
                TOWARDS_AXIS.t + 1.0,
                integrate::Sdirk { steps: 8 },
            )
            .observe(finite)
            .run(),
        ),
    ];
    for (name, result) in failures {
        let error = result.expect_err(name);
        assert!((error.t - 0.5).abs() < 1e-12, "{name}: {error}");
        assert!((error.q[1] - FRAC_PI_2).abs() < 1e-12, "{name}: {error}");
        assert!(
            matches!(
                error.cause,
                Failure::Dynamics(DynamicsError::SingularMassMatrix {
                    coordinate: "phi",
                    ..
                })
            ),
            "{name}: {error}"
        );
        let message = error.to_string();
        assert!(
            message.starts_with("singular mass matrix: coordinate `phi`")
                && message.contains("at t = 0.5")
                && message.contains("q = [0.0, 1.57"),
            "{name}: {message}"
        );
    }
}

#[test]
fn chaotic_trajectories_one_e_minus_ten_apart_part_after_about_nine_seconds() {
    let dynamics = Unconstrained::without_inputs(&CHAOTIC);
    let (h, steps) = (2e-3, 6_000);
    let mut first = Vec::with_capacity(steps + 1);
    let method = GaussLegendre::Order6;
    integrate::Integration::new(
        &dynamics,
        CHAOTIC_START,
        CHAOTIC_START.t + steps as f64 * h,
        integrate::Gauss {
            rule: method,
            steps: steps as u64,
        },
    )
    .observe(|s| first.push(*s))
    .run()
    .unwrap();
    let mut nudged = CHAOTIC_START;
    nudged.q[0] += 1e-10;
    let mut parted = None;
    let mut index = 0;
    integrate::Integration::new(
        &dynamics,
        nudged,
        nudged.t + steps as f64 * h,
        integrate::Gauss {
            rule: method,
            steps: steps as u64,
        },
    )
    .observe(|s| {
        if parted.is_none() && state_error(s, &first[index]) > 1e-3 {
            parted = Some(s.t);
        }
        index += 1;
    })
    .run()
    .unwrap();
    // Measured: 8.75 s (Gauss 6, h = 1 ms); the reference README's
    // amplification of 1.3e7 by t = 10 puts it at about 9 s.
    let parted = parted.expect("the trajectories part within 12 s");
    assert!((7.5..10.5).contains(&parted), "parted at {parted} s");
}
