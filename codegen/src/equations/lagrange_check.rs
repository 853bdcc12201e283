//! The d'Alembert route checked against the independent Lagrange route
//! ([`lagrange`](super::lagrange)) in the interpreter, at random states of
//! systems that exercise the whole language.

use crate::interpret::{Interpreter, Route, Sample};
use crate::seeds::{CONSTRAINED_PENDULUM, DOUBLE_PENDULUM, ROTATING_BAR};

/// Seed examples 1–3 as in the language reference, and systems that exercise the rest of
/// the language: 3-D rotations, products of inertia, particles, forces,
/// reacting torques, potentials, dissipation, constant tilts and joints.
const SYSTEMS: [&str; 11] = [
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
    // The seed's spelling of a spatial chain: frames and points relative to
    // the parent, joint torques as inputs (the recursive route).
    "pub SeedChain {
        parameters m1, m2, m3, L1, L2, L3, g, c;
        coordinates q1, q2, q3;
        inputs tau1, tau2, tau3;
        frame B1 = N.rotate_z(q1);
        point P1 = O + L1 * B1.x;
        body link1 { mass: m1, center: O + L1/2 * B1.x, frame: B1, inertia: [m1/50, m1*L1^2/12, m1*L1^2/12] };
        frame B2 = B1.rotate_y(q2);
        point P2 = P1 + L2 * B2.x;
        body link2 { mass: m2, center: P1 + L2/2 * B2.x, frame: B2, inertia: [m2/50, m2*L2^2/12, m2*L2^2/12] };
        frame B3 = B2.rotate_z(q3);
        body link3 { mass: m3, center: P2 + L3/2 * B3.x, frame: B3, inertia: [m3/50, m3*L3^2/12, m3*L3^2/12] };
        gravity -g * N.z;
        torque tau1 * N.z on B1;
        torque tau2 * B1.y on B2 reacting B1;
        torque tau3 * B2.z on B3 reacting B2;
        dissipation c * dt(q2)^2 / 2;
        potential c * q3^2 / 2;
    }",
    // A cart-pole: a slide, then a revolute joint on the cart.
    "pub CartPole {
        parameters m, M, l, g, c;
        coordinates s, theta;
        inputs F;
        point C = O + s * N.x;
        frame B = N.rotate_z(theta);
        body cart { mass: M, center: C, frame: N, inertia: [M, M, M] };
        body pole { mass: m, center: C - l * B.y, frame: B, inertia: [m*l^2/12, 0, m*l^2/12] };
        particle tip { mass: m/2, at: C - 2 * l * B.y };
        gravity -g * N.y;
        force F * N.x - c * dt(s) * N.x at C;
        force c * sin(theta) * B.x at C - l * B.y;
    }",
    // Constant axes and welded frames of both signs, a slide along a
    // rotated axis, loads in other links' frames.
    // Two joints through one point (a shoulder): the second hangs from
    // the first at the first's origin, and the third sits further out.
    "pub Shoulder {
        parameters m, L, g;
        coordinates q1, q2, q3;
        joint revolute J1 { parent: N, child: A, axis: z, coordinate: q1, at: O + L * N.z };
        joint revolute J2 { parent: A, child: B, axis: [0, 1, 1], coordinate: q2, at: J1 };
        joint revolute J3 { parent: B, child: C, axis: x, coordinate: q3, at: J2 + L * B.x };
        body upper { mass: m, center: J2 + L/2 * B.x, frame: B, inertia: [m/10, m*L^2/12, m*L^2/12] };
        body lower { mass: m/2, center: J3 + L/2 * C.y, frame: C, inertia: [m*L^2/24, m/20, m*L^2/24, m/50, 0, 0] };
        gravity -g * N.z;
    }",
    "pub Tilted {
        parameters m, a, b, g;
        coordinates q1, q2, q3;
        inputs u;
        joint revolute J1 { parent: N, child: A, axis: [1, 2, -2], coordinate: q1, at: O + a * N.z };
        frame T = A.rotate_x(-1.8);
        joint prismatic J2 { parent: T, child: S, axis: [0, 1, 1], coordinate: q2, at: J1 + a * A.x };
        frame U = S.rotate([a, 1, b], 0.7);
        joint revolute J3 { parent: U, child: C, axis: z, coordinate: q3, at: J2 - b * T.z };
        body hub { mass: m, center: J1 + b * T.y, frame: T, inertia: [m, 2 * m, 3 * m, m/10, m/20, -m/30] };
        body slider { mass: m/2, center: J2 + a * U.x, frame: U, inertia: [m/3, m/4, m/5] };
        body arm { mass: m/3, center: J3 + a * C.y, frame: C, inertia: [m/7, m/5, m/3, m/40, 0, m/50] };
        gravity -g * N.z + g/3 * N.x;
        torque u * T.y on C reacting S;
        torque u * N.x on A;
        force u * C.x + a * N.y at J3 + b * C.z;
    }",
];

/// The kinematic trees among [`SYSTEMS`].
const TREES: [&str; 8] = [
    "RotatingBar",
    "TiltedRail",
    "Chain",
    "Tree",
    "SeedChain",
    "CartPole",
    "Shoulder",
    "Tilted",
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

/// Both routes give the same `M` and `f`, and on every tree the
/// articulated-body recursion's `q̈` satisfies Lagrange's `M q̈ = f`.
#[test]
fn dalembert_agrees_with_lagrange_on_every_example_system() {
    let mut solved = Vec::new();
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
            let Some(qdd) = ours.articulated_accelerations(&at) else {
                continue;
            };
            let scale = largest(&f2) + largest(&m2.concat()) * largest(&qdd);
            for (k, row) in m2.iter().enumerate() {
                let mq: f64 = row.iter().zip(&qdd).map(|(mkj, a)| mkj * a).sum();
                assert_close(&format!("{name}: (M q̈)[{k}]"), mq, f2[k], scale);
            }
            if seed == 0 {
                solved.push(ours.name());
            }
        }
    }
    assert_eq!(solved, TREES);
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
        // No mass of these systems moves with time, so every one is
        // scleronomic: T = ½ q̇ᵀ M q̇ exactly.
        let t = ours.kinetic_energy(&at);
        assert_close(&format!("{}: 2T", ours.name()), quadratic, 2.0 * t, t.abs());
    }
}

#[test]
fn the_trees_among_them_take_the_recursive_route() {
    let trees: Vec<String> = SYSTEMS
        .iter()
        .filter_map(|source| {
            let system =
                crate::language::parse_system(source.parse().expect("tokens")).expect("parses");
            let (model, _) = crate::model::resolve(&system).unwrap_or_else(|e| panic!("{e}"));
            model.tree.is_some().then(|| model.name.to_string())
        })
        .collect();
    assert_eq!(trees, TREES);
}
