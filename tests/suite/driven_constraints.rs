//! Constraints that drive a system with time, against closed forms: a driven
//! crank and a bead on a hoop turned by a constraint, whose bias must carry
//! the explicit time derivatives, and whose motor does the work.

use crate::redundant_parallelogram::scalar_motion;

use dalembert::constrained::{constrained_accelerations, constraint_drift};
use dalembert::integrate::{Integration, Rk4};
use dalembert::{Constrained, Stabilisation, State, energy};
use dalembert_fixtures::reference::assert_near;

dalembert::dalembert! {
    /// A slider-crank whose crank a motor drives through a prescribed
    /// angle, `theta = w t + k sin(w t)`: three rows, three coordinates,
    /// the driving row's multiplier the motor's torque.
    pub DrivenSliderCrank {
        parameters r, L, m, g, w, k;
        coordinates theta, phi, s;
        frame C = N.rotate_z(theta);
        frame R = N.rotate_z(phi);
        point A = O + r * C.x;
        body crank { mass: m, center: O + r/2 * C.x, frame: C, inertia: [0, 0, m*r^2/12] };
        body rod { mass: m, center: A + L/2 * R.x, frame: R, inertia: [0, 0, m*L^2/12] };
        particle slider { mass: m, at: O + s * N.x };
        gravity -g * N.y;
        constraint r*cos(theta) + L*cos(phi) - s == 0;
        constraint r*sin(theta) + L*sin(phi) == 0;
        constraint theta == w*t + k*sin(w*t);
    }
}

const DRIVEN: DrivenSliderCrank = DrivenSliderCrank {
    r: 0.1,
    L: 0.3,
    m: 0.6,
    g: 9.81,
    w: 7.0,
    k: 0.4,
};

/// The prescribed motion of [`DRIVEN`] at `t`, in closed form.
fn driven_motion(t: f64) -> [f64; 3] {
    let DrivenSliderCrank { r, L, w, k, .. } = DRIVEN;
    let theta = w * t + k * (w * t).sin();
    let phi = -(r * theta.sin() / L).asin();
    [theta, phi, r * theta.cos() + L * phi.cos()]
}

/// The rate and acceleration of `motion` at `t` by central differences
/// (steps `1e-5` and `1e-4`: errors about `1e-9` and `1e-7` relative for
/// [`DRIVEN`]).
fn differentiated(motion: impl Fn(f64) -> [f64; 3], t: f64) -> ([f64; 3], [f64; 3]) {
    let (h, h2) = (1e-5, 1e-4);
    let (ahead, behind) = (motion(t + h), motion(t - h));
    let (far_ahead, here, far_behind) = (motion(t + h2), motion(t), motion(t - h2));
    (
        std::array::from_fn(|i| (ahead[i] - behind[i]) / (2.0 * h)),
        std::array::from_fn(|i| (far_ahead[i] - 2.0 * here[i] + far_behind[i]) / (h2 * h2)),
    )
}

#[test]
fn driven_crank_bias_carries_the_explicit_time_derivative() {
    for t in [0.0, 0.13, 0.61, 1.4] {
        let q = driven_motion(t);
        let (qd, qdd) = differentiated(driven_motion, t);
        assert!(
            DRIVEN
                .constraint_residual(t, &q)
                .iter()
                .all(|r| r.abs() < 1e-15)
        );
        let velocity = DRIVEN.constraint_velocity(t, &q, &qd);
        assert!(velocity.iter().all(|v| v.abs() < 1e-8), "{velocity:?}");
        // On the motion, A q̈ = b, the driving row's b being θ̈ itself.
        let a = DRIVEN.constraint_jacobian(&q);
        let b = DRIVEN.constraint_bias(t, &q, &qd);
        for (row, bias) in a.iter().zip(b) {
            let achieved: f64 = row.iter().zip(&qdd).map(|(a, x)| a * x).sum();
            assert!(
                (achieved - bias).abs() < 1e-5 * (1.0 + bias.abs()),
                "t = {t}: {achieved} vs {bias}"
            );
        }
        let DrivenSliderCrank { w, k, .. } = DRIVEN;
        assert_near("θ̈", b[2], -k * w * w * (w * t).sin(), 1e-13);
    }
}

#[test]
#[ignore = "long: run in release"]
fn driven_crank_follows_its_drive_and_the_motor_does_the_work() {
    // No degree of freedom is left: the integration must follow the
    // prescribed motion, and the work of the driving row's multiplier (the
    // motor torque, `λ θ̇`) is the change of energy.
    let (qd, _) = differentiated(driven_motion, 0.0);
    let start = State {
        t: 0.0,
        q: driven_motion(0.0),
        v: qd,
    };
    let start = State {
        v: dalembert::constrained::project_onto_constraints(&DRIVEN, &start, 1e-14, 5)
            .unwrap()
            .v,
        ..start
    };
    let initial_energy = energy(&DRIVEN, &start.q, &start.v);
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let dynamics = Constrained::without_inputs(&DRIVEN, projection);
    let (mut worst, mut work, mut last_power) = (0.0f64, 0.0, None::<(f64, f64)>);
    let end = Integration::new(&dynamics, start, 2.0, Rk4 { steps: 20_000 })
        .observe(|s| {
            let exact = driven_motion(s.t);
            worst = (0..3).fold(worst, |m, i| m.max((s.q[i] - exact[i]).abs()));
            let (_, lambda) = constrained_accelerations(&DRIVEN, s.t, &s.q, &s.v, &[]).unwrap();
            let power = lambda[2] * s.v[0];
            if let Some((t, p)) = last_power {
                work += (s.t - t) * (p + power) / 2.0;
            }
            last_power = Some((s.t, power));
        })
        .run()
        .unwrap()
        .end;
    let change = energy(&DRIVEN, &end.q, &end.v) - initial_energy;
    println!(
        "driven crank, 2 s: max |q − q(t)| {worst:.2e}, ΔE {change:.6e}, motor work {work:.6e}"
    );
    assert!(worst < 1e-10, "{worst:e}");
    assert!(
        (change - work).abs() < 1e-6 * work.abs().max(1.0),
        "{change} vs {work}"
    );
}

dalembert::dalembert! {
    /// A bead on a hoop that a motor turns about the vertical at the
    /// prescribed rate `w`: the bead at `theta` from the bottom, the hoop at
    /// `phi`, held by the rheonomic row `phi == w t`.
    pub BeadOnHoop {
        parameters m, R, J, w, g;
        coordinates theta, phi;
        frame H = N.rotate_z(phi);
        particle bead { mass: m, at: O + R * sin(theta) * H.x - R * cos(theta) * N.z };
        body hoop { mass: m, center: O, frame: H, inertia: [J, J, 2*J] };
        gravity -g * N.z;
        constraint phi == w*t;
    }
}

#[test]
fn bead_on_a_driven_hoop_follows_the_closed_form_equation_and_torque() {
    let hoop = BeadOnHoop {
        m: 0.2,
        R: 0.5,
        J: 0.05,
        w: 6.0,
        g: 9.81,
    };
    let BeadOnHoop { m, R, w, g, .. } = hoop;
    // θ̈ = sin θ (w² cos θ − g/R); the motor's torque is the rate of the
    // angular momentum about the axis, 2 m R² w sin θ cos θ θ̇.
    let bead = |theta: f64| theta.sin() * (w * w * theta.cos() - g / R);
    for (t, theta, theta_dot) in [(0.0, 0.5, 0.0), (0.3, 1.1, -2.0), (2.0, 2.5, 3.0)] {
        let (q, v) = ([theta, w * t], [theta_dot, w]);
        assert_eq!(hoop.constraint_residual(t, &q), [0.0]);
        let (vdot, [torque]) = constrained_accelerations(&hoop, t, &q, &v, &[]).unwrap();
        assert_near("θ̈", vdot[0], bead(theta), 1e-13);
        assert_near("φ̈", vdot[1], 0.0, 1e-13);
        let expected = 2.0 * m * R * R * w * theta.sin() * theta.cos() * theta_dot;
        assert_near("motor torque", torque, expected, 1e-13);
    }
    let start = State {
        t: 0.0,
        q: [0.5, 0.0],
        v: [0.0, w],
    };
    let expected = scalar_motion(bead, 0.5, 0.0, 10.0);
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 5,
    };
    let mut drift = 0.0f64;
    let end = Integration::new(
        &Constrained::without_inputs(&hoop, projection),
        start,
        10.0,
        Rk4 { steps: 10_000 },
    )
    .observe(|s| {
        drift = drift.max(constraint_drift(&hoop, s));
    })
    .run()
    .unwrap()
    .end;
    println!(
        "bead on a hoop, 10 s: θ off by {:.2e}, max |φ| {drift:.2e}",
        end.q[0] - expected
    );
    assert_near("θ(10 s)", end.q[0], expected, 1e-9);
    assert_near("φ(10 s)", end.q[1], 10.0 * w, 1e-12);
}
