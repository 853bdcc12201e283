//! A free joint end to end, through the macro: the emitted equations against
//! Newton–Euler in closed form, the configuration update (a quaternion stays
//! unit), a body thrown under gravity (parabola of the centre, torque-free
//! precession; by DOP853 and by the Taylor series of `q̇ = N(q) v`), the
//! Dzhanibekov effect in quaternions (energy and angular momentum conserved
//! while the body flips), and the regressor of a floating arm.

use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration, Taylor};
use dalembert::{State, Unconstrained, energy};
use dalembert_codegen::testing::{mat_vec, quaternion_rotation as rotation};

dalembert::dalembert! {
    /// An axisymmetric body thrown under gravity.
    pub Thrown {
        parameters m, I1, I3, g;
        joint free base { parent: N, child: B, at: O };
        body b { mass: m, center: base, frame: B, inertia: [I1, I1, I3] };
        gravity -g * N.z;
        outputs taylor;
    }
}

dalembert::dalembert! {
    /// A rigid body turning freely about its centre.
    pub Tumbler {
        parameters I1, I2, I3;
        joint spherical ball { parent: N, child: B, at: O };
        body b { mass: 1, center: ball, frame: B, inertia: [I1, I2, I3] };
    }
}

dalembert::dalembert! {
    /// A floating base carrying an arm on a hinge, on a ball-jointed tail:
    /// every parameter that enters linearly, for the regressor.
    pub FloatingArm {
        parameters m1, c1, J1, J2, J3, m2, a, K1, K3, L, m3, d, g;
        joint free base { parent: N, child: B, at: O };
        coordinates q1;
        joint revolute hinge { parent: B, child: C, axis: y, coordinate: q1, at: base + L * B.x };
        joint spherical tail { parent: B, child: D, at: base - L * B.x };
        body hull { mass: m1, center: base + c1 * B.z, frame: B, inertia: [J1, J2, J3, 0.1, 0, 0] };
        body arm { mass: m2, center: hinge + a * C.x, frame: C, inertia: [K1, K1, K3] };
        body fin { mass: m3, center: tail - d * D.x, frame: D, inertia: [0.01, 0.02, 0.03] };
        gravity -g * N.z;
        outputs inverse_dynamics, regressor;
    }
}

pub(crate) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn quaternion(q: &[f64]) -> [f64; 4] {
    [q[0], q[1], q[2], q[3]]
}

const THROWN: Thrown = Thrown {
    m: 2.0,
    I1: 0.3,
    I3: 0.5,
    g: 9.81,
};

/// Tilted, moving and spinning.
fn thrown_start() -> State<7, 6> {
    let (s, c) = (0.4_f64).sin_cos();
    State {
        t: 0.0,
        q: [0.1, -0.2, 1.0, s * 0.6, s * 0.8, 0.0, c],
        v: [1.0, 0.5, 3.0, 0.7, -0.4, 5.0],
    }
}

#[test]
fn the_api_has_seven_coordinates_and_six_speeds() {
    assert_eq!((Thrown::NQ, Thrown::NV), (7, 6));
    assert_eq!(
        Thrown::COORDINATES,
        [
            "base_x", "base_y", "base_z", "base_qx", "base_qy", "base_qz", "base_qw"
        ]
    );
    assert_eq!(
        Thrown::SPEEDS,
        [
            "base_vx", "base_vy", "base_vz", "base_wx", "base_wy", "base_wz"
        ]
    );
    assert_eq!(Tumbler::SPEEDS, ["ball_wx", "ball_wy", "ball_wz"]);
}

#[test]
fn the_emitted_equations_are_newton_and_euler_in_body_axes() {
    let start = thrown_start();
    let (q, v) = (start.q, start.v);
    let Thrown { m, I1, I3, g } = THROWN;
    let mass = THROWN.mass_matrix(&q);
    let inertia = [I1, I1, I3];
    for (k, row) in mass.iter().enumerate() {
        for (j, entry) in row.iter().enumerate() {
            let expected = match k == j {
                true if k < 3 => m,
                true => inertia[k - 3],
                false => 0.0,
            };
            assert!((entry - expected).abs() < 1e-14, "M[{k}][{j}]");
        }
    }
    // f = (m Rᵀ g − m ω × v, −ω × I ω)
    let r = rotation(quaternion(&q[3..]));
    let weight: [f64; 3] = [0, 1, 2].map(|i| r[2][i] * -m * g);
    let (u, w) = ([v[0], v[1], v[2]], [v[3], v[4], v[5]]);
    let h = [I1 * w[0], I1 * w[1], I3 * w[2]];
    let expected = [
        weight[0] - m * (w[1] * u[2] - w[2] * u[1]),
        weight[1] - m * (w[2] * u[0] - w[0] * u[2]),
        weight[2] - m * (w[0] * u[1] - w[1] * u[0]),
        -(w[1] * h[2] - w[2] * h[1]),
        -(w[2] * h[0] - w[0] * h[2]),
        -(w[0] * h[1] - w[1] * h[0]),
    ];
    let forcing = THROWN.forcing(0.0, &q, &v, &[]);
    for k in 0..6 {
        assert!((forcing[k] - expected[k]).abs() < 1e-13, "f[{k}]");
    }
    // q̇ = N(q) v: the origin moves at R v, the quaternion at ½ q ⊗ ω.
    let rates = THROWN.coordinate_rates(&q, &v);
    let velocity = mat_vec(&r, u);
    for i in 0..3 {
        assert!((rates[i] - velocity[i]).abs() < 1e-15, "ṙ[{i}]");
    }
    let [x, y, z, s] = quaternion(&q[3..]);
    let spin = [
        0.5 * (s * w[0] + y * w[2] - z * w[1]),
        0.5 * (s * w[1] + z * w[0] - x * w[2]),
        0.5 * (s * w[2] + x * w[1] - y * w[0]),
        -0.5 * (x * w[0] + y * w[1] + z * w[2]),
    ];
    for i in 0..4 {
        assert!((rates[3 + i] - spin[i]).abs() < 1e-15, "q̇[{i}]");
    }
}

#[test]
fn the_configuration_update_is_exact_and_keeps_the_quaternion_unit() {
    let start = thrown_start();
    // Constant speeds for 2 s: a screw motion, compared with many small
    // steps of the same update (which compose exactly).
    let once = THROWN.integrate_configuration(&start.q, &start.v, 2.0);
    let mut q = start.q;
    for _ in 0..1000 {
        q = THROWN.integrate_configuration(&q, &start.v, 2e-3);
    }
    for i in 0..7 {
        assert!(
            (once[i] - q[i]).abs() < 1e-12,
            "q[{i}]: {} vs {}",
            once[i],
            q[i]
        );
    }
    assert!((norm(&once[3..]) - 1.0).abs() < 1e-15);
    // A quaternion that is not unit in a call is normalised by the update
    // (the equations take it as given: R(q) is |q|² times a rotation).
    let mut long = start.q;
    long[3..].iter_mut().for_each(|c| *c *= 3.0);
    let still = THROWN.integrate_configuration(&long, &[0.0; 6], 0.1);
    for (i, (got, expected)) in still.iter().zip(start.q).enumerate() {
        assert!((got - expected).abs() < 1e-15, "q[{i}]");
    }
}

/// The adaptive DOP853 at tolerance `1e-12`.
fn tight() -> AdaptiveOptions {
    AdaptiveOptions {
        max_steps: 10_000_000,
        ..AdaptiveOptions::with_tolerance(1e-12)
    }
}

#[test]
fn a_thrown_body_follows_the_parabola_and_precesses_about_its_axis() {
    let start = thrown_start();
    let dynamics = Unconstrained::without_inputs(&THROWN);
    let end = Integration::new(
        &dynamics,
        start,
        2.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options: tight(),
        },
    )
    .run()
    .expect("integrates")
    .end;
    assert_thrown_motion(&start, &end, 1e-9);
}

/// The Taylor integrator's series of `q̇ = N(q) v` (the position's rate
/// `R(q) v` as well as the quaternion's) follow the same closed form,
/// tighter.
#[test]
fn the_taylor_series_of_a_thrown_body_follow_the_parabola_and_the_precession() {
    let start = thrown_start();
    let dynamics = Unconstrained::without_inputs(&THROWN);
    let options = Taylor::with_tolerance(1e-15);
    let end = Integration::new(&dynamics, start, 2.0, options)
        .run()
        .expect("integrates")
        .end;
    assert_thrown_motion(&start, &end, 1e-11);
}

/// `end` is the thrown body's motion from `start` to within `tolerance`.
fn assert_thrown_motion(start: &State<7, 6>, end: &State<7, 6>, tolerance: f64) {
    let t = end.t - start.t;
    // The centre: r₀ + v₀ t − ½ g t² N.z, with v₀ = R₀ v.
    let v0 = mat_vec(
        &rotation(quaternion(&start.q[3..])),
        [start.v[0], start.v[1], start.v[2]],
    );
    for (i, v0) in v0.into_iter().enumerate() {
        let gravity = if i == 2 { -0.5 * THROWN.g * t * t } else { 0.0 };
        let expected = start.q[i] + v0 * t + gravity;
        assert!(
            (end.q[i] - expected).abs() < tolerance,
            "r[{i}] {} vs {expected}",
            end.q[i]
        );
    }
    // Torque-free and axisymmetric: ω₃ constant, (ω₁, ω₂) turning at
    // λ = (I₃ − I₁) ω₃ / I₁ in body axes.
    let (w1, w2, w3) = (start.v[3], start.v[4], start.v[5]);
    let lambda = (THROWN.I3 - THROWN.I1) * w3 / THROWN.I1;
    let (s, c) = (lambda * t).sin_cos();
    let expected = [w1 * c - w2 * s, w1 * s + w2 * c, w3];
    for (i, expected) in expected.into_iter().enumerate() {
        assert!(
            (end.v[3 + i] - expected).abs() < tolerance,
            "ω[{i}] {} vs {expected}",
            end.v[3 + i]
        );
    }
}

pub(crate) const DZHANIBEKOV: Tumbler = Tumbler {
    I1: 1.0,
    I2: 2.0,
    I3: 3.0,
};

/// The angular momentum `R I ω` in `N`'s axes.
fn momentum(q: &[f64; 4], v: &[f64; 3]) -> [f64; 3] {
    let body = [
        DZHANIBEKOV.I1 * v[0],
        DZHANIBEKOV.I2 * v[1],
        DZHANIBEKOV.I3 * v[2],
    ];
    mat_vec(&rotation(*q), body)
}

#[test]
fn dzhanibekov_flips_while_energy_and_momentum_stay() {
    // Spun about the intermediate axis, with a small wobble.
    let start = State {
        t: 0.0,
        q: [0.0, 0.0, 0.0, 1.0],
        v: [1e-3, 2.0, 1e-3],
    };
    let dynamics = Unconstrained::without_inputs(&DZHANIBEKOV);
    let (e0, l0) = (
        energy(&DZHANIBEKOV, &start.q, &start.v),
        momentum(&start.q, &start.v),
    );
    let (mut worst_energy, mut worst_momentum) = (0.0_f64, 0.0_f64);
    let mut flips = 0;
    let mut sign = 1.0;
    Integration::new(
        &dynamics,
        start,
        100.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options: tight(),
        },
    )
    .observe(|s| {
        let e = energy(&DZHANIBEKOV, &s.q, &s.v);
        worst_energy = worst_energy.max((e - e0).abs() / e0);
        let l = momentum(&s.q, &s.v);
        let drift = [0, 1, 2].map(|i| l[i] - l0[i]);
        worst_momentum = worst_momentum.max(norm(&drift) / norm(&l0));
        if s.v[1] * sign < 0.0 {
            flips += 1;
            sign = -sign;
        }
    })
    .run()
    .expect("integrates");
    println!("relative drift: energy {worst_energy:e}, momentum {worst_momentum:e}; {flips} flips");
    assert!(flips >= 4, "{flips} flips in 100 s");
    assert!(worst_energy < 1e-9, "energy drift {worst_energy:e}");
    assert!(worst_momentum < 1e-9, "momentum drift {worst_momentum:e}");
}

/// The regressor of a system with free and spherical joints: `Y π` is the
/// inverse dynamics at states with unit quaternions, and the base
/// parameters hold every parameter that enters linearly.
#[test]
fn a_floating_regressor_times_its_base_parameters_is_the_inverse_dynamics() {
    let arm = FloatingArm {
        m1: 3.0,
        c1: 0.05,
        J1: 0.4,
        J2: 0.5,
        J3: 0.6,
        m2: 1.2,
        a: 0.3,
        K1: 0.02,
        K3: 0.03,
        L: 0.5,
        m3: 0.4,
        d: 0.2,
        g: 9.81,
    };
    let pi = arm.base_parameters();
    let unit = |x: [f64; 4]| x.map(|c| c / norm(&x));
    for k in 0..5 {
        let s = f64::from(k);
        let (b, d) = (
            unit([0.3 + s, -0.2, 0.5 - 0.1 * s, 0.9]),
            unit([-0.1, 0.4 * s, 0.2, 0.7]),
        );
        let q = [
            0.1 * s,
            -0.3,
            1.0,
            b[0],
            b[1],
            b[2],
            b[3],
            0.7 - 0.2 * s,
            d[0],
            d[1],
            d[2],
            d[3],
        ];
        let v: [f64; 10] = core::array::from_fn(|i| (0.37 * (i as f64 + s)).sin() * 2.0);
        let vdot: [f64; 10] = core::array::from_fn(|i| (0.61 * (i as f64) - s).cos() * 3.0);
        let tau = arm.inverse_dynamics(0.0, &q, &v, &vdot, &[]);
        let y = arm.regressor(&q, &v, &vdot);
        let scale = norm(&tau).max(1.0);
        for (i, (row, tau)) in y.iter().zip(tau).enumerate() {
            let product: f64 = row.iter().zip(&pi).map(|(y, p)| y * p).sum();
            assert!(
                (product - tau).abs() <= 1e-12 * scale,
                "state {k}, row {i}: Y π = {product}, τ = {tau}"
            );
        }
    }
}
