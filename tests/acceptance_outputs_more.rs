//! The control outputs of `docs/language.md` ("Outputs") on systems that no
//! other test writes, checked as an outside tester would: every derivative
//! against central differences of the emitted functions, the kinematic
//! outputs against the rates of `position` and `rotation` along the motion,
//! `inverse_dynamics` against `M v̇ − f` (and against the `M v̇ − f` of the
//! SymPy reading `dal_sympy.py`) and the regressor against
//! `inverse_dynamics` with the inputs at zero. The systems: a planar arm with
//! a slide and a payload on a massless wrist (spelled with frames and points,
//! and with `joint`s), inputs in a turning frame, springs, dampers and a
//! support shaken with time, and a body with symbolic products of inertia
//! and parameters inside functions.

use dalembert::MultibodySystem;
use dalembert_fixtures::differences::central_differences;
use dalembert_fixtures::reference::{assert_close, assert_near_all, flat};

type Vec3 = [f64; 3];
type Mat3 = [[f64; 3]; 3];

const STEP: f64 = 1e-6;
const DIFFERENCES: f64 = 1e-7;

/// The planar arm (a shoulder, a slide along the upper arm, a wrist without
/// mass carrying a payload) in one spelling of its geometry, its loads and
/// outputs common to both, and its constant `$value`.
macro_rules! arm {
    ($(#[$doc:meta])* $name:ident = $value:ident, $($geometry:tt)*) => {
        dalembert::dalembert! {
            $(#[$doc])*
            pub $name {
                parameters m1, m2, mp, l1, l2, I1, I2, g;
                coordinates th, s, ph;
                inputs tau, push, twist;
                $($geometry)*
                point P = S + l2 * W.x;
                point C1 = O + l1 / 2 * A.x;
                body upper { mass: m1, center: C1, frame: A, inertia: [0, 0, I1] };
                body slider { mass: m2, center: S, frame: B, inertia: [0, 0, I2] };
                particle payload { mass: mp, at: P };
                gravity -g * N.y;
                torque tau * N.z on A;
                force push * A.x at S;
                torque twist * N.z on W reacting B;
                outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize, regressor;
                outputs position(P), velocity(P), acceleration(P), jacobian(P);
                outputs position(P in A), velocity(P in A), acceleration(P in A), jacobian(P in A);
                outputs rotation(A), rotation(W), angular_velocity(W), angular_jacobian(W);
                outputs rotation(W in A), angular_velocity(W in A), angular_jacobian(W in A);
            }
        }

        const $value: $name = $name {
            m1: 2.1,
            m2: 0.9,
            mp: 0.45,
            l1: 0.8,
            l2: 0.35,
            I1: 0.11,
            I2: 0.02,
            g: 9.81,
        };
    };
}

arm! {
    /// The arm with frames and points.
    ArmByPoints = ARM_BY_POINTS,
    frame A = N.rotate_z(th);
    frame B = A.rotate_z(0);
    point S = O + s * A.x;
    frame W = B.rotate_z(ph);
}

arm! {
    /// The arm with joints.
    ArmByJoints = ARM_BY_JOINTS,
    joint revolute shoulder { parent: N, child: A, axis: z, coordinate: th, at: O };
    joint prismatic slide { parent: A, child: B, axis: x, coordinate: s, at: O };
    point S = slide;
    joint revolute wrist { parent: B, child: W, axis: z, coordinate: ph, at: S };
}

dalembert::dalembert! {
    /// A turntable carrying a tilting arm; a force along the arm and a motor
    /// between arm and table, so the inputs enter through the turning axes.
    pub TurningInputs {
        parameters m, d, l, g;
        coordinates phi, theta;
        inputs pull, motor;
        frame F = N.rotate_z(phi);
        frame B = F.rotate_y(theta);
        point H = O + d * F.y;
        point G = H + l * B.z;
        body arm { mass: m, center: G, frame: B, inertia: [m*l^2/3, m*l^2/3, 0.01*m] };
        gravity -g * N.z;
        force pull * B.x at G;
        torque motor * F.y on B reacting F;
        outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize, regressor;
        outputs position(G in F), velocity(G in F), acceleration(G in F), jacobian(G in F);
        outputs rotation(F), angular_velocity(B in F), angular_jacobian(B in F), rotation(B in F);
    }
}

const TURNING_INPUTS: TurningInputs = TurningInputs {
    m: 1.4,
    d: 0.3,
    l: 0.6,
    g: 9.81,
};

dalembert::dalembert! {
    /// A cart on a spring carrying a pendulum, springs and dampers both (the
    /// damping depending on the coordinates), a load that varies with time
    /// and a marker without mass sliding along the pendulum with time.
    pub ShakenSprings {
        parameters m, M, l, k, kt, c, ct, a, w, g;
        coordinates x, th;
        inputs u;
        frame B = N.rotate_z(th);
        point Cart = O + x * N.x;
        point Bob = Cart - l * B.y;
        point Marker = Bob + a * sin(w * t) * B.x;
        particle cart { mass: M, at: Cart };
        particle bob { mass: m, at: Bob };
        gravity -g * N.y;
        potential k / 2 * x^2 + kt * (1 - cos(th));
        dissipation c / 2 * dt(x)^2 + ct / 2 * (cos(th) * dt(th))^2 + c / 2 * x^2 * dt(th)^2;
        force (u + a * cos(w * t)) * N.x at Cart;
        outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize;
        outputs position(Marker), velocity(Marker), acceleration(Marker), jacobian(Marker);
        outputs position(Marker in B), velocity(Marker in B), acceleration(Marker in B), jacobian(Marker in B), rotation(B);
    }
}

const SHAKEN: ShakenSprings = ShakenSprings {
    m: 0.6,
    M: 1.9,
    l: 0.7,
    k: 12.0,
    kt: 0.8,
    c: 0.4,
    ct: 0.3,
    a: 0.05,
    w: 7.0,
    g: 9.81,
};

dalembert::dalembert! {
    /// A body on a tilted axis (`alpha` inside functions), turning and
    /// nodding, with all six entries of its inertia symbolic and its center
    /// off both axes.
    pub FullInertia {
        parameters m, c, e, alpha, Ixx, Iyy, Izz, Ixy, Iyz, Izx, g;
        coordinates q1, q2;
        inputs u1;
        frame A = N.rotate_x(alpha);
        frame B = A.rotate_z(q1);
        frame C = B.rotate_x(q2);
        point G = O + e^2 * B.x + c * C.y;
        body b { mass: m, center: G, frame: C, inertia: [Ixx, Iyy, Izz, Ixy, Iyz, Izx] };
        gravity -g * N.z;
        torque u1 * B.x on C reacting B;
        outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize, regressor;
        outputs velocity(G in C), acceleration(G in C), angular_velocity(C in A), angular_jacobian(C in A);
        outputs rotation(C), rotation(A), position(G), velocity(G), acceleration(G), jacobian(G);
        outputs angular_velocity(C), angular_jacobian(C), position(G in C), jacobian(G in C), rotation(C in A);
    }
}

const FULL_INERTIA: FullInertia = FullInertia {
    m: 1.3,
    c: 0.25,
    e: 0.6,
    alpha: 0.4,
    Ixx: 0.05,
    Iyy: 0.07,
    Izz: 0.09,
    Ixy: 0.004,
    Iyz: -0.006,
    Izx: 0.003,
    g: 9.81,
};

dalembert::dalembert! {
    /// A heavy top in X-Y-Z Cardan angles with its body rates as speeds.
    pub RatesTop {
        parameters m, h, I1, I2, I3, g;
        coordinates a, b, c;
        inputs spin;
        speeds wx, wy, wz {
            a: (cos(c) * wx - sin(c) * wy) / cos(b),
            b: sin(c) * wx + cos(c) * wy,
            c: wz - tan(b) * (cos(c) * wx - sin(c) * wy)
        };
        frame A = N.rotate_x(a);
        frame C = A.rotate_y(b);
        frame B = C.rotate_z(c);
        point G = O + h * B.x;
        body top { mass: m, center: G, frame: B, inertia: [I1, I2, I3] };
        gravity -g * N.z;
        torque spin * B.z on B;
        outputs inverse_dynamics, inverse_dynamics_jacobian, accelerations_jacobian, linearize, regressor;
        outputs position(G), velocity(G), acceleration(G), jacobian(G);
        outputs rotation(B), angular_velocity(B), angular_jacobian(B);
        outputs position(G in C), velocity(G in C), acceleration(G in C), jacobian(G in C);
        outputs rotation(B in C), angular_velocity(B in C), angular_jacobian(B in C);
    }
}

const RATES_TOP: RatesTop = RatesTop {
    m: 0.8,
    h: 0.12,
    I1: 0.011,
    I2: 0.013,
    I3: 0.02,
    g: 9.81,
};

/// A configuration, speeds, accelerations and inputs.
struct Sample<const NQ: usize, const NV: usize, const NU: usize> {
    t: f64,
    q: [f64; NQ],
    v: [f64; NV],
    vdot: [f64; NV],
    u: [f64; NU],
}

/// Deterministic pseudo-random entries in `[-1.5, 1.5)` (a linear
/// congruential generator: the tests need spread, not quality).
fn draws<const N: usize>(seed: &mut u64) -> [f64; N] {
    std::array::from_fn(|_| {
        *seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        3.0 * ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 1.5
    })
}

fn samples<const NQ: usize, const NV: usize, const NU: usize>(
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
fn rate<const K: usize>(g: impl Fn(f64) -> [f64; K]) -> [f64; K] {
    let (plus, minus) = (g(STEP), g(-STEP));
    std::array::from_fn(|i| (plus[i] - minus[i]) / (2.0 * STEP))
}

fn moved<const N: usize>(x: &[f64; N], dx: &[f64; N], s: f64) -> [f64; N] {
    std::array::from_fn(|i| x[i] + s * dx[i])
}

fn transposed_times(r: &Mat3, x: &Vec3) -> Vec3 {
    std::array::from_fn(|i| (0..3).map(|k| r[k][i] * x[k]).sum())
}

fn product<const K: usize>(a: &Mat3, b: &[[f64; K]; 3]) -> [[f64; K]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose(a: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

fn matrix_times<const R: usize, const C: usize>(m: &[[f64; C]; R], x: &[f64; C]) -> [f64; R] {
    std::array::from_fn(|i| m[i].iter().zip(x).map(|(a, b)| a * b).sum())
}

/// `ω` from `Ṙ Rᵀ = [ω]×`.
fn spin(rotation: &Mat3, rate: &Mat3) -> Vec3 {
    let w = product(rate, &transpose(rotation));
    [
        (w[2][1] - w[1][2]) / 2.0,
        (w[0][2] - w[2][0]) / 2.0,
        (w[1][0] - w[0][1]) / 2.0,
    ]
}

fn unflat(m: [f64; 9]) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| m[3 * i + j]))
}

/// An output of the time and the configuration.
type OfConfiguration<const NQ: usize, R> = Box<dyn Fn(f64, &[f64; NQ]) -> R>;
/// An output of the time, the configuration and the speeds.
type OfSpeeds<const NQ: usize, const NV: usize, R> = Box<dyn Fn(f64, &[f64; NQ], &[f64; NV]) -> R>;
/// An output of the time, the configuration, the speeds and the inputs.
type OfInputs<const NQ: usize, const NV: usize, const NU: usize, R> =
    Box<dyn Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NU]) -> R>;
/// An output of the time, the configuration, the speeds and their rates.
type OfMotion<const NQ: usize, const NV: usize, R> =
    Box<dyn Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NV]) -> R>;
/// An output of the motion and the inputs.
type OfMotionAndInputs<const NQ: usize, const NV: usize, const NU: usize, R> =
    Box<dyn Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NV], &[f64; NU]) -> R>;

/// A point's four kinematic outputs at a time, in one frame's axes.
struct PointOutputs<const NQ: usize, const NV: usize> {
    position: OfConfiguration<NQ, Vec3>,
    velocity: OfSpeeds<NQ, NV, Vec3>,
    acceleration: OfMotion<NQ, NV, Vec3>,
    jacobian: OfConfiguration<NQ, [[f64; NV]; 3]>,
}

/// A frame's three kinematic outputs at a time, in one frame's axes.
struct FrameOutputs<const NQ: usize, const NV: usize> {
    rotation: OfConfiguration<NQ, Mat3>,
    angular_velocity: OfSpeeds<NQ, NV, Vec3>,
    angular_jacobian: OfConfiguration<NQ, [[f64; NV]; 3]>,
}

/// In `N`'s axes: the velocity is the rate of the position along
/// `(t + s, q + s q̇)`, the jacobian its derivative by the speeds, the
/// acceleration the rate of the velocity along `(t + s, q + s q̇, v + s v̇)`.
fn check_point_in_n<S, const NQ: usize, const NV: usize, const NU: usize>(
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
fn check_frame_in_n<S, const NQ: usize, const NV: usize, const NU: usize>(
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

fn flat_array(m: &Mat3) -> [f64; 9] {
    std::array::from_fn(|k| m[k / 3][k % 3])
}

/// `name(P in F)` is `name(P)` in `F`'s axes: `Rᵀ x` for `R = rotation(F)`.
fn check_point_in_frame<const NQ: usize, const NV: usize, const NU: usize>(
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
fn check_frame_in_frame<const NQ: usize, const NV: usize, const NU: usize>(
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

type Jacobians<const NV: usize, const NU: usize> =
    ([[f64; NV]; NV], [[f64; NV]; NV], [[f64; NU]; NV]);

/// `linearize`'s `(A, B)`.
type StateEquation<const N2: usize, const NU: usize> = ([[f64; N2]; N2], [[f64; NU]; N2]);

/// The dynamic outputs of one system, by their method names.
struct DynamicOutputs<const NQ: usize, const NV: usize, const NU: usize, const N2: usize> {
    inverse_dynamics: OfMotionAndInputs<NQ, NV, NU, [f64; NV]>,
    inverse_dynamics_jacobian: OfMotionAndInputs<NQ, NV, NU, [[[f64; NV]; NV]; 3]>,
    accelerations_jacobian: OfInputs<NQ, NV, NU, Jacobians<NV, NU>>,
    linearize: OfInputs<NQ, NV, NU, StateEquation<N2, NU>>,
}

/// `inverse_dynamics = M v̇ − f`, its jacobian the central differences of
/// it, `accelerations_jacobian` those of `dalembert::accelerations`, and
/// `linearize` those of `(coordinate_rates, accelerations)` by `(q, v, u)`:
/// every coordinate here is a plain one, so `∂/∂q` is along `q + s eⱼ`.
fn check_dynamics<S, const NQ: usize, const NV: usize, const NU: usize, const N2: usize>(
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
fn check_regressor<const NQ: usize, const NV: usize, const NU: usize, const NP: usize>(
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

#[test]
fn arm_outputs_match_their_derivatives() {
    let dynamics = dynamic_outputs!(ARM_BY_POINTS);
    let payload = point_outputs!(
        ARM_BY_POINTS,
        position_P,
        velocity_P,
        acceleration_P,
        jacobian_P
    );
    let payload_in_a = point_outputs!(
        ARM_BY_POINTS,
        position_P_in_A,
        velocity_P_in_A,
        acceleration_P_in_A,
        jacobian_P_in_A
    );
    let wrist = frame_outputs!(
        ARM_BY_POINTS,
        rotation_W,
        angular_velocity_W,
        angular_jacobian_W
    );
    let wrist_in_a = frame_outputs!(
        ARM_BY_POINTS,
        rotation_W_in_A,
        angular_velocity_W_in_A,
        angular_jacobian_W_in_A
    );
    let upper = |t, q: &[f64; 3]| ARM_BY_POINTS.rotation_A(t, q);
    for x in samples::<3, 3, 3>(1) {
        check_dynamics(&ARM_BY_POINTS, &dynamics, &x);
        check_regressor(
            |q, v, a| ARM_BY_POINTS.regressor(q, v, a),
            ARM_BY_POINTS.base_parameters(),
            |q, v, a| ARM_BY_POINTS.inverse_dynamics(x.t, q, v, a, &[0.0; 3]),
            &x,
        );
        check_point_in_n(&ARM_BY_POINTS, &payload, &x);
        check_point_in_frame(&payload, &payload_in_a, upper, &x);
        check_frame_in_n(&ARM_BY_POINTS, &wrist, &x);
        check_frame_in_frame(&wrist, &wrist_in_a, upper, &x);
    }
}

/// Spelled with joints, the arm has the same outputs to rounding.
#[test]
fn arm_by_joints_has_the_outputs_of_arm_by_points() {
    for x in samples::<3, 3, 3>(2) {
        let (t, q, v, a, u) = (x.t, &x.q, &x.v, &x.vdot, &x.u);
        let pairs: [(&str, Vec<f64>, Vec<f64>); 9] = [
            (
                "τ",
                ARM_BY_JOINTS.inverse_dynamics(t, q, v, a, u).to_vec(),
                ARM_BY_POINTS.inverse_dynamics(t, q, v, a, u).to_vec(),
            ),
            (
                "Y",
                flat(&ARM_BY_JOINTS.regressor(q, v, a)),
                flat(&ARM_BY_POINTS.regressor(q, v, a)),
            ),
            (
                "π",
                ARM_BY_JOINTS.base_parameters().to_vec(),
                ARM_BY_POINTS.base_parameters().to_vec(),
            ),
            (
                "A",
                flat(&ARM_BY_JOINTS.linearize(t, q, v, u).expect("regular").0),
                flat(&ARM_BY_POINTS.linearize(t, q, v, u).expect("regular").0),
            ),
            (
                "B",
                flat(&ARM_BY_JOINTS.linearize(t, q, v, u).expect("regular").1),
                flat(&ARM_BY_POINTS.linearize(t, q, v, u).expect("regular").1),
            ),
            (
                "a_P in A",
                ARM_BY_JOINTS.acceleration_P_in_A(t, q, v, a).to_vec(),
                ARM_BY_POINTS.acceleration_P_in_A(t, q, v, a).to_vec(),
            ),
            (
                "J_P",
                flat(&ARM_BY_JOINTS.jacobian_P(t, q)),
                flat(&ARM_BY_POINTS.jacobian_P(t, q)),
            ),
            (
                "R_W in A",
                flat(&ARM_BY_JOINTS.rotation_W_in_A(t, q)),
                flat(&ARM_BY_POINTS.rotation_W_in_A(t, q)),
            ),
            (
                "J_W",
                flat(&ARM_BY_JOINTS.angular_jacobian_W(t, q)),
                flat(&ARM_BY_POINTS.angular_jacobian_W(t, q)),
            ),
        ];
        for (what, joints, points) in pairs {
            assert_close(what, &joints, &points, 1e-13);
        }
    }
    assert_eq!(ArmByJoints::BASE_PARAMETERS, ArmByPoints::BASE_PARAMETERS);
}

#[test]
fn inputs_in_turning_axes_match_their_derivatives() {
    let dynamics = dynamic_outputs!(TURNING_INPUTS);
    let table = |t, q: &[f64; 2]| TURNING_INPUTS.rotation_F(t, q);
    for x in samples::<2, 2, 2>(3) {
        check_dynamics(&TURNING_INPUTS, &dynamics, &x);
        check_regressor(
            |q, v, a| TURNING_INPUTS.regressor(q, v, a),
            TURNING_INPUTS.base_parameters(),
            |q, v, a| TURNING_INPUTS.inverse_dynamics(x.t, q, v, a, &[0.0; 2]),
            &x,
        );
        // The rotation of F is about N.z by phi; G in F's axes is the
        // closed form d F.y + l B.z with B.z = (sin θ, 0, cos θ) in F.
        let (s, c) = x.q[1].sin_cos();
        let expected = [TURNING_INPUTS.l * s, TURNING_INPUTS.d, TURNING_INPUTS.l * c];
        assert_close(
            "G in F",
            &TURNING_INPUTS.position_G_in_F(x.t, &x.q),
            &expected,
            1e-14,
        );
        let g_in_f = PointOutputs {
            position: Box::new(|t, q: &[f64; 2]| {
                let r = TURNING_INPUTS.rotation_F(t, q);
                matrix_times(&r, &TURNING_INPUTS.position_G_in_F(t, q))
            }),
            velocity: Box::new(|t, q, v| {
                matrix_times(
                    &TURNING_INPUTS.rotation_F(t, q),
                    &TURNING_INPUTS.velocity_G_in_F(t, q, v),
                )
            }),
            acceleration: Box::new(|t, q, v, a| {
                matrix_times(
                    &TURNING_INPUTS.rotation_F(t, q),
                    &TURNING_INPUTS.acceleration_G_in_F(t, q, v, a),
                )
            }),
            jacobian: Box::new(|t, q| {
                product(
                    &TURNING_INPUTS.rotation_F(t, q),
                    &TURNING_INPUTS.jacobian_G_in_F(t, q),
                )
            }),
        };
        check_point_in_n(&TURNING_INPUTS, &g_in_f, &x);
        // B relative to F turns about F.y at θ̇: its ω in F's axes is that
        // plus φ̇ N.z = φ̇ F.z.
        let omega = TURNING_INPUTS.angular_velocity_B_in_F(x.t, &x.q, &x.v);
        assert_close("ω_B in F", &omega, &[0.0, x.v[1], x.v[0]], 1e-14);
        let jacobian = TURNING_INPUTS.angular_jacobian_B_in_F(x.t, &x.q);
        assert_close(
            "J_B in F",
            &flat(&jacobian),
            &[0.0, 0.0, 0.0, 1.0, 1.0, 0.0],
            1e-14,
        );
        let r_b = product(
            &table(x.t, &x.q),
            &TURNING_INPUTS.rotation_B_in_F(x.t, &x.q),
        );
        let expected_b = [[c, -0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]];
        assert_close(
            "R_B in F",
            &flat(&TURNING_INPUTS.rotation_B_in_F(x.t, &x.q)),
            &flat(&expected_b),
            1e-14,
        );
        assert_close(
            "R_F R_B/F",
            &flat(&r_b),
            &flat(&product(&table(x.t, &x.q), &expected_b)),
            1e-14,
        );
    }
}

#[test]
fn springs_dampers_and_time_match_their_derivatives() {
    let dynamics = dynamic_outputs!(SHAKEN);
    let marker = point_outputs!(
        SHAKEN,
        position_Marker,
        velocity_Marker,
        acceleration_Marker,
        jacobian_Marker
    );
    let marker_in_b = point_outputs!(
        SHAKEN,
        position_Marker_in_B,
        velocity_Marker_in_B,
        acceleration_Marker_in_B,
        jacobian_Marker_in_B
    );
    let pendulum = |t, q: &[f64; 2]| SHAKEN.rotation_B(t, q);
    for x in samples::<2, 2, 1>(4) {
        check_dynamics(&SHAKEN, &dynamics, &x);
        check_point_in_n(&SHAKEN, &marker, &x);
        check_point_in_frame(&marker, &marker_in_b, pendulum, &x);
    }
}

#[test]
fn symbolic_products_of_inertia_match_their_derivatives() {
    let dynamics = dynamic_outputs!(FULL_INERTIA);
    let center = point_outputs!(
        FULL_INERTIA,
        position_G,
        velocity_G,
        acceleration_G,
        jacobian_G
    );
    let center_in_c = point_outputs!(
        FULL_INERTIA,
        position_G_in_C,
        velocity_G_in_C,
        acceleration_G_in_C,
        jacobian_G_in_C
    );
    let body = frame_outputs!(
        FULL_INERTIA,
        rotation_C,
        angular_velocity_C,
        angular_jacobian_C
    );
    let body_in_a = FrameOutputs {
        rotation: Box::new(|t, q: &[f64; 2]| FULL_INERTIA.rotation_C_in_A(t, q)),
        angular_velocity: Box::new(|t, q, v| FULL_INERTIA.angular_velocity_C_in_A(t, q, v)),
        angular_jacobian: Box::new(|t, q| FULL_INERTIA.angular_jacobian_C_in_A(t, q)),
    };
    let tilted = |t, q: &[f64; 2]| FULL_INERTIA.rotation_A(t, q);
    let own = |t, q: &[f64; 2]| FULL_INERTIA.rotation_C(t, q);
    for x in samples::<2, 2, 1>(5) {
        check_dynamics(&FULL_INERTIA, &dynamics, &x);
        check_regressor(
            |q, v, a| FULL_INERTIA.regressor(q, v, a),
            FULL_INERTIA.base_parameters(),
            |q, v, a| FULL_INERTIA.inverse_dynamics(x.t, q, v, a, &[0.0]),
            &x,
        );
        check_point_in_n(&FULL_INERTIA, &center, &x);
        check_point_in_frame(&center, &center_in_c, own, &x);
        check_frame_in_n(&FULL_INERTIA, &body, &x);
        check_frame_in_frame(&body, &body_in_a, tilted, &x);
    }
}

#[test]
fn speeds_of_ones_own_match_their_derivatives() {
    let dynamics = dynamic_outputs!(RATES_TOP);
    let center = point_outputs!(
        RATES_TOP,
        position_G,
        velocity_G,
        acceleration_G,
        jacobian_G
    );
    let center_in_c = point_outputs!(
        RATES_TOP,
        position_G_in_C,
        velocity_G_in_C,
        acceleration_G_in_C,
        jacobian_G_in_C
    );
    let body = frame_outputs!(
        RATES_TOP,
        rotation_B,
        angular_velocity_B,
        angular_jacobian_B
    );
    let body_in_c = frame_outputs!(
        RATES_TOP,
        rotation_B_in_C,
        angular_velocity_B_in_C,
        angular_jacobian_B_in_C
    );
    let gimbal = |t, q: &[f64; 3]| {
        let turned_back = transpose(&RATES_TOP.rotation_B_in_C(t, q));
        product(&RATES_TOP.rotation_B(t, q), &turned_back)
    };
    for x in samples::<3, 3, 1>(6) {
        check_dynamics(&RATES_TOP, &dynamics, &x);
        check_regressor(
            |q, v, a| RATES_TOP.regressor(q, v, a),
            RATES_TOP.base_parameters(),
            |q, v, a| RATES_TOP.inverse_dynamics(x.t, q, v, a, &[0.0]),
            &x,
        );
        check_point_in_n(&RATES_TOP, &center, &x);
        check_point_in_frame(&center, &center_in_c, gimbal, &x);
        check_frame_in_n(&RATES_TOP, &body, &x);
        check_frame_in_frame(&body, &body_in_c, gimbal, &x);
        // The speeds are B's angular velocity in B's axes.
        let in_b = transposed_times(
            &RATES_TOP.rotation_B(x.t, &x.q),
            &RATES_TOP.angular_velocity_B(x.t, &x.q, &x.v),
        );
        assert_close("ω_B in B", &in_b, &x.v, 1e-14);
    }
}

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

/// The smallest singular value of `Y` stacked over 12 random motions,
/// relative to the largest: positive where no combination of the base
/// parameters leaves `M v̇ − f` unchanged.
fn independence<const NQ: usize, const NV: usize, const NP: usize>(
    regressor: impl Fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> [[f64; NP]; NV],
) -> f64 {
    let mut seed = 11;
    let rows: Vec<[f64; NP]> = (0..12)
        .flat_map(|_| regressor(&draws(&mut seed), &draws(&mut seed), &draws(&mut seed)))
        .collect();
    let stacked = nalgebra::DMatrix::from_fn(rows.len(), NP, |i, j| rows[i][j]);
    let singular = stacked.singular_values();
    singular.min() / singular.max()
}

/// The base parameters are independent: none can be merged into the
/// others (with `Y π = τ` above, they are a basis of what motions tell);
/// the smallest relative singular values are 2e-3 to 0.3.
#[test]
fn base_parameters_are_independent() {
    assert!(independence(|q, v, a| ARM_BY_POINTS.regressor(q, v, a)) > 1e-5);
    assert!(independence(|q, v, a| TURNING_INPUTS.regressor(q, v, a)) > 1e-5);
    assert!(independence(|q, v, a| FULL_INERTIA.regressor(q, v, a)) > 1e-5);
    assert!(independence(|q, v, a| RATES_TOP.regressor(q, v, a)) > 1e-5);
}

/// One state of an independent SymPy reading of the language
/// (`dal_sympy.py --values` at the test's parameters, 30 digits, kept
/// outside this repository): `t`, `q`, `v`, `u`, and the `M` and `f` it
/// derives.
type SympyState = (f64, [f64; 2], [f64; 2], [f64; 1], [[f64; 2]; 2], [f64; 2]);

/// `FullInertia` without its outputs, read by SymPy.
const FULL_INERTIA_SYMPY: [SympyState; 2] = [
    (
        0.3,
        [0.7, -1.1],
        [1.3, -0.4],
        [0.8],
        [
            [0.26416310936186566, 0.10206722005121893],
            [0.10206722005121893, 0.13125],
        ],
        [-0.950607968011449, -1.3031689877263903],
    ),
    (
        -0.5,
        [-2.2, 0.9],
        [-0.6, 1.7],
        [-1.2],
        [
            [0.2717598081708933, -0.08665111088309363],
            [-0.08665111088309363, 0.13125],
        ],
        [0.5401780060333977, -3.6150070916547956],
    ),
];

/// `ShakenSprings` without its outputs and marker, read by SymPy.
const SHAKEN_SYMPY: [SympyState; 2] = [
    (
        0.3,
        [0.2, -1.1],
        [1.3, -0.4],
        [0.8],
        [
            [2.5, 0.19051037099874246],
            [0.19051037099874246, 0.29399999999999993],
        ],
        [-2.2051314398261215, 4.416008385938953],
    ),
    (
        1.7,
        [-0.4, 2.5],
        [-0.6, 1.7],
        [-1.2],
        [
            [2.5, -0.3364803185297121],
            [-0.3364803185297121, 0.29399999999999993],
        ],
        [4.605729003320435, -3.380736500713409],
    ),
];

/// `inverse_dynamics` is SymPy's `M v̇ − f`: the six-entry symbolic inertia
/// on a tilted axis, and the springs, the angle-dependent dampers and the
/// load that varies with time.
#[test]
fn inverse_dynamics_is_sympys_reading() {
    let vdot = [0.9, -1.4];
    let expected = |(_, _, _, _, mass, forcing): &SympyState| -> [f64; 2] {
        std::array::from_fn(|i| matrix_times(mass, &vdot)[i] - forcing[i])
    };
    for state in &FULL_INERTIA_SYMPY {
        let (t, q, v, u, ..) = *state;
        let tau = FULL_INERTIA.inverse_dynamics(t, &q, &v, &vdot, &u);
        assert_close("tilted body", &tau, &expected(state), 1e-13);
    }
    for state in &SHAKEN_SYMPY {
        let (t, q, v, u, ..) = *state;
        let tau = SHAKEN.inverse_dynamics(t, &q, &v, &vdot, &u);
        assert_close("springs and dampers", &tau, &expected(state), 1e-13);
    }
}
