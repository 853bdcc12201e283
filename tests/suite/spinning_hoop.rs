//! A bead on a hoop spun about its vertical diameter at a prescribed rate,
//! `frame H = N.rotate_y(W * t)`: the textbook system whose bottom loses
//! its stability above the critical rate `W² = g/R`.
//!
//! With `θ` the bead's angle from the bottom, `R θ̈ = sin θ (R W² cos θ − g)`.
//! Above the critical rate the bead rests at `cos θ* = g/(R W²)`, where it
//! oscillates at `ω = W sin θ*`; the bottom is unstable, with the exponent
//! `√(W² − g/R)`. `t` cancels from `M`, `T` and `V` (the hoop turns
//! steadily about the axis it is symmetric about), so the time-free API
//! holds, and the Jacobi integral `T₂ − T₀ + V` is conserved where `T + V`
//! is not.

use std::f64::consts::PI;

use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration};
use dalembert::{MultibodySystem, State, Unconstrained};

dalembert::dalembert! {
    /// A bead on a hoop of radius `R` spun at the rate `W` about its vertical diameter.
    pub SpinningHoop {
        parameters m, R, W, g;
        coordinates theta;
        frame H = N.rotate_y(W * t);
        frame B = H.rotate_z(theta);
        point P = O - R * B.y;
        particle bead { mass: m, at: P };
        gravity -g * N.y;
    }
}

const HOOP: SpinningHoop = SpinningHoop {
    m: 0.05,
    R: 0.4,
    W: 7.0,
    g: 9.81,
};

fn rest_angle() -> f64 {
    (HOOP.g / (HOOP.R * HOOP.W * HOOP.W)).acos()
}

fn acceleration(t: f64, theta: f64, rate: f64) -> f64 {
    dalembert::accelerations(&HOOP, t, &[theta], &[rate], &[]).expect("regular")[0]
}

#[test]
fn time_cancels_from_the_mass_matrix_and_energies() {
    const { assert!(!<SpinningHoop as MultibodySystem<1, 1, 0>>::TIME_DEPENDENT) };
    let (theta, rate): (f64, f64) = (0.7, 1.3);
    let expected = 0.5 * HOOP.m * HOOP.R.powi(2) * (rate * rate + (HOOP.W * theta.sin()).powi(2));
    let kinetic = HOOP.kinetic_energy(&[theta], &[rate]);
    assert!(
        (kinetic - expected).abs() <= 1e-15,
        "{kinetic} vs {expected}"
    );
}

#[test]
fn the_bead_rests_off_the_bottom_above_the_critical_rate() {
    const { assert!(HOOP.W * HOOP.W > HOOP.g / HOOP.R) };
    let rest = rest_angle();
    let mut checked = 0;
    for t in [0.0, 0.4, 3.1] {
        for theta in [rest, -rest] {
            let a = acceleration(t, theta, 0.0);
            assert!(a.abs() < 1e-12, "t = {t}, θ = {theta}: θ̈ = {a:e}");
            checked += 1;
        }
        // The bottom is an equilibrium too.
        assert_eq!(acceleration(t, 0.0, 0.0), 0.0);
    }
    assert_eq!(checked, 6);
}

#[test]
fn the_rest_angle_is_stable_with_the_closed_form_frequency() {
    let rest = rest_angle();
    let frequency = HOOP.W * rest.sin();
    // The stiffness −∂θ̈/∂θ at the rest angle, by central differences.
    let h = 1e-5;
    let stiffness =
        -(acceleration(0.0, rest + h, 0.0) - acceleration(0.0, rest - h, 0.0)) / (2.0 * h);
    assert!(
        (stiffness - frequency * frequency).abs() < 1e-8 * frequency * frequency,
        "{stiffness} vs {}",
        frequency * frequency
    );
    // A small oscillation comes back after one period, to second order in
    // its amplitude.
    let amplitude = 1e-5;
    let period = 2.0 * PI / frequency;
    let start = State {
        t: 0.0,
        q: [rest + amplitude],
        v: [0.0],
    };
    let dynamics = Unconstrained::without_inputs(&HOOP);
    let mut farthest: f64 = 0.0;
    let jacobi = |s: &State<1, 1>| dalembert::jacobi_integral(&HOOP, s.t, &s.q, &s.v);
    let (h0, mut worst_jacobi) = (jacobi(&start), 0.0_f64);
    let options = AdaptiveOptions::with_tolerance(1e-13);
    let end = Integration::new(
        &dynamics,
        start,
        period,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .observe(|s| {
        farthest = farthest.max((s.q[0] - rest).abs());
        worst_jacobi = worst_jacobi.max((jacobi(s) - h0).abs());
    })
    .run()
    .expect("integrates")
    .end;
    assert!(
        farthest <= amplitude * (1.0 + 1e-3),
        "stays near rest: {farthest:e}"
    );
    let back = (end.q[0] - rest - amplitude).abs();
    assert!(back < 1e-3 * amplitude, "after one period: {back:e} off");
    assert!(
        worst_jacobi < 1e-13,
        "Jacobi integral drift {worst_jacobi:e}"
    );
}

#[test]
fn the_bottom_is_unstable_with_the_closed_form_exponent() {
    let exponent = (HOOP.W * HOOP.W - HOOP.g / HOOP.R).sqrt();
    let h = 1e-6;
    let slope = (acceleration(0.0, h, 0.0) - acceleration(0.0, -h, 0.0)) / (2.0 * h);
    assert!(
        (slope - exponent * exponent).abs() < 1e-8 * exponent * exponent,
        "{slope} vs {}",
        exponent * exponent
    );
    // Released 1e-9 from the bottom, it leaves as cosh(λ t).
    let start = State {
        t: 0.0,
        q: [1e-9],
        v: [0.0],
    };
    let dynamics = Unconstrained::without_inputs(&HOOP);
    let options = AdaptiveOptions::with_tolerance(1e-14);
    let end = Integration::new(
        &dynamics,
        start,
        2.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .run()
    .expect("integrates")
    .end;
    let expected = 1e-9 * (exponent * 2.0).cosh();
    assert!(
        (end.q[0] - expected).abs() < 1e-6 * expected,
        "{} vs {expected}",
        end.q[0]
    );
}

#[test]
fn energy_is_not_conserved_but_the_jacobi_integral_is() {
    let start = State {
        t: 0.0,
        q: [0.3],
        v: [2.0],
    };
    let dynamics = Unconstrained::without_inputs(&HOOP);
    let jacobi = |s: &State<1, 1>| dalembert::jacobi_integral(&HOOP, s.t, &s.q, &s.v);
    let energy = |s: &State<1, 1>| dalembert::energy(&HOOP, &s.q, &s.v);
    let (h0, e0) = (jacobi(&start), energy(&start));
    let (mut worst_jacobi, mut widest_energy, mut seen) = (0.0_f64, 0.0_f64, 0);
    let options = AdaptiveOptions::with_tolerance(1e-13);
    Integration::new(
        &dynamics,
        start,
        5.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .observe(|s| {
        worst_jacobi = worst_jacobi.max((jacobi(s) - h0).abs());
        widest_energy = widest_energy.max((energy(s) - e0).abs());
        seen += 1;
    })
    .run()
    .expect("integrates");
    assert!(seen > 10);
    // T₂ − T₀ + V: ½ m R² θ̇² − ½ m R² W² sin²θ − m g R cos θ.
    let (m, r, w, g) = (HOOP.m, HOOP.R, HOOP.W, HOOP.g);
    let closed = 0.5 * m * r * r * (4.0 - (w * 0.3_f64.sin()).powi(2)) - m * g * r * 0.3_f64.cos();
    assert!((h0 - closed).abs() < 1e-15, "{h0} vs {closed}");
    println!("Jacobi integral drift {worst_jacobi:e}; energy swings by {widest_energy:e}");
    assert!(worst_jacobi < 1e-12 * h0.abs().max(1.0), "{worst_jacobi:e}");
    assert!(
        widest_energy > 1e-3,
        "the motor does work: {widest_energy:e}"
    );
}
