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
use dalembert_fixtures::differences::central_differences;
use dalembert_generated::CartPole;
use dalembert_generated::derivatives::*;
use nalgebra::SMatrix;
use serde_json::Value;

/// Relative agreement required of the central differences.
const TOLERANCE: f64 = 1e-6;

/// Step of the central differences (their error is `O(h²)`, the rounding
/// `O(ε/h)`).
const STEP: f64 = 1e-5;

/// A random state: coordinates in `[−π, π)` (each quaternion then
/// normalised), speeds and inputs in `[−2, 2)`.
struct State<const NQ: usize, const NV: usize, const NU: usize> {
    t: f64,
    q: [f64; NQ],
    v: [f64; NV],
    u: [f64; NU],
}

impl<const NQ: usize, const NV: usize, const NU: usize> State<NQ, NV, NU> {
    fn random<S: MultibodySystem<NQ, NV, NU>>(system: &S, random: &mut Random) -> Self {
        let pi = std::f64::consts::PI;
        let t = random.uniform(0.0, 3.0);
        let q = std::array::from_fn(|_| random.uniform(-pi, pi));
        State {
            t,
            // `q ⊕ 0` normalises the quaternions and moves nothing else.
            q: system.integrate_configuration(&q, &[0.0; NV], 0.0),
            v: std::array::from_fn(|_| random.uniform(-2.0, 2.0)),
            u: std::array::from_fn(|_| random.uniform(-2.0, 2.0)),
        }
    }
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
pub(crate) type AccelerationsJacobian<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(
        &S,
        f64,
        &[f64; NQ],
        &[f64; NV],
        &[f64; NU],
    )
        -> Result<([[f64; NV]; NV], [[f64; NV]; NV], [[f64; NU]; NV]), dalembert::DynamicsError>;

/// `inverse_dynamics_jacobian(t, q, v, v̇, u)` of a system.
type InverseDynamicsJacobian<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(
        &S,
        f64,
        &[f64; NQ],
        &[f64; NV],
        &[f64; NV],
        &[f64; NU],
    ) -> ([[f64; NV]; NV], [[f64; NV]; NV], [[f64; NV]; NV]);

/// Both Jacobians of `system` against central differences of its
/// accelerations and of `M v̇ − f`, at random states; by `q` along
/// `q ⊕ δ` (`integrate_configuration`), in the tangent space.
fn check<S: MultibodySystem<NQ, NV, NU>, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    accelerations_jacobian: AccelerationsJacobian<S, NQ, NV, NU>,
    inverse_dynamics_jacobian: InverseDynamicsJacobian<S, NQ, NV, NU>,
    seed: u64,
) {
    let mut random = Random::new(seed);
    for _ in 0..5 {
        let State { t, q, v, u } = State::<NQ, NV, NU>::random(system, &mut random);
        let vdot = dalembert::accelerations(system, t, &q, &v, &u).expect("solvable");
        let accelerations = |q: &[f64; NQ], v: &[f64; NV], u: &[f64; NU]| {
            dalembert::accelerations(system, t, q, v, u).expect("solvable")
        };
        let moved = |delta: &[f64; NV]| system.integrate_configuration(&q, delta, 1.0);
        let (by_q, by_v, by_u) = accelerations_jacobian(system, t, &q, &v, &u).expect("solvable");
        assert_matches(
            "∂v̇/∂q",
            &by_q,
            &central_differences(&[0.0; NV], STEP, |delta| {
                accelerations(&moved(delta), &v, &u)
            }),
        );
        assert_matches(
            "∂v̇/∂v",
            &by_v,
            &central_differences(&v, STEP, |v| accelerations(&q, v, &u)),
        );
        assert_matches(
            "∂v̇/∂u",
            &by_u,
            &central_differences(&u, STEP, |u| accelerations(&q, &v, u)),
        );
        // τ = M v̇ − f at an arbitrary v̇, not only the solved one.
        let a: [f64; NV] = std::array::from_fn(|i| vdot[i] + random.uniform(-1.0, 1.0));
        let tau = |q: &[f64; NQ], v: &[f64; NV]| -> [f64; NV] {
            let (m, f) = (system.mass_matrix(q), system.forcing(t, q, v, &u));
            std::array::from_fn(|i| (0..NV).map(|j| m[i][j] * a[j]).sum::<f64>() - f[i])
        };
        let (tau_q, tau_v, mass) = inverse_dynamics_jacobian(system, t, &q, &v, &a, &u);
        assert_matches(
            "∂τ/∂q",
            &tau_q,
            &central_differences(&[0.0; NV], STEP, |delta| tau(&moved(delta), &v)),
        );
        assert_matches(
            "∂τ/∂v",
            &tau_v,
            &central_differences(&v, STEP, |v| tau(&q, v)),
        );
        // The same entries, emitted in two functions that may choose
        // different forms for them: equal to rounding.
        let m = system.mass_matrix(&q);
        for (row, m_row) in mass.iter().zip(&m) {
            for (x, y) in row.iter().zip(m_row) {
                assert!(
                    (x - y).abs() <= 1e-14 * (1.0 + y.abs()),
                    "∂τ/∂v̇ = M: {x} against {y}"
                );
            }
        }
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
fn quaternion_joints_match_central_differences_in_the_tangent_space() {
    check!(5;
        dzhanibekov::Dzhanibekov { m: 12.0, a: 3.0, b: 2.0, c: 1.0 },
        floating_solo12::FloatingSolo {},
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

/// A branching tree large enough for the jacobian's rows as adjoints
/// (`plan::ADJOINT_ROW_AT_MOST`; the world-frame partials in loops before),
/// with a slide among its joints.
#[test]
fn a_branching_tree_matches_central_differences() {
    check!(6; spatial_tree_14::SpatialTree14 {});
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
pub(crate) fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        other => vec![other.as_f64().expect("a number")],
    }
}

/// `max |got − want| / max |want|`, after checking the lengths agree.
pub(crate) fn relative_error(what: &str, got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len(), "{what}: length");
    let scale = want.iter().fold(f64::MIN_POSITIVE, |m, w| m.max(w.abs()));
    let error = got
        .iter()
        .zip(want)
        .fold(0.0_f64, |m, (g, w)| m.max((g - w).abs()));
    error / scale
}

/// `max |got − want| ≤ PINOCCHIO_TOLERANCE · max |want|`.
fn assert_agrees(what: &str, got: &[f64], want: &Value) {
    let error = relative_error(what, got, &numbers(want));
    assert!(
        error <= PINOCCHIO_TOLERANCE,
        "{what}: off by {error:e} relative"
    );
}

/// The states (never none) of `model` in `document`, the text of a
/// reference file `file` listing `models`, each with its `states`.
pub(crate) fn model_states(document: &str, file: &str, model: &str) -> Vec<Value> {
    let document: Value =
        serde_json::from_str(document).unwrap_or_else(|e| panic!("{file} parses: {e}"));
    let entry = document["models"]
        .as_array()
        .expect("models")
        .iter()
        .find(|m| m["model"] == model)
        .unwrap_or_else(|| panic!("{model} in {file}"));
    dalembert_fixtures::reference::states(entry).to_vec()
}

/// The reference states of `model` in `derivatives.json`.
fn reference_states(model: &str) -> Vec<Value> {
    let text = include_str!("../../../tests/reference/derivatives.json");
    model_states(text, "derivatives.json", model)
}

/// Both Jacobians of `system` against Pinocchio's at every reference state
/// of `model` (the torques are the inputs, if the system has any: the
/// last `NU` speeds').
fn check_against_pinocchio<
    S: MultibodySystem<NQ, NV, NU>,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
>(
    model: &str,
    system: &S,
    accelerations_jacobian: AccelerationsJacobian<S, NQ, NV, NU>,
    inverse_dynamics_jacobian: InverseDynamicsJacobian<S, NQ, NV, NU>,
) {
    fn array<const N: usize>(v: &Value) -> [f64; N] {
        numbers(v).try_into().expect("N numbers")
    }
    for state in reference_states(model) {
        let (q, v, a) = (
            array::<NQ>(&state["q"]),
            array::<NV>(&state["qd"]),
            array::<NV>(&state["vdot"]),
        );
        let u: [f64; NU] = match NU {
            0 => [0.0; NU],
            _ => array(&state["tau"]),
        };
        let (by_q, by_v, by_u) = accelerations_jacobian(system, 0.0, &q, &v, &u).expect("solvable");
        let flat = |m: &[[f64; NV]; NV]| -> Vec<f64> { m.iter().flatten().copied().collect() };
        assert_agrees(&format!("{model} ∂q̈/∂q"), &flat(&by_q), &state["ddq_dq"]);
        assert_agrees(&format!("{model} ∂q̈/∂v"), &flat(&by_v), &state["ddq_dv"]);
        if NU > 0 {
            // The columns of M⁻¹ of the actuated speeds.
            let rows = state["ddq_dtau"].as_array().expect("rows");
            let want: Vec<Value> = rows
                .iter()
                .map(|row| Value::Array(row.as_array().expect("a row")[NV - NU..].to_vec()))
                .collect();
            let by_u: Vec<f64> = by_u.iter().flatten().copied().collect();
            assert_agrees(&format!("{model} ∂q̈/∂τ"), &by_u, &Value::Array(want));
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

/// The floating Solo-12 and the brick on a ball joint: Pinocchio's
/// derivatives by `q` are in the tangent space of its free flyer and
/// spherical joint, as ours.
#[test]
fn quaternion_joints_match_pinocchio_in_the_tangent_space() {
    check_against_pinocchio(
        "solo12_floating",
        &floating_solo12::FloatingSolo {},
        floating_solo12::FloatingSolo::accelerations_jacobian,
        floating_solo12::FloatingSolo::inverse_dynamics_jacobian,
    );
    check_against_pinocchio(
        "dzhanibekov",
        &dzhanibekov::Dzhanibekov {
            m: 12.0,
            a: 3.0,
            b: 2.0,
            c: 1.0,
        },
        dzhanibekov::Dzhanibekov::accelerations_jacobian,
        dzhanibekov::Dzhanibekov::inverse_dynamics_jacobian,
    );
}

/// How a system's coordinates sit in its tangent space: a quaternion joint
/// first (a free joint's position and quaternion, or a spherical joint's
/// quaternion), then plain coordinates, one per remaining speed.
#[derive(Clone, Copy)]
enum Base {
    Free,
    Spherical,
}

/// `(x, y, z, w) ⊗ (x, y, z, w)`.
fn quaternion_product(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    let (u, v) = ([a[0], a[1], a[2]], [b[0], b[1], b[2]]);
    let cross = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let vector: [f64; 3] = std::array::from_fn(|i| a[3] * v[i] + b[3] * u[i] + cross[i]);
    let dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    [vector[0], vector[1], vector[2], a[3] * b[3] - dot]
}

/// `p⁻¹ ⊗ x ⊗ p` for a unit `p`: `x` in `p`'s axes.
fn in_axes_of(p: [f64; 4], x: [f64; 3]) -> [f64; 3] {
    let conjugate = [-p[0], -p[1], -p[2], p[3]];
    let turned = quaternion_product(quaternion_product(conjugate, [x[0], x[1], x[2], 0.0]), p);
    [turned[0], turned[1], turned[2]]
}

/// `q ⊖ q̄`: the tangent vector `δ` with `q̄ ⊕ δ = q` (the SE(3) or SO(3)
/// logarithm of `q̄⁻¹ q` for the quaternion joint, differences for the
/// rest), computed independently of the generated code.
fn tangent_difference<const NQ: usize, const NV: usize>(
    base: Base,
    q: &[f64; NQ],
    from: &[f64; NQ],
) -> [f64; NV] {
    // Where the quaternion is in `q`, and the angular speeds in `v`.
    let (quaternion, angular) = match base {
        Base::Free => (3, 3),
        Base::Spherical => (0, 0),
    };
    let at = |x: &[f64; NQ]| -> [f64; 4] { std::array::from_fn(|i| x[quaternion + i]) };
    let mut relative = quaternion_product(
        [-at(from)[0], -at(from)[1], -at(from)[2], at(from)[3]],
        at(q),
    );
    if relative[3] < 0.0 {
        relative = relative.map(|x| -x);
    }
    let sine = (relative[0].powi(2) + relative[1].powi(2) + relative[2].powi(2)).sqrt();
    let angle = 2.0 * sine.atan2(relative[3]);
    // angle / sine → 2 / w for a vanishing angle.
    let scale = match sine > 0.0 {
        true => angle / sine,
        false => 2.0 / relative[3],
    };
    let omega: [f64; 3] = std::array::from_fn(|i| relative[i] * scale);
    let mut delta = [0.0; NV];
    delta[angular..angular + 3].copy_from_slice(&omega);
    if let Base::Free = base {
        // V(ω)⁻¹ R̄ᵀ (r − r̄), V⁻¹ = 1 − ½[ω]× + (1 − θ sin θ / (2 (1 − cos θ))) [ω]×² / θ².
        let moved = in_axes_of(at(from), std::array::from_fn(|i| q[i] - from[i]));
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let once = cross(omega, moved);
        let twice = cross(omega, once);
        let c = match angle < 1e-2 {
            true => 1.0 / 12.0 + angle * angle / 720.0,
            false => (1.0 - angle * angle.sin() / (2.0 * (1.0 - angle.cos()))) / (angle * angle),
        };
        for i in 0..3 {
            delta[i] = moved[i] - 0.5 * once[i] + c * twice[i];
        }
    }
    let (first_plain, first_plain_speed) = (quaternion + 4, angular + 3);
    for (k, i) in (first_plain_speed..NV).zip(first_plain..NQ) {
        delta[k] = q[i] - from[i];
    }
    delta
}

/// The kinematic rows of `linearize` (`δ̇` by `δ` and `δv`, with
/// `q = q̄ ⊕ δ`) against mixed central differences of
/// `((q̄ ⊕ ε δ₀) ⊕ h (v̄ + ε δv)) ⊖ (q̄ ⊕ h v̄)` in `h` and `ε`; the dynamic
/// rows are `accelerations_jacobian`'s.
fn check_kinematic_rows<
    S: MultibodySystem<NQ, NV, NU>,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const NX: usize,
>(
    system: &S,
    base: Base,
    linearize: Linearize<S, NQ, NV, NU, NX>,
    accelerations_jacobian: AccelerationsJacobian<S, NQ, NV, NU>,
) {
    let mut random = Random::new(6);
    for _ in 0..3 {
        let State { t, q, v, u } = State::<NQ, NV, NU>::random(system, &mut random);
        let (a, b) = linearize(system, t, &q, &v, &u).expect("solvable");
        let (by_q, by_v, by_u) = accelerations_jacobian(system, t, &q, &v, &u).expect("solvable");
        let step = 1e-4;
        let delta = |h: f64, epsilon: f64, j: usize| -> [f64; NV] {
            let (mut d0, mut dv) = ([0.0; NV], [0.0; NV]);
            match j < NV {
                true => d0[j] = epsilon,
                false => dv[j - NV] = epsilon,
            }
            let start = system.integrate_configuration(&q, &d0, 1.0);
            let speeds: [f64; NV] = std::array::from_fn(|k| v[k] + dv[k]);
            let moved = system.integrate_configuration(&start, &speeds, h);
            let reference = system.integrate_configuration(&q, &v, h);
            tangent_difference(base, &moved, &reference)
        };
        // Column j of the mixed differences, then transposed.
        let columns: [[f64; NV]; NX] = std::array::from_fn(|j| {
            let (pp, pm, mp, mm) = (
                delta(step, step, j),
                delta(step, -step, j),
                delta(-step, step, j),
                delta(-step, -step, j),
            );
            std::array::from_fn(|i| (pp[i] - pm[i] - mp[i] + mm[i]) / (4.0 * step * step))
        });
        let numeric: [[f64; NX]; NV] = std::array::from_fn(|i| columns.map(|column| column[i]));
        let kinematic: [[f64; NX]; NV] = std::array::from_fn(|i| a[i]);
        assert_matches("A's kinematic rows", &kinematic, &numeric);
        for i in 0..NV {
            assert_eq!(a[NV + i][..NV], by_q[i], "A's row {}", NV + i);
            assert_eq!(a[NV + i][NV..], by_v[i], "A's row {}", NV + i);
            assert_eq!(b[i], [0.0; NU]);
            assert_eq!(b[NV + i], by_u[i]);
        }
    }
}

/// `linearize(t, q, v, u)` of a system with a state of `NX` entries.
type Linearize<S, const NQ: usize, const NV: usize, const NU: usize, const NX: usize> =
    fn(
        &S,
        f64,
        &[f64; NQ],
        &[f64; NV],
        &[f64; NU],
    ) -> Result<([[f64; NX]; NX], [[f64; NU]; NX]), dalembert::DynamicsError>;

#[test]
fn linearize_of_quaternion_joints_has_the_kinematic_rows_of_the_tangent_space() {
    let brick = dzhanibekov::Dzhanibekov {
        m: 12.0,
        a: 3.0,
        b: 2.0,
        c: 1.0,
    };
    check_kinematic_rows(
        &brick,
        Base::Spherical,
        dzhanibekov::Dzhanibekov::linearize,
        dzhanibekov::Dzhanibekov::accelerations_jacobian,
    );
    check_kinematic_rows(
        &floating_solo12::FloatingSolo {},
        Base::Free,
        floating_solo12::FloatingSolo::linearize,
        floating_solo12::FloatingSolo::accelerations_jacobian,
    );
}
