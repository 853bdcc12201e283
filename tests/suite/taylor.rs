//! The Taylor integrator and the coefficients it sums, against values
//! found apart from the code under test: closed forms (a linear
//! oscillator's coefficients, free precession, zero crossings), SymPy's
//! derivatives along the flow (`scripts/taylor_functions_reference.py`),
//! the 25-digit reference of the chaotic double pendulum, and the energy of
//! a conservative system.

use std::f64::consts::PI;

use dalembert::integrate::{Crossing, Event, Integration, State, Taylor, Unconstrained};
use dalembert_fixtures::stability::chaotic_reference;
use dalembert_generated::taylor_double_pendulum::TaylorDoublePendulum;
use dalembert_generated::taylor_functions::TaylorFunctions;
use dalembert_generated::taylor_oscillator::TaylorOscillator;
use dalembert_generated::taylor_top::TaylorTop;

const K: usize = 24;

/// `|a − b| ≤ tolerance · max(1, |b|)`.
fn close(what: &str, a: f64, b: f64, tolerance: f64) {
    assert!(
        (a - b).abs() <= tolerance * b.abs().max(1.0),
        "{what}: {a:e} against {b:e} (difference {:e})",
        (a - b).abs()
    );
}

/// `x(t) = x₀ cos ωt + (v₀/ω) sin ωt` has the coefficients
/// `ωᵏ (x₀ cos(kπ/2) + (v₀/ω) sin(kπ/2)) / k!`.
#[test]
fn oscillator_coefficients_are_the_closed_form_to_the_last_bits() {
    let oscillator = TaylorOscillator { m: 2.0, k: 8.0 };
    let (omega, x0, v0) = (2.0f64, 0.3, -0.5);
    let ([x], [v]) = oscillator
        .taylor_coefficients::<K>(0.7, &[x0], &[v0], &[], K - 1)
        .expect("expands");
    let mut factorial = 1.0;
    for k in 0..K {
        if k > 0 {
            factorial *= k as f64;
        }
        let derivative = |k: usize| {
            let angle = k as f64 * PI / 2.0;
            omega.powi(k as i32) * (x0 * angle.cos() + v0 / omega * angle.sin())
        };
        close(&format!("x_{k}"), x[k], derivative(k) / factorial, 1e-15);
        if k + 1 < K {
            close(
                &format!("v_{k}"),
                v[k],
                derivative(k + 1) / factorial,
                1e-15,
            );
        }
    }
}

/// Orders above the one asked for are zero, and the order is capped at
/// `K − 1`.
#[test]
fn coefficients_stop_at_the_order_asked_for() {
    let oscillator = TaylorOscillator { m: 1.0, k: 1.0 };
    let ([x], [v]) = oscillator
        .taylor_coefficients::<8>(0.0, &[1.0], &[0.0], &[], 4)
        .expect("expands");
    assert_eq!(x, [1.0, 0.0, -0.5, 0.0, 1.0 / 24.0, 0.0, 0.0, 0.0]);
    assert_eq!(v, [0.0, -1.0, 0.0, 1.0 / 6.0, 0.0, 0.0, 0.0, 0.0]);
    let (capped, _) = oscillator
        .taylor_coefficients::<3>(0.0, &[1.0], &[0.0], &[], 10)
        .expect("expands");
    assert_eq!(capped, [[1.0, 0.0, -0.5]]);
}

/// Every recurrence (quotients, powers, `sqrt`, `exp`, `ln`, `tan`, `abs`,
/// `sin`/`cos` of a coordinate and of the time, the moving mass matrix)
/// against SymPy's derivatives along the flow, printed by
/// `scripts/taylor_functions_reference.py` (30 digits).
#[test]
#[allow(clippy::excessive_precision)] // SymPy's digits as the script prints them
fn coefficients_match_sympys_derivatives_along_the_flow() {
    let system = TaylorFunctions {
        m: 1.5,
        k: 0.7,
        c: 0.3,
    };
    let ([x], [v]) = system
        .taylor_coefficients::<7>(0.2, &[0.8], &[-0.3], &[0.4], 6)
        .expect("expands");
    let expected_x = [
        0.8,
        -0.3,
        0.21027594722209126361,
        -0.036224382893640438665,
        -0.0062667597879301911418,
        -0.00088221463497440206834,
        -0.00099953862038983307716,
    ];
    let expected_v = [
        -0.3,
        0.42055189444418252722,
        -0.10867314868092131599,
        -0.025067039151720764567,
        -0.0044110731748720103417,
        -0.0059972317223389984630,
        0.010157756954766081476,
    ];
    for k in 0..7 {
        close(&format!("x_{k}"), x[k], expected_x[k], 1e-13);
        close(&format!("v_{k}"), v[k], expected_v[k], 1e-13);
    }
}

/// A state that cannot be expanded is the runtime's error, not a panic.
#[test]
fn a_non_finite_state_is_an_error() {
    let oscillator = TaylorOscillator { m: 1.0, k: 1.0 };
    let result = oscillator.taylor_coefficients::<8>(0.0, &[f64::NAN], &[0.0], &[], 5);
    assert_eq!(result, Err(dalembert::DynamicsError::NonFiniteState));
    let massless = TaylorOscillator { m: 0.0, k: 1.0 };
    let result = massless.taylor_coefficients::<8>(0.0, &[1.0], &[0.0], &[], 5);
    assert!(matches!(
        result,
        Err(dalembert::DynamicsError::SingularMassMatrix { .. })
    ));
}

/// Free precession of a symmetric body with its angular momentum along
/// `N.z`: `θ` stays, `ψ̇ = L / I₁` and `φ̇ = ψ̇ cos θ (I₁/I₃ − 1)` are
/// constant. Every coefficient above the first vanishes, and ten seconds
/// later the state is the straight line's.
#[test]
fn free_precession_is_a_uniform_turn() {
    let top = TaylorTop {
        m: 1.0,
        I1: 2.0,
        I3: 3.0,
    };
    let (theta, psi_dot) = (0.6f64, 1.3);
    let phi_dot = psi_dot * theta.cos() * (2.0 / 3.0 - 1.0);
    let (q0, v0) = ([0.1, theta, -0.2], [psi_dot, 0.0, phi_dot]);
    let (q, v) = top
        .taylor_coefficients::<K>(0.0, &q0, &v0, &[], 20)
        .expect("expands");
    for (i, (qi, vi)) in q.iter().zip(&v).enumerate() {
        assert!(qi[2..].iter().all(|c| c.abs() < 1e-15), "q{i}: {qi:?}");
        assert!(vi[1..].iter().all(|c| c.abs() < 1e-15), "v{i}: {vi:?}");
    }
    let dynamics = Unconstrained::without_inputs(&top);
    let start = State {
        t: 0.0,
        q: q0,
        v: v0,
    };
    let end = Integration::new(&dynamics, start, 10.0, Taylor::with_tolerance(1e-15))
        .run()
        .expect("integrates")
        .end;
    let expected = [0.1 + 10.0 * psi_dot, theta, -0.2 + 10.0 * phi_dot];
    for i in 0..3 {
        close("q", end.q[i], expected[i], 1e-13);
        close("v", end.v[i], v0[i], 1e-13);
    }
}

/// The chaotic double pendulum (seed example 1 from `θ₁ = θ₂ = 2`) at
/// `t = 10` against its 25-digit reference, at the tightest tolerance: the
/// reference data put the limit of double precision near 1e-8.
#[test]
fn the_chaotic_pendulum_reaches_its_reference() {
    let pendulum = TaylorDoublePendulum {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    let reference = chaotic_reference().expect("reference data");
    let dynamics = Unconstrained::without_inputs(&pendulum);
    let start = State {
        t: 0.0,
        q: [2.0, 2.0],
        v: [0.0, 0.0],
    };
    let solution = Integration::new(&dynamics, start, reference.t, Taylor::with_tolerance(1e-16))
        .run()
        .expect("integrates");
    let end = solution.end;
    let error = end
        .q
        .iter()
        .chain(&end.v)
        .zip(reference.q.iter().chain(&reference.v))
        .fold(0.0f64, |e, (a, b)| e.max((a - b).abs()));
    assert!(error < 1e-8, "error {error:e} at t = 10");
    assert_eq!(end.t, reference.t);
}

fn oscillating_pendulum() -> (TaylorDoublePendulum, State<2, 2>) {
    let pendulum = TaylorDoublePendulum {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    let start = State {
        t: 0.0,
        q: [0.2, 0.2],
        v: [0.0, 0.0],
    };
    (pendulum, start)
}

/// Relative energy error of the double pendulum at 0.2 rad after `t_end`.
fn energy_drift(t_end: f64) -> f64 {
    let (pendulum, start) = oscillating_pendulum();
    let dynamics = Unconstrained::without_inputs(&pendulum);
    let options = Taylor::with_tolerance(1e-16);
    let end = Integration::new(&dynamics, start, t_end, options)
        .run()
        .expect("integrates")
        .end;
    let energy = |s: &State<2, 2>| dalembert::energy(&pendulum, &s.q, &s.v);
    ((energy(&end) - energy(&start)) / energy(&start)).abs()
}

/// A conservative system keeps its energy to rounding over a hundred
/// seconds (the ten-thousand-second figure is the ignored test below).
#[test]
fn energy_is_kept_over_a_hundred_seconds() {
    let drift = energy_drift(100.0);
    assert!(drift < 1e-13, "relative energy error {drift:e}");
}

/// `cargo test --release --test suite taylor:: -- --ignored`: the energy over
/// 10⁴ s (BENCHMARKS.md quotes it).
#[test]
#[ignore = "long: run in release"]
fn energy_is_kept_over_ten_thousand_seconds() {
    let drift = energy_drift(1e4);
    println!("relative energy error over 1e4 s: {drift:e}");
    assert!(drift < 1e-12, "relative energy error {drift:e}");
}

/// The state inside each step, summed from its polynomial, is the closed
/// form's.
#[test]
fn dense_output_is_the_closed_form_between_steps() {
    let oscillator = TaylorOscillator { m: 2.0, k: 8.0 };
    let dynamics = Unconstrained::without_inputs(&oscillator);
    let start = State {
        t: 0.0,
        q: [0.3],
        v: [0.0],
    };
    let mut checked = 0;
    Integration::new(&dynamics, start, 5.0, Taylor::with_tolerance(1e-15))
        .dense(|step| {
            let (a, b) = (step.start().t, step.end().t);
            for theta in [0.25, 0.5, 0.9] {
                let t = a + theta * (b - a);
                let state = step.state_at(t);
                close("x", state.q[0], 0.3 * (2.0 * t).cos(), 1e-13);
                close("v", state.v[0], -0.6 * (2.0 * t).sin(), 1e-13);
                checked += 1;
            }
            std::ops::ControlFlow::Continue(())
        })
        .run()
        .expect("integrates");
    assert!(checked >= 6, "{checked} points");
}

/// `x = 0.3 cos 2t` crosses zero at `t = π/4 + nπ/2`; the events are
/// located on the polynomials to 1e-12 s, and a stopping event ends there.
#[test]
fn events_are_located_on_the_polynomial() {
    let oscillator = TaylorOscillator { m: 2.0, k: 8.0 };
    let dynamics = Unconstrained::without_inputs(&oscillator);
    let start = State {
        t: 0.0,
        q: [0.3],
        v: [0.0],
    };
    let options = Taylor::with_tolerance(1e-15);
    let through_zero = |_: f64, q: &[f64; 1], _: &[f64; 1]| q[0];
    let mut times = Vec::new();
    let event = Event::record(through_zero, Crossing::Either);
    Integration::new(&dynamics, start, 6.0, options)
        .event(event, |s| times.push(s.t))
        .run()
        .expect("integrates");
    let expected: Vec<f64> = (0..4).map(|n| PI / 4.0 + n as f64 * PI / 2.0).collect();
    assert_eq!(times.len(), expected.len(), "{times:?}");
    for (t, e) in times.iter().zip(&expected) {
        assert!((t - e).abs() < 1e-12, "{t} against {e}");
    }
    let event = Event::stop_at(through_zero, Crossing::Rising);
    let end = Integration::new(&dynamics, start, 6.0, options)
        .event(event, |_| {})
        .run()
        .expect("integrates")
        .end;
    assert!((end.t - 3.0 * PI / 4.0).abs() < 1e-12, "{}", end.t);
}

/// Order 1 of the speeds is the accelerations that the emitted solver
/// (`dalembert::accelerations`, another route) computes.
#[test]
fn order_two_is_half_the_accelerations() {
    let (pendulum, _) = oscillating_pendulum();
    let (q, v) = ([1.1, -0.4], [0.3, 2.0]);
    let (series_q, series_v) = pendulum
        .taylor_coefficients::<8>(0.0, &q, &v, &[], 7)
        .expect("expands");
    let a = dalembert::accelerations(&pendulum, 0.0, &q, &v, &[]).expect("solves");
    for i in 0..2 {
        close("q₂", series_q[i][2], a[i] / 2.0, 1e-15);
        close("v₁", series_v[i][1], a[i], 1e-15);
    }
}
