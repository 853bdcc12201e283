//! A model computes the same whatever its names: each system here is
//! written twice, once with plain names and once with names spelled like
//! the generated code's own (the multipliers and weights `lambda{i}`, the
//! temporaries `x{i}`, the solve's `m{i}_{j}`, `l{i}_{j}`, `w{i}_{j}`,
//! `p{i}`, `r{i}`, `y{i}`, `f{i}`, the derivatives' `dq{i}_{j}`, `du{i}`,
//! `k{i}`, `b{i}`, `row{i}`, the configuration update's `q{i}`, `v{i}`,
//! `n{i}`, `k1_{i}`, the arguments `mu`, `qdd`, `order`, the locals
//! `accelerations`, `partials`, the Taylor route's const generic `K`), and
//! every output of DESIGN §4 and §7 (and the language's others) must agree
//! between the two at states no test chose. A parameter `lambda0` once
//! shadowed the adjoint's weight `lambda0`: it compiled and the adjoint
//! was wrong. The spatial chain of 12, whose `accelerations_jacobian` takes
//! its rows as adjoints in lanes, is written once more with coordinates
//! named like that function's fixed locals (`inverse`, `coefficients`,
//! `pass`, `jacobian`, `by_q`, `by_v`, `by_u`, `angles`, `finite`, the
//! rows `b{i}`, `equations_or`) and must agree with the generated crate's.

use dalembert::DynamicsError;

dalembert::dalembert! {
    /// A pendulum hanging from a cart on a spring and a damper, driven at
    /// the cart and the pivot, with plain names.
    pub Plain {
        parameters mc, mp, l, g, k, c, d, a1, a2;
        coordinates s, theta;
        inputs force, motor;
        frame B = N.rotate_z(theta);
        point C = O + s * N.x;
        point P = C - l * B.y;
        particle cart { mass: mc, at: C };
        body pole { mass: mp, center: P, frame: B, inertia: [0, 0, mp * l^2 / 12] };
        gravity -g * N.y;
        force force * N.x at C;
        torque motor * N.z on B;
        potential k * s^2 / 2 + a1 * cos(theta);
        dissipation c * dt(s)^2 / 2 + d * dt(theta)^2 / 2 + a2 * dt(s) * dt(theta);
        outputs inverse_dynamics, regressor, inverse_dynamics_jacobian, inverse_dynamics_adjoint;
        outputs accelerations_jacobian, linearize, taylor, accelerations_x4;
        outputs position(P), velocity(P in B), acceleration(P), jacobian(P);
        outputs rotation(B), angular_velocity(B), angular_jacobian(B in B);
    }
}

dalembert::dalembert! {
    /// The same system, its names those of the generated code's locals.
    pub Mimic {
        parameters lambda0, lambda1, mu, x0, K, m0_0, l1_0, order, accelerations;
        coordinates q0, v0;
        inputs lambda2, n0;
        frame B = N.rotate_z(v0);
        point C = O + q0 * N.x;
        point P = C - lambda1 * B.y;
        particle cart { mass: lambda0, at: C };
        body pole { mass: mu, center: P, frame: B, inertia: [0, 0, mu * lambda1^2 / 12] };
        gravity -x0 * N.y;
        force lambda2 * N.x at C;
        torque n0 * N.z on B;
        potential K * q0^2 / 2 + order * cos(v0);
        dissipation m0_0 * dt(q0)^2 / 2 + l1_0 * dt(v0)^2 / 2 + accelerations * dt(q0) * dt(v0);
        outputs inverse_dynamics, regressor, inverse_dynamics_jacobian, inverse_dynamics_adjoint;
        outputs accelerations_jacobian, linearize, taylor, accelerations_x4;
        outputs position(P), velocity(P in B), acceleration(P), jacobian(P);
        outputs rotation(B), angular_velocity(B), angular_jacobian(B in B);
    }
}

dalembert::dalembert! {
    /// Seed example 3 (a bar held at its end by two constraints), with
    /// plain names.
    pub PlainBar {
        parameters m, l, g;
        coordinates x, y, theta;
        inputs torque;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y;
        body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
        gravity -g * N.y;
        torque torque * N.z on B;
        constraint x - l/2 * sin(theta) == 0;
        constraint y + l/2 * cos(theta) == 0;
        outputs inverse_dynamics, accelerations_jacobian, linearize(theta), taylor;
    }
}

dalembert::dalembert! {
    /// The same bar, named like the multipliers and the locals of the
    /// constrained derivatives.
    pub MimicBar {
        parameters lambda0, lambda1, partials;
        coordinates accelerations, qdd, lambda_0;
        inputs mu;
        frame B = N.rotate_z(lambda_0);
        point G = O + accelerations * N.x + qdd * N.y;
        body bar { mass: lambda0, center: G, frame: B, inertia: [0, 0, lambda0*lambda1^2/12] };
        gravity -partials * N.y;
        torque mu * N.z on B;
        constraint accelerations - lambda1/2 * sin(lambda_0) == 0;
        constraint qdd + lambda1/2 * cos(lambda_0) == 0;
        outputs inverse_dynamics, accelerations_jacobian, linearize(lambda_0), taylor;
    }
}

dalembert::dalembert! {
    /// The spatial chain of 12 links (`generated/models/spatial_chain_12.dal`),
    /// its coordinates named like the locals of the jacobian's rows as
    /// adjoints.
    pub MimicChain12 {
        coordinates inverse, coefficients, pass, jacobian, by_q, by_v, by_u, angles, finite, b0, b11, equations_or;
        joint revolute J1 { parent: N, child: B1, axis: z, coordinate: inverse, at: O };
        body link1 { mass: 1.1, center: J1 + 0.55/2 * B1.x, frame: B1, inertia: [0, 1.1 * 0.55^2/12, 1.1 * 0.55^2/12] };
        joint revolute J2 { parent: B1, child: B2, axis: y, coordinate: coefficients, at: J1 + 0.55 * B1.x };
        body link2 { mass: 1.2, center: J2 + 0.60/2 * B2.x, frame: B2, inertia: [0, 1.2 * 0.60^2/12, 1.2 * 0.60^2/12] };
        joint revolute J3 { parent: B2, child: B3, axis: z, coordinate: pass, at: J2 + 0.60 * B2.x };
        body link3 { mass: 1.3, center: J3 + 0.65/2 * B3.x, frame: B3, inertia: [0, 1.3 * 0.65^2/12, 1.3 * 0.65^2/12] };
        joint revolute J4 { parent: B3, child: B4, axis: y, coordinate: jacobian, at: J3 + 0.65 * B3.x };
        body link4 { mass: 1.4, center: J4 + 0.70/2 * B4.x, frame: B4, inertia: [0, 1.4 * 0.70^2/12, 1.4 * 0.70^2/12] };
        joint revolute J5 { parent: B4, child: B5, axis: z, coordinate: by_q, at: J4 + 0.70 * B4.x };
        body link5 { mass: 1.5, center: J5 + 0.75/2 * B5.x, frame: B5, inertia: [0, 1.5 * 0.75^2/12, 1.5 * 0.75^2/12] };
        joint revolute J6 { parent: B5, child: B6, axis: y, coordinate: by_v, at: J5 + 0.75 * B5.x };
        body link6 { mass: 1.6, center: J6 + 0.80/2 * B6.x, frame: B6, inertia: [0, 1.6 * 0.80^2/12, 1.6 * 0.80^2/12] };
        joint revolute J7 { parent: B6, child: B7, axis: z, coordinate: by_u, at: J6 + 0.80 * B6.x };
        body link7 { mass: 1.7, center: J7 + 0.85/2 * B7.x, frame: B7, inertia: [0, 1.7 * 0.85^2/12, 1.7 * 0.85^2/12] };
        joint revolute J8 { parent: B7, child: B8, axis: y, coordinate: angles, at: J7 + 0.85 * B7.x };
        body link8 { mass: 1.8, center: J8 + 0.90/2 * B8.x, frame: B8, inertia: [0, 1.8 * 0.90^2/12, 1.8 * 0.90^2/12] };
        joint revolute J9 { parent: B8, child: B9, axis: z, coordinate: finite, at: J8 + 0.90 * B8.x };
        body link9 { mass: 1.9, center: J9 + 0.95/2 * B9.x, frame: B9, inertia: [0, 1.9 * 0.95^2/12, 1.9 * 0.95^2/12] };
        joint revolute J10 { parent: B9, child: B10, axis: y, coordinate: b0, at: J9 + 0.95 * B9.x };
        body link10 { mass: 2.0, center: J10 + 1.00/2 * B10.x, frame: B10, inertia: [0, 2.0 * 1.00^2/12, 2.0 * 1.00^2/12] };
        joint revolute J11 { parent: B10, child: B11, axis: z, coordinate: b11, at: J10 + 1.00 * B10.x };
        body link11 { mass: 2.1, center: J11 + 1.05/2 * B11.x, frame: B11, inertia: [0, 2.1 * 1.05^2/12, 2.1 * 1.05^2/12] };
        joint revolute J12 { parent: B11, child: B12, axis: y, coordinate: equations_or, at: J11 + 1.05 * B11.x };
        body link12 { mass: 2.2, center: J12 + 1.10/2 * B12.x, frame: B12, inertia: [0, 2.2 * 1.10^2/12, 2.2 * 1.10^2/12] };
        gravity -9.81 * N.z;
        outputs accelerations_jacobian;
    }
}

const PARAMETERS: [f64; 9] = [1.3, 0.7, 0.9, 9.81, 4.0, 0.3, 0.05, 0.4, 0.02];

fn plain() -> Plain {
    let [mc, mp, l, g, k, c, d, a1, a2] = PARAMETERS;
    Plain {
        mc,
        mp,
        l,
        g,
        k,
        c,
        d,
        a1,
        a2,
    }
}

#[allow(non_snake_case)]
fn mimic() -> Mimic {
    let [
        lambda0,
        mu,
        lambda1,
        x0,
        K,
        m0_0,
        l1_0,
        order,
        accelerations,
    ] = PARAMETERS;
    Mimic {
        lambda0,
        lambda1,
        mu,
        x0,
        K,
        m0_0,
        l1_0,
        order,
        accelerations,
    }
}

/// A state of the two systems: `(t, q, v, vdot, u, weights)`.
type Sample = (f64, [f64; 2], [f64; 2], [f64; 2], [f64; 2], [f64; 2]);

/// States no other test uses.
fn states() -> Vec<Sample> {
    vec![
        (
            0.0,
            [0.31, -2.2],
            [1.7, -0.4],
            [0.2, 3.1],
            [0.6, -1.9],
            [0.8, -1.3],
        ),
        (
            1.5,
            [-1.1, 0.45],
            [-0.3, 2.6],
            [-1.4, 0.7],
            [-2.5, 0.35],
            [-0.2, 2.1],
        ),
        (
            3.0,
            [2.4, 3.0],
            [0.05, -1.1],
            [0.9, -0.6],
            [1.2, 0.8],
            [1.5, 0.4],
        ),
    ]
}

/// Whether `a` and `b` agree entry by entry to 1e-12 of their size.
fn assert_same(what: &str, a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len(), "{what}");
    assert!(!a.is_empty(), "{what}");
    let scale = a.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (x, y) in a.iter().zip(b) {
        assert!(
            (x - y).abs() <= 1e-12 * scale,
            "{what}: {a:?} against {b:?}"
        );
    }
}

fn flat<const R: usize, const C: usize>(m: [[f64; C]; R]) -> Vec<f64> {
    m.iter().flatten().copied().collect()
}

fn ok<T>(result: Result<T, DynamicsError>) -> T {
    result.expect("a regular state")
}

#[test]
fn every_output_is_the_same_under_the_generated_code_s_names() {
    let (a, b) = (plain(), mimic());
    assert_eq!(Mimic::PARAMETERS[0], "lambda0");
    let states = states();
    assert!(!states.is_empty());
    for (t, q, v, vdot, u, weights) in states {
        assert_same("M", &flat(a.mass_matrix(&q)), &flat(b.mass_matrix(&q)));
        assert_same("f", &a.forcing(t, &q, &v, &u), &b.forcing(t, &q, &v, &u));
        let energies = |x: [f64; 2]| x.to_vec();
        assert_same(
            "energies",
            &energies([a.kinetic_energy(&q, &v), a.potential_energy(&q)]),
            &energies([b.kinetic_energy(&q, &v), b.potential_energy(&q)]),
        );
        assert_same(
            "inverse dynamics",
            &a.inverse_dynamics(t, &q, &v, &vdot, &u),
            &b.inverse_dynamics(t, &q, &v, &vdot, &u),
        );
        assert_same(
            "regressor times base parameters",
            &mat_vec(&a.regressor(&q, &v, &vdot), &a.base_parameters()),
            &mat_vec(&b.regressor(&q, &v, &vdot), &b.base_parameters()),
        );
        let (aq, av, am) = a.inverse_dynamics_jacobian(t, &q, &v, &vdot, &u);
        let (bq, bv, bm) = b.inverse_dynamics_jacobian(t, &q, &v, &vdot, &u);
        assert_same("dtau/dq", &flat(aq), &flat(bq));
        assert_same("dtau/dv", &flat(av), &flat(bv));
        assert_same("dtau/dvdot", &flat(am), &flat(bm));
        let (aq, av, au) = a.inverse_dynamics_adjoint(t, &q, &v, &vdot, &u, &weights);
        let (bq, bv, bu) = b.inverse_dynamics_adjoint(t, &q, &v, &vdot, &u, &weights);
        assert_same("adjoint by q", &aq, &bq);
        assert_same("adjoint by v", &av, &bv);
        assert_same("adjoint by u", &au, &bu);
        // And the adjoint is the weights times the jacobian.
        let (by_q, ..) = a.inverse_dynamics_jacobian(t, &q, &v, &vdot, &u);
        let weighted: Vec<f64> = (0..2)
            .map(|j| (0..2).map(|i| weights[i] * by_q[i][j]).sum())
            .collect();
        assert_same("adjoint against the jacobian", &bq, &weighted);
        let (aq, av, au) = ok(a.accelerations_jacobian(t, &q, &v, &u));
        let (bq, bv, bu) = ok(b.accelerations_jacobian(t, &q, &v, &u));
        assert_same("dvdot/dq", &flat(aq), &flat(bq));
        assert_same("dvdot/dv", &flat(av), &flat(bv));
        assert_same("dvdot/du", &flat(au), &flat(bu));
        let (aa, ab) = ok(a.linearize(t, &q, &v, &u));
        let (ba, bb) = ok(b.linearize(t, &q, &v, &u));
        assert_same("A", &flat(aa), &flat(ba));
        assert_same("B", &flat(ab), &flat(bb));
        let (aq, av) = ok(a.taylor_coefficients::<5>(t, &q, &v, &u, 4));
        let (bq, bv) = ok(b.taylor_coefficients::<5>(t, &q, &v, &u, 4));
        assert_same("Taylor q", &flat(aq), &flat(bq));
        assert_same("Taylor v", &flat(av), &flat(bv));
        let lanes = |s: &[f64; 2]| [*s; 4];
        let ax4 = a.accelerations_x4([t; 4], &lanes(&q), &lanes(&v), &lanes(&u));
        let bx4 = b.accelerations_x4([t; 4], &lanes(&q), &lanes(&v), &lanes(&u));
        for (x, y) in ax4.into_iter().zip(bx4) {
            assert_same("accelerations x4", &ok(x), &ok(y));
        }
        assert_same("position", &a.position_P(t, &q), &b.position_P(t, &q));
        assert_same(
            "velocity in B",
            &a.velocity_P_in_B(t, &q, &v),
            &b.velocity_P_in_B(t, &q, &v),
        );
        assert_same(
            "acceleration",
            &a.acceleration_P(t, &q, &v, &vdot),
            &b.acceleration_P(t, &q, &v, &vdot),
        );
        assert_same(
            "jacobian",
            &flat(a.jacobian_P(t, &q)),
            &flat(b.jacobian_P(t, &q)),
        );
        assert_same(
            "rotation",
            &flat(a.rotation_B(t, &q)),
            &flat(b.rotation_B(t, &q)),
        );
        assert_same(
            "angular velocity",
            &a.angular_velocity_B(t, &q, &v),
            &b.angular_velocity_B(t, &q, &v),
        );
        assert_same(
            "angular jacobian",
            &flat(a.angular_jacobian_B_in_B(t, &q)),
            &flat(b.angular_jacobian_B_in_B(t, &q)),
        );
    }
}

fn mat_vec<const R: usize, const C: usize>(m: &[[f64; C]; R], x: &[f64; C]) -> Vec<f64> {
    m.iter()
        .map(|row| row.iter().zip(x).map(|(a, b)| a * b).sum())
        .collect()
}

#[test]
fn a_constrained_system_is_the_same_under_the_multipliers_names() {
    let a = PlainBar {
        m: 1.2,
        l: 0.8,
        g: 9.81,
    };
    let b = MimicBar {
        lambda0: 1.2,
        lambda1: 0.8,
        partials: 9.81,
    };
    let states: [(f64, f64, f64, f64); 2] = [(0.3, 1.1, -0.7, 0.9), (2.0, -0.4, 2.3, -1.6)];
    for (t, angle, rate, torque) in states {
        // On the constraint manifold: the bar's centre half a length from O.
        let q = [0.4 * angle.sin(), -0.4 * angle.cos(), angle];
        let v = [0.4 * angle.cos() * rate, 0.4 * angle.sin() * rate, rate];
        let u = [torque];
        assert_same(
            "residual",
            &a.constraint_residual(t, &q),
            &b.constraint_residual(t, &q),
        );
        assert_same(
            "accelerations",
            &ok(dalembert::accelerations(&a, t, &q, &v, &u)),
            &ok(dalembert::accelerations(&b, t, &q, &v, &u)),
        );
        let (aq, av, au) = ok(a.accelerations_jacobian(t, &q, &v, &u));
        let (bq, bv, bu) = ok(b.accelerations_jacobian(t, &q, &v, &u));
        assert_same("dvdot/dq", &flat(aq), &flat(bq));
        assert_same("dvdot/dv", &flat(av), &flat(bv));
        assert_same("dvdot/du", &flat(au), &flat(bu));
        let (aa, ab) = ok(a.linearize(t, &q, &v, &u));
        let (ba, bb) = ok(b.linearize(t, &q, &v, &u));
        assert_same("A", &flat(aa), &flat(ba));
        assert_same("B", &flat(ab), &flat(bb));
        let (aq, av) = ok(a.taylor_coefficients::<4>(t, &q, &v, &u, 3));
        let (bq, bv) = ok(b.taylor_coefficients::<4>(t, &q, &v, &u, 3));
        assert_same("Taylor q", &flat(aq), &flat(bq));
        assert_same("Taylor v", &flat(av), &flat(bv));
        let vdot = ok(dalembert::accelerations(&a, t, &q, &v, &u));
        assert_same(
            "inverse dynamics",
            &a.inverse_dynamics(t, &q, &v, &vdot, &u),
            &b.inverse_dynamics(t, &q, &v, &vdot, &u),
        );
    }
}

#[test]
fn the_jacobian_rows_as_adjoints_are_the_same_under_their_locals_names() {
    use dalembert_generated::derivatives::spatial_chain_12::SpatialChain12;
    // The route this test is about: rows as adjoints, four in SIMD lanes.
    let code = dalembert_codegen::generate(MimicChain12::SOURCE).expect("the model");
    assert!(code.contains("weight_lanes"), "not the adjoint rows' route");
    let (a, b) = (SpatialChain12 {}, MimicChain12 {});
    let states: [(f64, f64); 3] = [(0.3, 1.7), (-1.2, -0.4), (2.6, 0.9)];
    for (angle, rate) in states {
        let q: [f64; 12] = std::array::from_fn(|i| angle * (1.0 + 0.13 * i as f64).sin());
        let v: [f64; 12] = std::array::from_fn(|i| rate * (0.7 * i as f64).cos());
        let (aq, av, _) = ok(a.accelerations_jacobian(0.0, &q, &v, &[]));
        let (bq, bv, _) = ok(b.accelerations_jacobian(0.0, &q, &v, &[]));
        assert_same("dvdot/dq", &flat(aq), &flat(bq));
        assert_same("dvdot/dv", &flat(av), &flat(bv));
    }
}
