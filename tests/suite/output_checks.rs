//! The checks of the control outputs of `docs/language.md` ("Outputs") as an
//! outside tester makes them, shared by the systems of `planar_arm_outputs`,
//! `outputs_against_derivatives` and `rotor_sled_linearisation`: every
//! derivative against central differences of the emitted functions, the
//! kinematic outputs against the rates of `position` and `rotation` along the
//! motion, `inverse_dynamics` against `M v̇ − f` and the regressor against
//! `inverse_dynamics` with the inputs at zero.

use dalembert::MultibodySystem;
use dalembert_fixtures::differences::central_differences;
use dalembert_fixtures::reference::{assert_close, assert_near_all, flat};

pub(crate) type Vec3 = [f64; 3];
pub(crate) type Mat3 = [[f64; 3]; 3];

pub(crate) const STEP: f64 = 1e-6;
pub(crate) const DIFFERENCES: f64 = 1e-7;

/// A configuration, speeds, accelerations and inputs.
pub(crate) struct Sample<const NQ: usize, const NV: usize, const NU: usize> {
    pub(crate) t: f64,
    pub(crate) q: [f64; NQ],
    pub(crate) v: [f64; NV],
    pub(crate) vdot: [f64; NV],
    pub(crate) u: [f64; NU],
}

/// Deterministic pseudo-random entries in `[-1.5, 1.5)` (a linear
/// congruential generator: the tests need spread, not quality).
pub(crate) fn draws<const N: usize>(seed: &mut u64) -> [f64; N] {
    std::array::from_fn(|_| {
        *seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        3.0 * ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 1.5
    })
}

pub(crate) fn samples<const NQ: usize, const NV: usize, const NU: usize>(
    seed: u64,
) -> Vec<Sample<NQ, NV, NU>> {
    let mut seed = seed;
    (0..5)
        .map(|_| Sample {
            t: draws::<1>(&mut seed)[0],
            q: draws(&mut seed),
            v: draws(&mut seed),
            vdot: draws(&mut seed),
            u: draws(&mut seed),
        })
        .collect()
}

/// `d/ds g(s)` at `s = 0` by central differences.
pub(crate) fn rate<const K: usize>(g: impl Fn(f64) -> [f64; K]) -> [f64; K] {
    let (plus, minus) = (g(STEP), g(-STEP));
    std::array::from_fn(|i| (plus[i] - minus[i]) / (2.0 * STEP))
}

pub(crate) fn moved<const N: usize>(x: &[f64; N], dx: &[f64; N], s: f64) -> [f64; N] {
    std::array::from_fn(|i| x[i] + s * dx[i])
}

pub(crate) fn transposed_times(r: &Mat3, x: &Vec3) -> Vec3 {
    std::array::from_fn(|i| (0..3).map(|k| r[k][i] * x[k]).sum())
}

pub(crate) fn product<const K: usize>(a: &Mat3, b: &[[f64; K]; 3]) -> [[f64; K]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

pub(crate) fn transpose(a: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

pub(crate) fn matrix_times<const R: usize, const C: usize>(
    m: &[[f64; C]; R],
    x: &[f64; C],
) -> [f64; R] {
    std::array::from_fn(|i| m[i].iter().zip(x).map(|(a, b)| a * b).sum())
}

/// `ω` from `Ṙ Rᵀ = [ω]×`.
pub(crate) fn spin(rotation: &Mat3, rate: &Mat3) -> Vec3 {
    let w = product(rate, &transpose(rotation));
    [
        (w[2][1] - w[1][2]) / 2.0,
        (w[0][2] - w[2][0]) / 2.0,
        (w[1][0] - w[0][1]) / 2.0,
    ]
}

pub(crate) fn unflat(m: [f64; 9]) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| m[3 * i + j]))
}

/// An output of the time and the configuration.
pub(crate) type OfConfiguration<const NQ: usize, R> = Box<dyn Fn(f64, &[f64; NQ]) -> R>;
/// An output of the time, the configuration and the speeds.
pub(crate) type OfSpeeds<const NQ: usize, const NV: usize, R> =
    Box<dyn Fn(f64, &[f64; NQ], &[f64; NV]) -> R>;
/// An output of the time, the configuration, the speeds and the inputs.
pub(crate) type OfInputs<const NQ: usize, const NV: usize, const NU: usize, R> =
    Box<dyn Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NU]) -> R>;
/// An output of the time, the configuration, the speeds and their rates.
pub(crate) type OfMotion<const NQ: usize, const NV: usize, R> =
    Box<dyn Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NV]) -> R>;
/// An output of the motion and the inputs.
pub(crate) type OfMotionAndInputs<const NQ: usize, const NV: usize, const NU: usize, R> =
    Box<dyn Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NV], &[f64; NU]) -> R>;

/// A point's four kinematic outputs at a time, in one frame's axes.
pub(crate) struct PointOutputs<const NQ: usize, const NV: usize> {
    pub(crate) position: OfConfiguration<NQ, Vec3>,
    pub(crate) velocity: OfSpeeds<NQ, NV, Vec3>,
    pub(crate) acceleration: OfMotion<NQ, NV, Vec3>,
    pub(crate) jacobian: OfConfiguration<NQ, [[f64; NV]; 3]>,
}

/// A frame's three kinematic outputs at a time, in one frame's axes.
pub(crate) struct FrameOutputs<const NQ: usize, const NV: usize> {
    pub(crate) rotation: OfConfiguration<NQ, Mat3>,
    pub(crate) angular_velocity: OfSpeeds<NQ, NV, Vec3>,
    pub(crate) angular_jacobian: OfConfiguration<NQ, [[f64; NV]; 3]>,
}

/// In `N`'s axes: the velocity is the rate of the position along
/// `(t + s, q + s q̇)`, the jacobian its derivative by the speeds, the
/// acceleration the rate of the velocity along `(t + s, q + s q̇, v + s v̇)`.
pub(crate) fn check_point_in_n<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    point: &PointOutputs<NQ, NV>,
    x: &Sample<NQ, NV, NU>,
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    let rates = system.coordinate_rates(&x.q, &x.v);
    let velocity = (point.velocity)(x.t, &x.q, &x.v);
    let expected = rate(|s| (point.position)(x.t + s, &moved(&x.q, &rates, s)));
    assert_close("velocity", &velocity, &expected, DIFFERENCES);
    let by_speeds = central_differences(&x.v, STEP, |v| (point.velocity)(x.t, &x.q, v));
    let jacobian = (point.jacobian)(x.t, &x.q);
    assert_close("jacobian", &flat(&jacobian), &flat(&by_speeds), DIFFERENCES);
    let along = |s: f64| {
        let q = system.integrate_configuration(&x.q, &moved(&x.v, &x.vdot, s / 2.0), s);
        (point.velocity)(x.t + s, &q, &moved(&x.v, &x.vdot, s))
    };
    let acceleration = (point.acceleration)(x.t, &x.q, &x.v, &x.vdot);
    assert_close("acceleration", &acceleration, &rate(along), DIFFERENCES);
}

/// In `N`'s axes: `R` is a rotation and `Ṙ Rᵀ = [ω]×` along the motion,
/// the angular jacobian `ω`'s derivative by the speeds.
pub(crate) fn check_frame_in_n<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    frame: &FrameOutputs<NQ, NV>,
    x: &Sample<NQ, NV, NU>,
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    let rotation = (frame.rotation)(x.t, &x.q);
    let unit: Mat3 = std::array::from_fn(|i| std::array::from_fn(|j| f64::from(u8::from(i == j))));
    let gram = product(&transpose(&rotation), &rotation);
    assert_close("RᵀR", &flat(&gram), &flat(&unit), 1e-14);
    let rates = system.coordinate_rates(&x.q, &x.v);
    let turning = rate(|s| flat_array(&(frame.rotation)(x.t + s, &moved(&x.q, &rates, s))));
    let omega = (frame.angular_velocity)(x.t, &x.q, &x.v);
    assert_close("ω", &omega, &spin(&rotation, &unflat(turning)), DIFFERENCES);
    let by_speeds = central_differences(&x.v, STEP, |v| (frame.angular_velocity)(x.t, &x.q, v));
    let jacobian = (frame.angular_jacobian)(x.t, &x.q);
    assert_close(
        "angular jacobian",
        &flat(&jacobian),
        &flat(&by_speeds),
        DIFFERENCES,
    );
}

pub(crate) fn flat_array(m: &Mat3) -> [f64; 9] {
    std::array::from_fn(|k| m[k / 3][k % 3])
}

/// `name(P in F)` is `name(P)` in `F`'s axes: `Rᵀ x` for `R = rotation(F)`.
pub(crate) fn check_point_in_frame<const NQ: usize, const NV: usize, const NU: usize>(
    in_n: &PointOutputs<NQ, NV>,
    in_f: &PointOutputs<NQ, NV>,
    rotation: impl Fn(f64, &[f64; NQ]) -> Mat3,
    x: &Sample<NQ, NV, NU>,
) {
    let r = rotation(x.t, &x.q);
    let turn = |w: Vec3| transposed_times(&r, &w);
    let pairs = [
        (
            "position in F",
            (in_f.position)(x.t, &x.q),
            (in_n.position)(x.t, &x.q),
        ),
        (
            "velocity in F",
            (in_f.velocity)(x.t, &x.q, &x.v),
            (in_n.velocity)(x.t, &x.q, &x.v),
        ),
        (
            "acceleration in F",
            (in_f.acceleration)(x.t, &x.q, &x.v, &x.vdot),
            (in_n.acceleration)(x.t, &x.q, &x.v, &x.vdot),
        ),
    ];
    for (what, got, in_n) in pairs {
        assert_close(what, &got, &turn(in_n), 1e-13);
    }
    let jacobian = product(&transpose(&r), &(in_n.jacobian)(x.t, &x.q));
    assert_close(
        "jacobian in F",
        &flat(&(in_f.jacobian)(x.t, &x.q)),
        &flat(&jacobian),
        1e-13,
    );
}

/// `name(B in F)`: `rotation(B in F) = R_Fᵀ R_B`, and `ω_B` in `F`'s axes.
pub(crate) fn check_frame_in_frame<const NQ: usize, const NV: usize, const NU: usize>(
    in_n: &FrameOutputs<NQ, NV>,
    in_f: &FrameOutputs<NQ, NV>,
    rotation: impl Fn(f64, &[f64; NQ]) -> Mat3,
    x: &Sample<NQ, NV, NU>,
) {
    let r = transpose(&rotation(x.t, &x.q));
    let turned = product(&r, &(in_n.rotation)(x.t, &x.q));
    assert_close(
        "rotation in F",
        &flat(&(in_f.rotation)(x.t, &x.q)),
        &flat(&turned),
        1e-13,
    );
    let omega = transposed_times(&transpose(&r), &(in_n.angular_velocity)(x.t, &x.q, &x.v));
    assert_close(
        "ω in F",
        &(in_f.angular_velocity)(x.t, &x.q, &x.v),
        &omega,
        1e-13,
    );
    let jacobian = product(&r, &(in_n.angular_jacobian)(x.t, &x.q));
    assert_close(
        "angular jacobian in F",
        &flat(&(in_f.angular_jacobian)(x.t, &x.q)),
        &flat(&jacobian),
        1e-13,
    );
}

pub(crate) type Jacobians<const NV: usize, const NU: usize> =
    ([[f64; NV]; NV], [[f64; NV]; NV], [[f64; NU]; NV]);

/// `linearize`'s `(A, B)`.
pub(crate) type StateEquation<const N2: usize, const NU: usize> =
    ([[f64; N2]; N2], [[f64; NU]; N2]);

/// The dynamic outputs of one system, by their method names.
pub(crate) struct DynamicOutputs<const NQ: usize, const NV: usize, const NU: usize, const N2: usize>
{
    pub(crate) inverse_dynamics: OfMotionAndInputs<NQ, NV, NU, [f64; NV]>,
    pub(crate) inverse_dynamics_jacobian: OfMotionAndInputs<NQ, NV, NU, [[[f64; NV]; NV]; 3]>,
    pub(crate) accelerations_jacobian: OfInputs<NQ, NV, NU, Jacobians<NV, NU>>,
    pub(crate) linearize: OfInputs<NQ, NV, NU, StateEquation<N2, NU>>,
}

/// `inverse_dynamics = M v̇ − f`, its jacobian the central differences of
/// it, `accelerations_jacobian` those of `dalembert::accelerations`, and
/// `linearize` those of `(coordinate_rates, accelerations)` by `(q, v, u)`:
/// every coordinate here is a plain one, so `∂/∂q` is along `q + s eⱼ`.
pub(crate) fn check_dynamics<
    S,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const N2: usize,
>(
    system: &S,
    outputs: &DynamicOutputs<NQ, NV, NU, N2>,
    x: &Sample<NQ, NV, NU>,
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    assert_eq!((NQ, N2), (NV, 2 * NV), "plain coordinates only");
    let mass = system.mass_matrix(&x.q);
    let forcing = system.forcing(x.t, &x.q, &x.v, &x.u);
    let expected: [f64; NV] = std::array::from_fn(|i| matrix_times(&mass, &x.vdot)[i] - forcing[i]);
    let tau = |q: &[f64; NQ], v: &[f64; NV], vdot: &[f64; NV]| {
        (outputs.inverse_dynamics)(x.t, q, v, vdot, &x.u)
    };
    assert_close("M v̇ − f", &tau(&x.q, &x.v, &x.vdot), &expected, 1e-12);
    let [by_q, by_v, by_vdot] = (outputs.inverse_dynamics_jacobian)(x.t, &x.q, &x.v, &x.vdot, &x.u);
    let by_q_differences = central_differences(&x.q, STEP, |q| tau(q, &x.v, &x.vdot));
    assert_close("∂τ/∂q", &flat(&by_q), &flat(&by_q_differences), DIFFERENCES);
    let by_v_differences = central_differences(&x.v, STEP, |v| tau(&x.q, v, &x.vdot));
    assert_close("∂τ/∂v", &flat(&by_v), &flat(&by_v_differences), DIFFERENCES);
    assert_close("∂τ/∂v̇ = M", &flat(&by_vdot), &flat(&mass), 1e-13);
    let accelerations = |t: f64, q: &[f64; NQ], v: &[f64; NV], u: &[f64; NU]| {
        system
            .accelerations(t, q, v, u)
            .expect("a regular mass matrix")
    };
    let vdot = accelerations(x.t, &x.q, &x.v, &x.u);
    let at_rest = (outputs.inverse_dynamics)(x.t, &x.q, &x.v, &vdot, &x.u);
    let scale = forcing.iter().fold(1.0, |m: f64, f| m.max(f.abs()));
    assert_near_all(
        "τ at the accelerations",
        &at_rest,
        &[0.0; NV],
        1e-12 * scale,
    );
    let (dq, dv, du) = (outputs.accelerations_jacobian)(x.t, &x.q, &x.v, &x.u);
    let expected_dq = central_differences(&x.q, STEP, |q| accelerations(x.t, q, &x.v, &x.u));
    let expected_dv = central_differences(&x.v, STEP, |v| accelerations(x.t, &x.q, v, &x.u));
    let expected_du = central_differences(&x.u, STEP, |u| accelerations(x.t, &x.q, &x.v, u));
    assert_close("∂v̇/∂q", &flat(&dq), &flat(&expected_dq), DIFFERENCES);
    assert_close("∂v̇/∂v", &flat(&dv), &flat(&expected_dv), DIFFERENCES);
    assert_close("∂v̇/∂u", &flat(&du), &flat(&expected_du), DIFFERENCES);
    let (a, b) = (outputs.linearize)(x.t, &x.q, &x.v, &x.u);
    let rates_by_q = central_differences(&x.q, STEP, |q| system.coordinate_rates(q, &x.v));
    let rates_by_v = central_differences(&x.v, STEP, |v| system.coordinate_rates(&x.q, v));
    for i in 0..NV {
        let (upper, lower) = (&a[i], &a[NV + i]);
        let what = format!("A row {i}");
        assert_close(&what, &upper[..NV], &rates_by_q[i], DIFFERENCES);
        assert_close(&what, &upper[NV..], &rates_by_v[i], DIFFERENCES);
        assert_close(&what, &lower[..NV], &dq[i], 1e-13);
        assert_close(&what, &lower[NV..], &dv[i], 1e-13);
        assert_near_all(&format!("B row {i}"), &b[i], &[0.0; NU], 0.0);
        assert_close(&format!("B row {}", NV + i), &b[NV + i], &du[i], 1e-13);
    }
}

/// `Y(q, v, v̇) π = τ(t, q, v, v̇, 0)` for the base parameters `π`.
pub(crate) fn check_regressor<
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const NP: usize,
>(
    regressor: impl Fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> [[f64; NP]; NV],
    base_parameters: [f64; NP],
    inverse_dynamics: impl Fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> [f64; NV],
    x: &Sample<NQ, NV, NU>,
) {
    let y = regressor(&x.q, &x.v, &x.vdot);
    let tau = inverse_dynamics(&x.q, &x.v, &x.vdot);
    assert_close("Y π", &matrix_times(&y, &base_parameters), &tau, 1e-12);
}

/// The four point outputs `$name_$point[_in_$frame]` of a system constant.
macro_rules! point_outputs {
    ($system:expr, $position:ident, $velocity:ident, $acceleration:ident, $jacobian:ident) => {
        PointOutputs {
            position: Box::new(|t, q| $system.$position(t, q)),
            velocity: Box::new(|t, q, v| $system.$velocity(t, q, v)),
            acceleration: Box::new(|t, q, v, a| $system.$acceleration(t, q, v, a)),
            jacobian: Box::new(|t, q| $system.$jacobian(t, q)),
        }
    };
}
pub(crate) use point_outputs;

/// The three frame outputs of a system constant.
macro_rules! frame_outputs {
    ($system:expr, $rotation:ident, $angular_velocity:ident, $angular_jacobian:ident) => {
        FrameOutputs {
            rotation: Box::new(|t, q| $system.$rotation(t, q)),
            angular_velocity: Box::new(|t, q, v| $system.$angular_velocity(t, q, v)),
            angular_jacobian: Box::new(|t, q| $system.$angular_jacobian(t, q)),
        }
    };
}
pub(crate) use frame_outputs;

/// The dynamic outputs of a system constant.
macro_rules! dynamic_outputs {
    ($system:expr) => {
        DynamicOutputs {
            inverse_dynamics: Box::new(|t, q, v, a, u| $system.inverse_dynamics(t, q, v, a, u)),
            inverse_dynamics_jacobian: Box::new(|t, q, v, a, u| {
                let (dq, dv, da) = $system.inverse_dynamics_jacobian(t, q, v, a, u);
                [dq, dv, da]
            }),
            accelerations_jacobian: Box::new(|t, q, v, u| {
                $system.accelerations_jacobian(t, q, v, u).expect("regular")
            }),
            linearize: Box::new(|t, q, v, u| $system.linearize(t, q, v, u).expect("regular")),
        }
    };
}
pub(crate) use dynamic_outputs;
