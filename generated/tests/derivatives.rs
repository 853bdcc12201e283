//! The exact derivatives (`accelerations_jacobian`, `linearize`,
//! `inverse_dynamics_jacobian`) of the models of `dalembert_generated::derivatives`
//! and the cart-pole: against central differences of the emitted
//! `accelerations`, `mass_matrix` and `forcing` at random states; the
//! chains' and robots' against Pinocchio's `computeABADerivatives` and
//! `computeRNEADerivatives` (`tests/reference/derivatives.json`, written by
//! `scripts/derivatives_reference.py`); and the linearisation of seed
//! example 1 at its hanging equilibrium against the closed form of its two
//! normal modes.

use dalembert::MultibodySystem;
use dalembert_codegen::testing::Random;
use dalembert_generated::CartPole;
use dalembert_generated::derivatives::*;
use nalgebra::SMatrix;
use serde_json::Value;

/// Relative agreement required of the central differences.
const TOLERANCE: f64 = 1e-6;

/// Step of the central differences (their error is `O(h²)`, the rounding
/// `O(ε/h)`).
const STEP: f64 = 1e-5;

/// A random state: coordinates in `[−π, π)`, speeds and inputs in `[−2, 2)`.
struct State<const N: usize, const NU: usize> {
    t: f64,
    q: [f64; N],
    v: [f64; N],
    u: [f64; NU],
}

impl<const N: usize, const NU: usize> State<N, NU> {
    fn random(random: &mut Random) -> Self {
        let pi = std::f64::consts::PI;
        State {
            t: random.uniform(0.0, 3.0),
            q: std::array::from_fn(|_| random.uniform(-pi, pi)),
            v: std::array::from_fn(|_| random.uniform(-2.0, 2.0)),
            u: std::array::from_fn(|_| random.uniform(-2.0, 2.0)),
        }
    }
}

/// `(g(x + h eⱼ) − g(x − h eⱼ)) / 2h` for every `j`: column `j` of `∂g/∂x`.
fn central_differences<const N: usize, const M: usize>(
    x: &[f64; M],
    g: impl Fn(&[f64; M]) -> [f64; N],
) -> [[f64; M]; N] {
    let mut jacobian = [[0.0; M]; N];
    for j in 0..M {
        let (mut plus, mut minus) = (*x, *x);
        plus[j] += STEP;
        minus[j] -= STEP;
        let (high, low) = (g(&plus), g(&minus));
        for i in 0..N {
            jacobian[i][j] = (high[i] - low[i]) / (2.0 * STEP);
        }
    }
    jacobian
}

/// `max |exact − numeric| ≤ TOLERANCE · (1 + max |numeric|)`, entry by entry.
fn assert_matches<const N: usize, const M: usize>(
    what: &str,
    exact: &[[f64; M]; N],
    numeric: &[[f64; M]; N],
) {
    let scale = 1.0
        + numeric
            .iter()
            .flatten()
            .fold(0.0_f64, |m, x| m.max(x.abs()));
    for i in 0..N {
        for j in 0..M {
            let error = (exact[i][j] - numeric[i][j]).abs();
            assert!(
                error <= TOLERANCE * scale,
                "{what}[{i}][{j}]: exact {}, central differences {} (scale {scale})",
                exact[i][j],
                numeric[i][j]
            );
        }
    }
}

/// `accelerations_jacobian(t, q, v, u)` of a system.
type AccelerationsJacobian<S, const N: usize, const NU: usize> =
    fn(
        &S,
        f64,
        &[f64; N],
        &[f64; N],
        &[f64; NU],
    ) -> Result<([[f64; N]; N], [[f64; N]; N], [[f64; NU]; N]), dalembert::DynamicsError>;

/// `inverse_dynamics_jacobian(t, q, v, v̇, u)` of a system.
type InverseDynamicsJacobian<S, const N: usize, const NU: usize> =
    fn(
        &S,
        f64,
        &[f64; N],
        &[f64; N],
        &[f64; N],
        &[f64; NU],
    ) -> ([[f64; N]; N], [[f64; N]; N], [[f64; N]; N]);

/// Both Jacobians of `system` against central differences of its
/// accelerations and of `M v̇ − f`, at `states` random states.
fn check<S: MultibodySystem<N, N, NU>, const N: usize, const NU: usize>(
    system: &S,
    accelerations_jacobian: AccelerationsJacobian<S, N, NU>,
    inverse_dynamics_jacobian: InverseDynamicsJacobian<S, N, NU>,
    seed: u64,
) {
    let mut random = Random::new(seed);
    for _ in 0..5 {
        let State { t, q, v, u } = State::<N, NU>::random(&mut random);
        let vdot = dalembert::accelerations(system, t, &q, &v, &u).expect("solvable");
        let accelerations = |q: &[f64; N], v: &[f64; N], u: &[f64; NU]| {
            dalembert::accelerations(system, t, q, v, u).expect("solvable")
        };
        let (by_q, by_v, by_u) = accelerations_jacobian(system, t, &q, &v, &u).expect("solvable");
        assert_matches(
            "∂v̇/∂q",
            &by_q,
            &central_differences(&q, |q| accelerations(q, &v, &u)),
        );
        assert_matches(
            "∂v̇/∂v",
            &by_v,
            &central_differences(&v, |v| accelerations(&q, v, &u)),
        );
        assert_matches(
            "∂v̇/∂u",
            &by_u,
            &central_differences(&u, |u| accelerations(&q, &v, u)),
        );
        // τ = M v̇ − f at an arbitrary v̇, not only the solved one.
        let a: [f64; N] = std::array::from_fn(|i| vdot[i] + random.uniform(-1.0, 1.0));
        let tau = |q: &[f64; N], v: &[f64; N]| -> [f64; N] {
            let (m, f) = (system.mass_matrix(q), system.forcing(t, q, v, &u));
            std::array::from_fn(|i| (0..N).map(|j| m[i][j] * a[j]).sum::<f64>() - f[i])
        };
        let (tau_q, tau_v, mass) = inverse_dynamics_jacobian(system, t, &q, &v, &a, &u);
        assert_matches("∂τ/∂q", &tau_q, &central_differences(&q, |q| tau(q, &v)));
        assert_matches("∂τ/∂v", &tau_v, &central_differences(&v, |v| tau(&q, v)));
        assert_eq!(mass, system.mass_matrix(&q), "∂τ/∂v̇ = M");
    }
}

/// Checks every listed system (by its module in `derivatives`).
macro_rules! check {
    ($seed:expr; $($module:ident :: $system:ident $fields:tt),* $(,)?) => {$(
        check(
            &$module::$system $fields,
            $module::$system::accelerations_jacobian,
            $module::$system::inverse_dynamics_jacobian,
            $seed,
        );
    )*};
}

#[test]
fn seed_examples_match_central_differences() {
    check!(1;
        double_pendulum::DoublePendulum { m: 1.3, L: 0.7, g: 9.81 },
        rotating_bar::RotatingBar { m: 1.1, l: 0.9, d: 0.4 },
    );
}

#[test]
fn chains_match_central_differences() {
    check!(2;
        planar_chain_02::PlanarChain2 {},
        planar_chain_06::PlanarChain6 {},
        planar_chain_12::PlanarChain12 {},
        spatial_chain_02::SpatialChain2 {},
        spatial_chain_06::SpatialChain6 {},
        spatial_chain_12::SpatialChain12 {},
    );
}

#[test]
fn robots_match_central_differences() {
    check!(3; panda::Panda {}, ur5_robot::Ur5 {});
}

#[test]
fn cart_pole_matches_central_differences() {
    let cart_pole = CartPole {
        m_c: 1.0,
        m_p: 0.3,
        l: 0.5,
        g: 9.81,
    };
    check(
        &cart_pole,
        CartPole::accelerations_jacobian,
        CartPole::inverse_dynamics_jacobian,
        4,
    );
}

#[test]
fn linearize_assembles_the_accelerations_jacobian() {
    let cart_pole = CartPole {
        m_c: 1.0,
        m_p: 0.3,
        l: 0.5,
        g: 9.81,
    };
    let (q, v, u) = ([0.2, -0.4], [0.5, 1.5], [0.7]);
    let (by_q, by_v, by_u) = cart_pole
        .accelerations_jacobian(0.0, &q, &v, &u)
        .expect("solvable");
    let (a, b) = cart_pole.linearize(0.0, &q, &v, &u).expect("solvable");
    assert_eq!(a[0], [0.0, 0.0, 1.0, 0.0]);
    assert_eq!(a[1], [0.0, 0.0, 0.0, 1.0]);
    for i in 0..2 {
        assert_eq!(a[2 + i], [by_q[i][0], by_q[i][1], by_v[i][0], by_v[i][1]]);
        assert_eq!(b[i], [0.0]);
        assert_eq!(b[2 + i], by_u[i]);
    }
}

/// Seed example 1 hanging at rest: `M₀ θ̈ + K θ = 0` with (from `T` and `V`
/// of two uniform rods) `M₀ = m L² [[4/3, 1/2], [1/2, 1/3]]` and
/// `K = m g L diag(3/2, 1/2)`, so `det(K − ω² M₀) = 0` reads
/// `7 s² − 42 s + 27 = 0` for `s = ω² L/g`: `ω² = (g/L)(3 ∓ 6/√7)`. The
/// eigenvalues of `A` are `±iω₁`, `±iω₂`.
#[test]
fn double_pendulum_hanging_has_the_closed_form_normal_modes() {
    let (m, length, g) = (1.3, 0.7, 9.81);
    let system = double_pendulum::DoublePendulum { m, L: length, g };
    let (a, b) = system
        .linearize(0.0, &[0.0; 2], &[0.0; 2], &[])
        .expect("solvable");
    assert_eq!(b, [[0.0; 0]; 4]);
    let a = SMatrix::<f64, 4, 4>::from_fn(|i, j| a[i][j]);
    let mut eigenvalues: Vec<(f64, f64)> = a
        .complex_eigenvalues()
        .iter()
        .map(|z| (z.re, z.im))
        .collect();
    eigenvalues.sort_by(|x, y| x.1.total_cmp(&y.1));
    let root = 6.0 / 7.0_f64.sqrt();
    let (slow, fast) = (
        (g / length * (3.0 - root)).sqrt(),
        (g / length * (3.0 + root)).sqrt(),
    );
    let expected = [-fast, -slow, slow, fast];
    for ((re, im), want) in eigenvalues.iter().zip(expected) {
        assert!(re.abs() < 1e-12 * fast, "real part {re}");
        assert!(
            (im - want).abs() < 1e-12 * fast,
            "ω {im}, closed form {want}"
        );
    }
}

/// Relative agreement required with Pinocchio, against the largest entry.
const PINOCCHIO_TOLERANCE: f64 = 1e-9;

/// The entries of a JSON number or nested array of numbers, in order.
fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        other => vec![other.as_f64().expect("a number")],
    }
}

/// `max |got − want| ≤ PINOCCHIO_TOLERANCE · max |want|`.
fn assert_agrees(what: &str, got: &[f64], want: &Value) {
    let want = numbers(want);
    assert_eq!(got.len(), want.len(), "{what}: length");
    let scale = want.iter().fold(f64::MIN_POSITIVE, |m, w| m.max(w.abs()));
    let error = got
        .iter()
        .zip(&want)
        .fold(0.0_f64, |m, (g, w)| m.max((g - w).abs()));
    assert!(
        error <= PINOCCHIO_TOLERANCE * scale,
        "{what}: off by {:e} relative",
        error / scale
    );
}

/// The reference states of `model` in `derivatives.json`.
fn reference_states(model: &str) -> Vec<Value> {
    let text = include_str!("../../tests/reference/derivatives.json");
    let document: Value = serde_json::from_str(text).expect("derivatives.json parses");
    let entry = document["models"]
        .as_array()
        .expect("models")
        .iter()
        .find(|m| m["model"] == model)
        .unwrap_or_else(|| panic!("{model} in derivatives.json"));
    entry["states"].as_array().expect("states").clone()
}

/// Both Jacobians of `system` against Pinocchio's at every reference state
/// of `model` (the torques are the inputs, if the system has any).
fn check_against_pinocchio<S: MultibodySystem<N, N, NU>, const N: usize, const NU: usize>(
    model: &str,
    system: &S,
    accelerations_jacobian: AccelerationsJacobian<S, N, NU>,
    inverse_dynamics_jacobian: InverseDynamicsJacobian<S, N, NU>,
) {
    let array = |v: &Value| -> [f64; N] { numbers(v).try_into().expect("N numbers") };
    for state in reference_states(model) {
        let (q, v, a) = (
            array(&state["q"]),
            array(&state["qd"]),
            array(&state["vdot"]),
        );
        let u: [f64; NU] = match NU {
            0 => [0.0; NU],
            _ => numbers(&state["tau"]).try_into().expect("NU torques"),
        };
        let (by_q, by_v, by_u) = accelerations_jacobian(system, 0.0, &q, &v, &u).expect("solvable");
        let flat = |m: &[[f64; N]; N]| -> Vec<f64> { m.iter().flatten().copied().collect() };
        assert_agrees(&format!("{model} ∂q̈/∂q"), &flat(&by_q), &state["ddq_dq"]);
        assert_agrees(&format!("{model} ∂q̈/∂v"), &flat(&by_v), &state["ddq_dv"]);
        if NU == N {
            let by_u: Vec<f64> = by_u.iter().flatten().copied().collect();
            assert_agrees(&format!("{model} ∂q̈/∂τ"), &by_u, &state["ddq_dtau"]);
        }
        let (tau_q, tau_v, mass) = inverse_dynamics_jacobian(system, 0.0, &q, &v, &a, &u);
        assert_agrees(&format!("{model} ∂τ/∂q"), &flat(&tau_q), &state["dtau_dq"]);
        assert_agrees(&format!("{model} ∂τ/∂v"), &flat(&tau_v), &state["dtau_dv"]);
        assert_agrees(&format!("{model} ∂τ/∂a"), &flat(&mass), &state["dtau_da"]);
    }
}

/// Checks every listed system against Pinocchio (by its module in `derivatives`).
macro_rules! check_against_pinocchio {
    ($($module:ident :: $system:ident),* $(,)?) => {$(
        check_against_pinocchio(
            stringify!($module),
            &$module::$system {},
            $module::$system::accelerations_jacobian,
            $module::$system::inverse_dynamics_jacobian,
        );
    )*};
}

#[test]
fn chains_and_robots_match_pinocchio() {
    dalembert_generated::chains_and_robots_with_derivatives!(check_against_pinocchio);
}
