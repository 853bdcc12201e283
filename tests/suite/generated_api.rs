//! The generated API of docs/architecture.md §4 and the control outputs, checked
//! as an outside tester would: the derives and constants, `inverse_dynamics`
//! against `M v̇ − f`, `accelerations_jacobian` and `linearize` against
//! central finite differences of `dalembert::accelerations`, and the
//! regressor against `inverse_dynamics` with the inputs at zero.

use dalembert_fixtures::reference::assert_near;
use std::fmt::Debug;

dalembert::dalembert! {
    /// An arm carrying a slider on a second axis, with forces, a reacting
    /// torque, a potential and a dissipation function.
    pub Api {
        parameters m1, m2, l, k, c, g;
        coordinates a, b, s;
        inputs u1, u2;
        frame A = N.rotate_y(a);
        frame B = A.rotate_x(b);
        point P = O - l * A.z;
        point S = P + s * B.y;
        body arm { mass: m1, center: P, frame: A, inertia: [m1*l^2/12, m1*l^2/12, 0.01*m1, 0.002*m1, 0, -0.001*m1] };
        body slider { mass: m2, center: S, frame: B, inertia: [0.02*m2, 0.01*m2, 0.02*m2] };
        gravity -g * N.z;
        force u1 * B.y + s^-2 * A.x - c * dt(s) * N.x at S;
        torque (u2 - c * dt(b)) * A.x on B reacting A;
        potential k / 2 * s^2;
        dissipation c / 2 * dt(a)^2;
        outputs inverse_dynamics, accelerations_jacobian, linearize, regressor;
    }
}

const SYSTEM: Api = Api {
    m1: 1.3,
    m2: 0.7,
    l: 0.55,
    k: 2.9,
    c: 0.35,
    g: 9.8,
};
const T: f64 = 0.7;
const Q: [f64; 3] = [0.4, -0.9, 1.3];
const V: [f64; 3] = [1.2, -0.5, 0.8];
const U: [f64; 2] = [0.6, -1.4];
const STEP: f64 = 1e-6;

fn has_the_derives<S: Clone + Copy + Debug + PartialEq>(_: &S) {}

fn accelerations(q: &[f64; 3], v: &[f64; 3], u: &[f64; 2]) -> [f64; 3] {
    dalembert::accelerations(&SYSTEM, T, q, v, u).expect("a regular state")
}

/// Central difference of the accelerations along `d(h)`, a state moved by `h`.
fn central<F: Fn(f64) -> [f64; 3]>(moved: F) -> [f64; 3] {
    let (plus, minus) = (moved(STEP), moved(-STEP));
    [0, 1, 2].map(|i| (plus[i] - minus[i]) / (2.0 * STEP))
}

fn shifted<const N: usize>(x: &[f64; N], j: usize, h: f64) -> [f64; N] {
    let mut y = *x;
    y[j] += h;
    y
}

#[test]
fn constants_fields_and_derives_are_as_written() {
    assert_eq!((Api::NQ, Api::NV, Api::NU, Api::NC), (3, 3, 2, 0));
    assert_eq!(Api::COORDINATES, ["a", "b", "s"]);
    assert_eq!(Api::SPEEDS, ["dt(a)", "dt(b)", "dt(s)"]);
    assert_eq!(Api::PARAMETERS, ["m1", "m2", "l", "k", "c", "g"]);
    assert_eq!(Api::INPUTS, ["u1", "u2"]);
    let copy = SYSTEM;
    has_the_derives(&copy);
    assert_eq!(copy, SYSTEM);
    assert!(format!("{SYSTEM:?}").contains("l: 0.55"));
    assert_eq!(SYSTEM.coordinate_rates(&Q, &V), V);
}

#[test]
fn inverse_dynamics_is_mass_matrix_times_accelerations_minus_forcing() {
    let vdot = [0.3, -2.1, 1.7];
    let (mass, forcing) = (SYSTEM.mass_matrix(&Q), SYSTEM.forcing(T, &Q, &V, &U));
    let tau = SYSTEM.inverse_dynamics(T, &Q, &V, &vdot, &U);
    for i in 0..3 {
        let expected = (0..3).map(|j| mass[i][j] * vdot[j]).sum::<f64>() - forcing[i];
        assert_near(&format!("tau[{i}]"), tau[i], expected, 1e-12);
    }
    let zero = SYSTEM.inverse_dynamics(T, &Q, &V, &accelerations(&Q, &V, &U), &U);
    zero.iter()
        .for_each(|x| assert_near("tau at the accelerations", *x, 0.0, 1e-11));
}

#[test]
fn accelerations_jacobian_matches_central_differences() {
    let (dq, dv, du) = SYSTEM
        .accelerations_jacobian(T, &Q, &V, &U)
        .expect("regular");
    for j in 0..3 {
        let by_q = central(|h| accelerations(&shifted(&Q, j, h), &V, &U));
        let by_v = central(|h| accelerations(&Q, &shifted(&V, j, h), &U));
        for i in 0..3 {
            assert_near(&format!("dvdot{i}/dq{j}"), dq[i][j], by_q[i], 1e-7);
            assert_near(&format!("dvdot{i}/dv{j}"), dv[i][j], by_v[i], 1e-7);
        }
    }
    for j in 0..2 {
        let by_u = central(|h| accelerations(&Q, &V, &shifted(&U, j, h)));
        for (i, row) in du.iter().enumerate() {
            assert_near(&format!("dvdot{i}/du{j}"), row[j], by_u[i], 1e-7);
        }
    }
}

#[test]
fn linearize_is_the_first_order_state_equation() {
    let (a, b) = SYSTEM.linearize(T, &Q, &V, &U).expect("regular");
    for j in 0..3 {
        let by_q = central(|h| accelerations(&shifted(&Q, j, h), &V, &U));
        let by_v = central(|h| accelerations(&Q, &shifted(&V, j, h), &U));
        for i in 0..3 {
            assert_near(&format!("dq{i}/dq{j}"), a[i][j], 0.0, 1e-12);
            assert_near(
                &format!("dq{i}/dv{j}"),
                a[i][3 + j],
                f64::from(u8::from(i == j)),
                1e-12,
            );
            assert_near(&format!("dv{i}/dq{j}"), a[3 + i][j], by_q[i], 1e-7);
            assert_near(&format!("dv{i}/dv{j}"), a[3 + i][3 + j], by_v[i], 1e-7);
        }
    }
    for j in 0..2 {
        let by_u = central(|h| accelerations(&Q, &V, &shifted(&U, j, h)));
        let (rates, accelerations) = b.split_at(3);
        for (i, (rate, acceleration)) in rates.iter().zip(accelerations).enumerate() {
            assert_near(&format!("dq{i}/du{j}"), rate[j], 0.0, 1e-12);
            assert_near(&format!("dv{i}/du{j}"), acceleration[j], by_u[i], 1e-7);
        }
    }
}

#[test]
fn regressor_times_base_parameters_is_inverse_dynamics_without_inputs() {
    let vdot = [-0.8, 0.4, 2.2];
    let (y, pi) = (SYSTEM.regressor(&Q, &V, &vdot), SYSTEM.base_parameters());
    let tau = SYSTEM.inverse_dynamics(T, &Q, &V, &vdot, &[0.0, 0.0]);
    for i in 0..3 {
        let product = y[i].iter().zip(&pi).map(|(y, p)| y * p).sum::<f64>();
        assert_near(&format!("Y pi[{i}]"), product, tau[i], 1e-12);
    }
}
