//! The d'Alembert route checked against the independent Lagrange route
//! ([`lagrange`](super::lagrange)) in the interpreter, at random states of
//! systems that exercise the whole language.

use crate::interpret::{Interpreter, Route, Sample};
use crate::seeds::{CONSTRAINED_PENDULUM, DOUBLE_PENDULUM, ROTATING_BAR};

/// Seed examples 1–3 as in DESIGN §3, and systems that exercise the rest of
/// the language: 3-D rotations, products of inertia, particles, forces,
/// reacting torques, potentials, dissipation, constant tilts and joints.
const SYSTEMS: [&str; 7] = [
    DOUBLE_PENDULUM,
    ROTATING_BAR,
    CONSTRAINED_PENDULUM,
    "pub Gyro {
        parameters m, a, b, c, g, k, r;
        coordinates psi, th, ph;
        inputs Tq, Fx;
        frame A = N.rotate_z(psi);
        frame B = A.rotate_x(th);
        frame C = B.rotate_y(ph);
        point G = O + a * B.z + r * C.x;
        body rotor { mass: m, center: G, frame: C, inertia: [a*m, b*m, c*m, m*a*b/10, -m*c/7, m/5] };
        particle tip { mass: m/3, at: G + b * C.z - r * B.y };
        gravity -g * N.z;
        force Fx * N.x + k * dt(th) * A.y at G;
        torque Tq * B.y on C reacting A;
        potential k * th^2 / 2 + k * sin(ph)^2;
        dissipation c * dt(psi)^2 / 2 + r * dt(ph) * dt(th);
    }",
    "pub TiltedRail {
        parameters m, l, w, g;
        coordinates s, theta;
        frame R = N.rotate_z(w);
        point C = O + s * R.x + sin(w) * N.y;
        frame B = R.rotate_z(theta);
        body cart { mass: 2 * m, center: C, frame: R, inertia: [0, 0, m] };
        body arm { mass: m, center: C - l * B.y, frame: B, inertia: [m*l^2, 0, m*l^2/3] };
        gravity -g * N.y + g/10 * N.x;
    }",
    "pub Chain {
        parameters m1, m2, L1, L2, g;
        coordinates q1, q2, q3;
        joint revolute J1 { parent: N, child: L1f, axis: z, coordinate: q1, at: O };
        joint revolute J2 { parent: L1f, child: L2f, axis: y, coordinate: q2, at: J1 + L1 * L1f.x };
        joint prismatic J3 { parent: L2f, child: S, axis: x, coordinate: q3, at: J2 };
        body link1 { mass: m1, center: J1 + L1/2 * L1f.x, frame: L1f, inertia: [0, m1*L1^2/12, m1*L1^2/12] };
        body link2 { mass: m2, center: J2 + L2/2 * L2f.x, frame: L2f, inertia: [m2/100, m2*L2^2/12, m2*L2^2/12] };
        particle slider { mass: m2/2, at: J3 };
        gravity -g * N.z;
    }",
    // A branching tree of revolute joints only: the recursive shortcut.
    "pub Tree {
        parameters m, a, b, g;
        coordinates q1, q2, q3, q4;
        inputs u;
        joint revolute J1 { parent: N, child: A, axis: z, coordinate: q1, at: O + a * N.y };
        joint revolute J2 { parent: A, child: B, axis: x, coordinate: q2, at: J1 + a * A.x - b * A.z };
        joint revolute J3 { parent: A, child: C, axis: y, coordinate: q3, at: J1 - b * A.y };
        joint revolute J4 { parent: C, child: D, axis: z, coordinate: q4, at: J3 + a * C.x + b * C.y };
        body hub { mass: 2 * m, center: J1 + b * A.x, frame: A, inertia: [m, 2 * m, 3 * m, m/10, m/20, -m/30] };
        body arm { mass: m, center: J2 + a/2 * B.y + b * B.z, frame: B, inertia: [m*a^2/12, m*b, m*a^2/12] };
        body leg { mass: m/2, center: J3 - b/2 * C.z, frame: C, inertia: [m*b^2/12, m*b^2/12, 0] };
        body foot { mass: m/3, center: J4, frame: D, inertia: [m/7, m/5, m/3] };
        particle toe { mass: m/4, at: J4 + a * D.x - b * D.z };
        gravity -g * N.z + g/3 * N.x;
        torque u * C.y on C reacting A;
        force u * N.y at J2;
    }",
];

fn interpreter(source: &str, route: Route) -> Interpreter {
    Interpreter::new(source, route).unwrap_or_else(|e| panic!("{e}"))
}

fn assert_close(what: &str, a: f64, b: f64, scale: f64) {
    assert!(
        (a - b).abs() <= 1e-10 * scale.max(1.0),
        "{what}: d'Alembert {a:e} vs Lagrange {b:e}"
    );
}

/// The largest magnitude in `values`.
fn largest(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, v| m.max(v.abs()))
}

#[test]
fn dalembert_agrees_with_lagrange_on_every_example_system() {
    for source in SYSTEMS {
        let ours = interpreter(source, Route::Dalembert);
        let theirs = interpreter(source, Route::Lagrange);
        for seed in 0..5 {
            let state = Sample::random(&ours, seed);
            let at = state.values();
            let name = format!("{} at state {seed}", ours.name());
            let (m1, m2) = (ours.mass_matrix(&at), theirs.mass_matrix(&at));
            let (f1, f2) = (ours.forcing(&at), theirs.forcing(&at));
            let scale_m = largest(&m1.concat());
            for (k, (row1, row2)) in m1.iter().zip(&m2).enumerate() {
                for (j, (a, b)) in row1.iter().zip(row2).enumerate() {
                    assert_close(&format!("{name}: M[{k}][{j}]"), *a, *b, scale_m);
                }
            }
            for (k, (a, b)) in f1.iter().zip(&f2).enumerate() {
                assert_close(&format!("{name}: f[{k}]"), *a, *b, largest(&f2));
            }
        }
    }
}

#[test]
fn the_mass_matrix_is_symmetric_and_its_quadratic_form_is_twice_t() {
    for source in SYSTEMS {
        let ours = interpreter(source, Route::Dalembert);
        let state = Sample::random(&ours, 42);
        let at = state.values();
        let m = ours.mass_matrix(&at);
        let mut quadratic = 0.0;
        for (k, row) in m.iter().enumerate() {
            for (j, &mkj) in row.iter().enumerate() {
                assert_eq!(mkj, m[j][k]);
                quadratic += state.qd[k] * mkj * state.qd[j];
            }
        }
        // No mass moves with time (the checker rejects it), so every
        // system is scleronomic: T = ½ q̇ᵀ M q̇ exactly.
        let t = ours.kinetic_energy(&at);
        assert_close(&format!("{}: 2T", ours.name()), quadratic, 2.0 * t, t.abs());
    }
}
