//! `linearize` of a constrained system: a sled with a rotor, linearised on its
//! blade against central differences of its flow in the independent
//! coordinates.

use dalembert_fixtures::differences::central_differences;
use dalembert_fixtures::reference::assert_close;

use crate::output_checks::*;

dalembert::dalembert! {
    /// A knife-edge sled (blade at the origin of `B`, center of mass `b`
    /// ahead) carrying a rotor on a torsion spring with a damper, pushed and
    /// turned by its inputs and its rotor driven by a motor reacting on it.
    pub RotorSled {
        parameters m, I, b, J, e, k, c;
        coordinates x, y, theta, phi;
        inputs push, turn, motor;
        frame B = N.rotate_z(theta);
        frame R = B.rotate_z(phi);
        point Blade = O + x * N.x + y * N.y;
        point G = Blade + b * B.x;
        point Rotor = Blade + e * B.y;
        body sled { mass: m, center: G, frame: B, inertia: [0, 0, I] };
        body rotor { mass: m / 4, center: Rotor, frame: R, inertia: [0, 0, J] };
        potential k / 2 * phi^2;
        dissipation c / 2 * dt(phi)^2;
        force push * B.x at G;
        torque turn * N.z on B;
        torque motor * N.z on R reacting B;
        constraint -sin(theta) * dt(x) + cos(theta) * dt(y) == 0;
        outputs accelerations_jacobian, linearize(x, y, theta, phi; dt(x), dt(theta), dt(phi));
    }
}

const ROTOR_SLED: RotorSled = RotorSled {
    m: 3.2,
    I: 0.4,
    b: 0.3,
    J: 0.05,
    e: 0.15,
    k: 2.5,
    c: 0.2,
};

/// The speed of `y` that keeps the blade from slipping sideways.
fn on_the_blade(q: &[f64; 4], v: &[f64; 4]) -> [f64; 4] {
    let (s, c) = q[2].sin_cos();
    [v[0], s / c * v[0], v[2], v[3]]
}

/// The sled's flow in the state `(q, (ẋ, θ̇, φ̇))` of its independent
/// coordinates and speeds: `(q̇, v̇)` with `ẏ` from the blade.
fn sled_flow(q: &[f64; 4], independent: &[f64; 3], u: &[f64; 3]) -> [f64; 8] {
    let v = on_the_blade(q, &[independent[0], 0.0, independent[1], independent[2]]);
    let vdot = dalembert::accelerations(&ROTOR_SLED, 0.0, q, &v, u).expect("a regular sled");
    std::array::from_fn(|i| if i < 4 { v[i] } else { vdot[i - 4] })
}

/// `linearize` of the sled is the derivative of its flow on the manifold:
/// columns of the coordinates, of the independent speeds and of the
/// inputs by central differences, the dependent speed's column zero.
#[test]
fn rotor_sled_linearises_on_the_blade() {
    for (q, independent, u) in [
        ([0.3, -0.2, 0.7, 0.4], [0.8, -0.6, 1.1], [0.5, -0.3, 0.2]),
        ([1.1, 0.4, -2.3, -0.9], [-1.2, 0.3, -0.4], [-0.7, 0.9, -1.3]),
    ] {
        let v = on_the_blade(&q, &[independent[0], 0.0, independent[1], independent[2]]);
        let (a, b) = ROTOR_SLED.linearize(0.0, &q, &v, &u).expect("on the blade");
        let by_q = central_differences(&q, STEP, |q| sled_flow(q, &independent, &u));
        let by_v = central_differences(&independent, STEP, |w| sled_flow(&q, w, &u));
        let by_u = central_differences(&u, STEP, |u| sled_flow(&q, &independent, u));
        for i in 0..8 {
            let what = format!("A row {i}");
            assert_close(&what, &a[i][..4], &by_q[i], DIFFERENCES);
            let speeds = [a[i][4], a[i][6], a[i][7]];
            assert_close(&what, &speeds, &by_v[i], DIFFERENCES);
            assert_eq!(a[i][5], 0.0, "{what}: the dependent speed's column");
            assert_close(&format!("B row {i}"), &b[i], &by_u[i], DIFFERENCES);
        }
    }
}
