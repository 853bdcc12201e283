//! A pendulum whose pivot is shaken horizontally, written with the pivot's
//! prescribed motion in its geometry: `point P = O + A*sin(w*t)*N.x`.
//!
//! `t` stays in the kinetic energy (`T` has the pivot's speed `A w cos(w t)`),
//! so the system is time-dependent: its `M`, `T` and `V` are the `_at`
//! functions with `t`. Its equation is
//! `ℓ θ̈ = A w² sin(w t) cos θ − g sin θ`; linearised about the bottom,
//! `θ̈ + ω₀² θ = (A w² / ℓ) sin(w t)` with `ω₀² = g/ℓ`, whose solution
//! from `θ(0) = 0`, `θ̇(0) = θ̇₀` is
//! `θ = K sin(w t) + (θ̇₀ − K w)/ω₀ sin(ω₀ t)`, `K = (A w²/ℓ)/(ω₀² − w²)`.

use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration};
use dalembert::{MultibodySystem, State, Unconstrained};
use dalembert_codegen::testing::{Interpreter, Route, Sample};

dalembert::dalembert! {
    /// A pendulum whose pivot is shaken horizontally, `x = A sin(w t)`.
    pub ShakenPendulum {
        parameters m, l, g, A, w;
        coordinates theta;
        frame B = N.rotate_z(theta);
        point P = O + A * sin(w * t) * N.x;
        point Q = P - l * B.y;
        particle bob { mass: m, at: Q };
        gravity -g * N.y;
    }
}

/// The same model, for the interpreter.
const SHAKEN_PENDULUM: &str = "pub ShakenPendulum {
    parameters m, l, g, A, w;
    coordinates theta;
    frame B = N.rotate_z(theta);
    point P = O + A * sin(w * t) * N.x;
    point Q = P - l * B.y;
    particle bob { mass: m, at: Q };
    gravity -g * N.y;
}";

const L: f64 = 0.8;
const G: f64 = 9.81;

fn shaken(amplitude: f64, frequency: f64) -> ShakenPendulum {
    ShakenPendulum {
        m: 0.7,
        l: L,
        g: G,
        A: amplitude,
        w: frequency,
    }
}

#[test]
fn the_system_carries_time_in_its_energies() {
    const { assert!(ShakenPendulum::TIME_DEPENDENT) };
    const { assert!(<ShakenPendulum as MultibodySystem<1, 1, 0>>::TIME_DEPENDENT) };
    let p = shaken(0.05, 7.0);
    let (t, q, v): (f64, [f64; 1], [f64; 1]) = (0.3, [0.4], [-1.1]);
    // The bob's velocity: the pivot's A w cos(w t) N.x plus ℓ θ̇ along B.x.
    let pivot = p.A * p.w * (p.w * t).cos();
    let (s, c) = q[0].sin_cos();
    let (vx, vy) = (pivot + p.l * c * v[0], p.l * s * v[0]);
    let expected = 0.5 * p.m * (vx * vx + vy * vy);
    let kinetic = p.kinetic_energy_at(t, &q, &v);
    assert!(
        (kinetic - expected).abs() <= 1e-14 * expected,
        "{kinetic} vs {expected}"
    );
    let [[mass]] = p.mass_matrix_at(t, &q);
    assert!((mass - p.m * p.l * p.l).abs() < 1e-15, "{mass}");
    let potential = p.potential_energy_at(t, &q);
    assert!((potential + p.m * p.g * p.l * c).abs() < 1e-14);
    // The traits' time-free functions have no time to give: NaN, never a
    // value at some time.
    assert!(MultibodySystem::kinetic_energy(&p, &q, &v).is_nan());
    assert!(MultibodySystem::mass_matrix(&p, &q)[0][0].is_nan());
    assert!(dalembert::energy(&p, &q, &v).is_nan());
    let total = dalembert::energy_at(&p, t, &q, &v);
    assert!((total - (expected + potential)).abs() < 1e-14);
}

#[test]
fn accelerations_are_the_closed_form_of_the_shaken_pivot() {
    let p = shaken(0.05, 7.0);
    let mut checked = 0;
    for (t, theta, omega) in [(0.0, 0.2, 0.0), (0.31, -1.3, 2.0), (2.7, 2.9, -4.0)] {
        let [acceleration] =
            dalembert::accelerations(&p, t, &[theta], &[omega], &[]).expect("regular");
        let expected = (p.A * p.w * p.w * (p.w * t).sin() * theta.cos() - p.g * theta.sin()) / p.l;
        assert!(
            (acceleration - expected).abs() <= 1e-13 * expected.abs().max(1.0),
            "t = {t}: {acceleration} vs {expected}"
        );
        checked += 1;
    }
    assert_eq!(checked, 3);
}

#[test]
fn small_shaking_follows_the_linearised_response() {
    // θ stays of order 1e-6, so the linearisation's error (θ³ against θ) is
    // of order 1e-12 relative.
    let (amplitude, frequency) = (1e-6, 2.3);
    let p = shaken(amplitude, frequency);
    let natural = (G / L).sqrt();
    let gain = amplitude * frequency * frequency / L / (natural * natural - frequency * frequency);
    let start_rate = 3e-6;
    let closed = |t: f64| {
        gain * (frequency * t).sin()
            + (start_rate - gain * frequency) / natural * (natural * t).sin()
    };
    let dynamics = Unconstrained::without_inputs(&p);
    let start = State {
        t: 0.0,
        q: [0.0],
        v: [start_rate],
    };
    let mut worst: f64 = 0.0;
    let mut seen = 0;
    // θ is of order 1e-6: a relative tolerance, and an absolute one far
    // below the motion.
    let options = AdaptiveOptions {
        relative_tolerance: 1e-13,
        absolute_tolerance: 1e-22,
        ..AdaptiveOptions::with_tolerance(1e-13)
    };
    let end = Integration::new(
        &dynamics,
        start,
        10.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .observe(|s| {
        worst = worst.max((s.q[0] - closed(s.t)).abs());
        seen += 1;
    })
    .run()
    .expect("integrates")
    .end;
    assert!(seen > 10, "{seen} states");
    assert_eq!(end.t, 10.0);
    let scale = gain.abs() + start_rate / natural;
    println!("largest deviation from the closed form: {worst:e} (scale {scale:e})");
    assert!(
        worst <= 1e-9 * scale,
        "{worst:e} against the scale {scale:e}"
    );
}

#[test]
fn generated_code_agrees_with_the_interpreter_on_both_routes() {
    let close = |what: &str, a: f64, b: f64| {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs().max(1.0),
            "{what}: {a} vs {b}"
        );
    };
    let mut checked = 0;
    for route in [Route::Dalembert, Route::Lagrange] {
        let interpreter = Interpreter::new(SHAKEN_PENDULUM, route).expect("a valid model");
        for seed in 0..8 {
            let sample = Sample::random(&interpreter, seed);
            let at = sample.values();
            let [m, l, g, amplitude, w] = [0, 1, 2, 3, 4].map(|i| sample.parameters[i]);
            let p = ShakenPendulum {
                m,
                l,
                g,
                A: amplitude,
                w,
            };
            let (t, q, v) = (sample.t, [sample.q[0]], [sample.qd[0]]);
            close(
                "M",
                p.mass_matrix_at(t, &q)[0][0],
                interpreter.mass_matrix(&at)[0][0],
            );
            close(
                "f",
                p.forcing(t, &q, &v, &[])[0],
                interpreter.forcing(&at)[0],
            );
            close(
                "T",
                p.kinetic_energy_at(t, &q, &v),
                interpreter.kinetic_energy(&at),
            );
            close(
                "V",
                p.potential_energy_at(t, &q),
                interpreter.potential_energy(&at),
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 16);
}
