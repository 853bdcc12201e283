//! The checks of the control outputs of `docs/language.md` ("Outputs") on
//! systems whose configuration is not a vector space (docs/architecture.md §4,
//! free and spherical joints), as an outside tester makes them: the kinematic
//! outputs of a point and a frame against central finite differences of
//! `position` and `rotation` along `integrate_configuration` (the tangent
//! space: one column per speed) and along `coordinate_rates`, their `… in F`
//! versions against the same vectors turned by `rotation(F)`,
//! `inverse_dynamics` against `M v̇ − f`, and `linearize` against central
//! differences of `accelerations` in the tangent space.

use dalembert::MultibodySystem;
use dalembert_fixtures::reference::assert_near;

dalembert::dalembert! {
    /// A body on a free joint placed away from `O`, carrying an arm on a
    /// hinge about its `y` axis, driven by a motor between the two.
    pub Flyer {
        parameters m, ma, l, g;
        inputs u;
        point P = O + 0.3 * N.x - 0.2 * N.y + 0.5 * N.z;
        joint free base { parent: N, child: B, at: P };
        coordinates a;
        frame C = B.rotate_y(a);
        point hinge = base + 0.1 * B.x + 0.05 * B.z;
        point tip = hinge + l * C.x - 0.1 * C.z;
        body b { mass: m, center: base + 0.02 * B.x - 0.03 * B.y + 0.01 * B.z, frame: B, inertia: [0.2, 0.3, 0.4, 0.01, -0.02, 0.03] };
        body arm { mass: ma, center: hinge + l / 2 * C.x, frame: C, inertia: [0.01, ma*l^2/12, ma*l^2/12] };
        gravity -g * N.z;
        torque u * B.y on C reacting B;
        outputs inverse_dynamics, linearize;
        outputs position(tip), velocity(tip), acceleration(tip), jacobian(tip);
        outputs rotation(B), rotation(C), angular_velocity(C), angular_jacobian(C);
        outputs position(tip in B), velocity(tip in B), acceleration(tip in B), jacobian(tip in B);
        outputs rotation(C in B), angular_velocity(C in B), angular_jacobian(C in B);
    }
}

dalembert::dalembert! {
    /// A bob on a spherical joint at the end of an arm turning about `N.z`.
    pub Swing {
        parameters m, ma, l, d, g;
        coordinates phi;
        inputs u;
        frame A = N.rotate_z(phi);
        point P = O + l * A.x;
        joint spherical ball { parent: A, child: B, at: P };
        point bob = ball - d * B.z + 0.1 * B.x;
        body arm { mass: ma, center: O + l / 2 * A.x, frame: A, inertia: [ma*l^2/100, ma*l^2/12, ma*l^2/12] };
        body weight { mass: m, center: bob, frame: B, inertia: [0.03, 0.05, 0.02, 0.004, 0, -0.003] };
        gravity -g * N.z;
        torque u * N.z on A;
        outputs inverse_dynamics, linearize;
        outputs position(bob), velocity(bob), acceleration(bob), jacobian(bob);
        outputs rotation(B), angular_velocity(B), angular_jacobian(B);
        outputs rotation(A), angular_velocity(A), angular_jacobian(A);
        outputs position(bob in B), velocity(bob in B), acceleration(bob in B), jacobian(bob in B);
        outputs rotation(A in B), angular_velocity(A in B), angular_jacobian(A in B);
    }
}

pub(crate) const FLYER: Flyer = Flyer {
    m: 1.7,
    ma: 0.6,
    l: 0.8,
    g: 9.81,
};
pub(crate) const SWING: Swing = Swing {
    m: 0.9,
    ma: 1.4,
    l: 0.8,
    d: 0.5,
    g: 9.81,
};
pub(crate) const STEP: f64 = 1e-5;
/// Central differences of step 1e-5: truncation ~1e-10, rounding ~1e-11.
pub(crate) const DIFFERENCES: f64 = 1e-8;

pub(crate) type Vec3 = [f64; 3];
pub(crate) type Mat3 = [[f64; 3]; 3];

/// The unit quaternion `(x, y, z, w)` of `raw`.
pub(crate) fn unit(raw: [f64; 4]) -> [f64; 4] {
    let norm = raw.iter().map(|x| x * x).sum::<f64>().sqrt();
    raw.map(|x| x / norm)
}

/// `(g(+h) − g(−h)) / 2h` of a vector function of the step.
pub(crate) fn central<const N: usize>(g: impl Fn(f64) -> [f64; N]) -> [f64; N] {
    let (plus, minus) = (g(STEP), g(-STEP));
    std::array::from_fn(|i| (plus[i] - minus[i]) / (2.0 * STEP))
}

pub(crate) fn unit_vector<const N: usize>(j: usize) -> [f64; N] {
    std::array::from_fn(|i| if i == j { 1.0 } else { 0.0 })
}

pub(crate) fn transpose_times(r: &Mat3, x: &Vec3) -> Vec3 {
    std::array::from_fn(|i| (0..3).map(|k| r[k][i] * x[k]).sum())
}

pub(crate) fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

pub(crate) fn transpose(a: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// The columns of a `3 × NV` matrix.
pub(crate) fn columns<const NV: usize>(m: &[[f64; NV]; 3]) -> [Vec3; NV] {
    std::array::from_fn(|j| [m[0][j], m[1][j], m[2][j]])
}

pub(crate) fn times<const NV: usize>(m: &[[f64; NV]; 3], v: &[f64; NV]) -> Vec3 {
    std::array::from_fn(|i| (0..NV).map(|j| m[i][j] * v[j]).sum())
}

pub(crate) fn assert_vec(what: &str, actual: &[f64], expected: &[f64], tol: f64) {
    assert_eq!(actual.len(), expected.len(), "{what}: length");
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        assert_near(&format!("{what}[{i}]"), *a, *e, tol);
    }
}

/// The angular velocity `ω` in `N`'s axes of a rotation `R(s)` through
/// `R(0)` with derivative `dR`: `[ω]× = dR R(0)ᵀ`.
pub(crate) fn angular_velocity(r: &Mat3, dr: &Mat3) -> Vec3 {
    let w = mat_mul(dr, &transpose(r));
    // Antisymmetric up to the differences' error: average the two halves.
    [
        (w[2][1] - w[1][2]) / 2.0,
        (w[0][2] - w[2][0]) / 2.0,
        (w[1][0] - w[0][1]) / 2.0,
    ]
}

pub(crate) fn flat(m: &Mat3) -> [f64; 9] {
    std::array::from_fn(|k| m[k / 3][k % 3])
}

/// The derivative of a rotation function along a path of the step.
pub(crate) fn rotation_rate(rotation: impl Fn(f64) -> Mat3) -> Mat3 {
    let d = central(|s| flat(&rotation(s)));
    std::array::from_fn(|i| std::array::from_fn(|j| d[3 * i + j]))
}

/// `(q, v, v̇)`.
pub(crate) type State<const NQ: usize, const NV: usize> = ([f64; NQ], [f64; NV], [f64; NV]);
pub(crate) type Acceleration<const NQ: usize, const NV: usize> =
    fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> Vec3;

/// A point's outputs (`position`, `velocity`, `acceleration`, `jacobian`),
/// in `N`'s axes or in a frame's.
pub(crate) struct Point<const NQ: usize, const NV: usize> {
    pub(crate) position: fn(&[f64; NQ]) -> Vec3,
    pub(crate) velocity: fn(&[f64; NQ], &[f64; NV]) -> Vec3,
    pub(crate) acceleration: Acceleration<NQ, NV>,
    pub(crate) jacobian: fn(&[f64; NQ]) -> [[f64; NV]; 3],
}

/// A frame's outputs (`rotation`, `angular_velocity`, `angular_jacobian`),
/// in `N`'s axes or in another frame's.
pub(crate) struct Frame<const NQ: usize, const NV: usize> {
    pub(crate) rotation: fn(&[f64; NQ]) -> Mat3,
    pub(crate) angular_velocity: fn(&[f64; NQ], &[f64; NV]) -> Vec3,
    pub(crate) angular_jacobian: fn(&[f64; NQ]) -> [[f64; NV]; 3],
}

/// `position` differentiated along `q ⊕ s e_j` (the jacobian's columns),
/// along `q ⊕ s v` and along `q + s q̇` with `q̇ = coordinate_rates(q, v)`
/// (the velocity), and `velocity` along the motion with `v̇` (the
/// acceleration); the velocity is also `J v`.
pub(crate) fn check_point<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    point: &Point<NQ, NV>,
    (q, v, vdot): State<NQ, NV>,
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    let along = |w: &[f64; NV], s: f64| system.integrate_configuration(&q, w, s);
    let jacobian = (point.jacobian)(&q);
    for (j, column) in columns(&jacobian).iter().enumerate() {
        let e = unit_vector(j);
        let expected = central(|s| (point.position)(&along(&e, s)));
        assert_vec(
            &format!("jacobian column {j}"),
            column,
            &expected,
            DIFFERENCES,
        );
    }
    let velocity = (point.velocity)(&q, &v);
    assert_vec("velocity = J v", &velocity, &times(&jacobian, &v), 1e-13);
    let tangent = central(|s| (point.position)(&along(&v, s)));
    assert_vec("velocity along q ⊕ s v", &velocity, &tangent, DIFFERENCES);
    let rates = system.coordinate_rates(&q, &v);
    let through_rates =
        central(|s| (point.position)(&std::array::from_fn(|i| q[i] + s * rates[i])));
    assert_vec(
        "velocity along q + s q̇",
        &velocity,
        &through_rates,
        DIFFERENCES,
    );
    // v(s) = v + s v̇; q(s) = q ⊕ s (v + s/2 v̇), the mean speed over [0, s].
    let moved = central(|s| {
        let mean: [f64; NV] = std::array::from_fn(|i| v[i] + s / 2.0 * vdot[i]);
        let speeds: [f64; NV] = std::array::from_fn(|i| v[i] + s * vdot[i]);
        (point.velocity)(&along(&mean, s), &speeds)
    });
    let acceleration = (point.acceleration)(&q, &v, &vdot);
    assert_vec("acceleration", &acceleration, &moved, DIFFERENCES);
}

/// `rotation` differentiated along `q ⊕ s e_j` (the angular jacobian's
/// columns) and along `q ⊕ s v` (the angular velocity, also `J v`).
pub(crate) fn check_frame<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    frame: &Frame<NQ, NV>,
    q: [f64; NQ],
    v: [f64; NV],
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    let along = |w: &[f64; NV], s: f64| system.integrate_configuration(&q, w, s);
    let rotation = (frame.rotation)(&q);
    let identity = mat_mul(&transpose(&rotation), &rotation);
    assert_vec("Rᵀ R", &flat(&identity), &flat(&unit_matrix()), 1e-14);
    let jacobian = (frame.angular_jacobian)(&q);
    for (j, column) in columns(&jacobian).iter().enumerate() {
        let e = unit_vector(j);
        let expected = angular_velocity(
            &rotation,
            &rotation_rate(|s| (frame.rotation)(&along(&e, s))),
        );
        assert_vec(
            &format!("angular jacobian column {j}"),
            column,
            &expected,
            DIFFERENCES,
        );
    }
    let omega = (frame.angular_velocity)(&q, &v);
    assert_vec("ω = J v", &omega, &times(&jacobian, &v), 1e-13);
    let expected = angular_velocity(
        &rotation,
        &rotation_rate(|s| (frame.rotation)(&along(&v, s))),
    );
    assert_vec("angular velocity", &omega, &expected, DIFFERENCES);
}

pub(crate) fn unit_matrix() -> Mat3 {
    std::array::from_fn(unit_vector)
}

/// A `3 × NV` matrix's columns in `F`'s axes (`r` = `rotation(F)`), row by row.
pub(crate) fn jacobian_in<const NV: usize>(r: &Mat3, m: &[[f64; NV]; 3]) -> Vec<f64> {
    let turned = columns(m).map(|c| transpose_times(r, &c));
    (0..3 * NV).map(|k| turned[k % NV][k / NV]).collect()
}

/// `inverse_dynamics = M v̇ − f`.
pub(crate) fn check_inverse_dynamics<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    inverse_dynamics: impl Fn(&[f64; NQ], &[f64; NV], &[f64; NV], &[f64; NU]) -> [f64; NV],
    (q, v, vdot): State<NQ, NV>,
    u: [f64; NU],
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    let mass = system.mass_matrix(&q);
    let forcing = system.forcing(0.0, &q, &v, &u);
    let expected: [f64; NV] =
        std::array::from_fn(|i| (0..NV).map(|j| mass[i][j] * vdot[j]).sum::<f64>() - forcing[i]);
    assert_vec(
        "inverse dynamics",
        &inverse_dynamics(&q, &v, &vdot, &u),
        &expected,
        1e-12,
    );
}

/// `linearize` at `(q, v, u)`: `A = [[K, I], [∂v̇/∂δ, ∂v̇/∂v]]` and
/// `B = [[0], [∂v̇/∂u]]`, the partials by central differences of
/// `accelerations` along `q ⊕ s e_j`, `v + s e_j` and `u + s e_k`, and `K`
/// the kinematic rows `δ̇ = δν − ad(ν̄) δ` given (zero at rest).
pub(crate) fn check_linearize<
    S,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const N2: usize,
>(
    system: &S,
    (a, b): ([[f64; N2]; N2], [[f64; NU]; N2]),
    (q, v, u): ([f64; NQ], [f64; NV], [f64; NU]),
    kinematic: [[f64; NV]; NV],
) where
    S: MultibodySystem<NQ, NV, NU>,
{
    assert_eq!(N2, 2 * NV);
    let accelerations = |q: &[f64; NQ], v: &[f64; NV], u: &[f64; NU]| {
        system
            .accelerations(0.0, q, v, u)
            .expect("a regular mass matrix")
    };
    for j in 0..NV {
        let e: [f64; NV] = unit_vector(j);
        let by_q = central(|s| accelerations(&system.integrate_configuration(&q, &e, s), &v, &u));
        let by_v = central(|s| accelerations(&q, &std::array::from_fn(|i| v[i] + s * e[i]), &u));
        for i in 0..NV {
            assert_near(&format!("A[{i}][{j}]"), a[i][j], kinematic[i][j], 1e-15);
            assert_near(&format!("A[{i}][{}]", NV + j), a[i][NV + j], e[i], 0.0);
            let (row, by_q, by_v) = (&a[NV + i], by_q[i], by_v[i]);
            assert_near(&format!("A[{}][{j}]", NV + i), row[j], by_q, DIFFERENCES);
            assert_near(
                &format!("A[{}][{}]", NV + i, NV + j),
                row[NV + j],
                by_v,
                DIFFERENCES,
            );
        }
    }
    for (k, e) in (0..NU).map(|k| (k, unit_vector::<NU>(k))) {
        let by_u = central(|s| accelerations(&q, &v, &std::array::from_fn(|i| u[i] + s * e[i])));
        for i in 0..NV {
            assert_near(&format!("B[{i}][{k}]"), b[i][k], 0.0, 0.0);
            assert_near(
                &format!("B[{}][{k}]", NV + i),
                b[NV + i][k],
                by_u[i],
                DIFFERENCES,
            );
        }
    }
}

/// Writes `−[x]×` into the 3 × 3 block of `k` at `(row, column)`.
pub(crate) fn minus_cross(k: &mut [[f64; 7]; 7], (row, column): (usize, usize), x: &[f64]) {
    let cross = [[0.0, -x[2], x[1]], [x[2], 0.0, -x[0]], [-x[1], x[0], 0.0]];
    for i in 0..3 {
        for j in 0..3 {
            k[row + i][column + j] = -cross[i][j];
        }
    }
}

/// A state of the flyer: `(q, v, v̇)`, the coordinates in `COORDINATES`' order.
pub(crate) fn flyer_state() -> ([f64; 8], [f64; 7], [f64; 7]) {
    let [qx, qy, qz, qw] = unit([0.3, -0.5, 0.2, 0.8]);
    (
        [0.4, -0.7, 1.1, qx, qy, qz, qw, 0.6],
        [0.5, -0.3, 0.8, 1.2, -0.7, 0.4, -0.9],
        [-0.6, 0.9, 0.2, -1.1, 0.5, 0.8, 1.3],
    )
}

pub(crate) fn swing_state() -> ([f64; 5], [f64; 4], [f64; 4]) {
    let [qx, qy, qz, qw] = unit([-0.4, 0.3, 0.6, 0.7]);
    (
        [0.8, qx, qy, qz, qw],
        [0.9, -1.1, 0.6, 0.7],
        [-0.4, 1.2, -0.8, 0.5],
    )
}

/// A point's outputs of a system constant, by their method names.
macro_rules! point {
    ($system:ident, $position:ident, $velocity:ident, $acceleration:ident, $jacobian:ident) => {
        Point {
            position: |q| $system.$position(0.0, q),
            velocity: |q, v| $system.$velocity(0.0, q, v),
            acceleration: |q, v, vdot| $system.$acceleration(0.0, q, v, vdot),
            jacobian: |q| $system.$jacobian(0.0, q),
        }
    };
}

/// A frame's outputs of a system constant, by their method names.
macro_rules! frame {
    ($system:ident, $rotation:ident, $angular_velocity:ident, $angular_jacobian:ident) => {
        Frame {
            rotation: |q| $system.$rotation(0.0, q),
            angular_velocity: |q, v| $system.$angular_velocity(0.0, q, v),
            angular_jacobian: |q| $system.$angular_jacobian(0.0, q),
        }
    };
}

pub(crate) fn flyer_tip() -> Point<8, 7> {
    point!(
        FLYER,
        position_tip,
        velocity_tip,
        acceleration_tip,
        jacobian_tip
    )
}

pub(crate) fn flyer_tip_in_b() -> Point<8, 7> {
    point!(
        FLYER,
        position_tip_in_B,
        velocity_tip_in_B,
        acceleration_tip_in_B,
        jacobian_tip_in_B
    )
}

pub(crate) fn flyer_c() -> Frame<8, 7> {
    frame!(FLYER, rotation_C, angular_velocity_C, angular_jacobian_C)
}

pub(crate) fn flyer_c_in_b() -> Frame<8, 7> {
    frame!(
        FLYER,
        rotation_C_in_B,
        angular_velocity_C_in_B,
        angular_jacobian_C_in_B
    )
}

pub(crate) fn swing_bob() -> Point<5, 4> {
    point!(
        SWING,
        position_bob,
        velocity_bob,
        acceleration_bob,
        jacobian_bob
    )
}

pub(crate) fn swing_bob_in_b() -> Point<5, 4> {
    point!(
        SWING,
        position_bob_in_B,
        velocity_bob_in_B,
        acceleration_bob_in_B,
        jacobian_bob_in_B
    )
}

pub(crate) fn swing_b() -> Frame<5, 4> {
    frame!(SWING, rotation_B, angular_velocity_B, angular_jacobian_B)
}

pub(crate) fn swing_a() -> Frame<5, 4> {
    frame!(SWING, rotation_A, angular_velocity_A, angular_jacobian_A)
}

pub(crate) fn swing_a_in_b() -> Frame<5, 4> {
    frame!(
        SWING,
        rotation_A_in_B,
        angular_velocity_A_in_B,
        angular_jacobian_A_in_B
    )
}

/// `name(P in F)` is `name(P)` in `F`'s axes: `R_Fᵀ x` for a vector,
/// each column turned for a jacobian, `R_Fᵀ R_B` for `rotation(B in F)`.
pub(crate) fn check_in_frame<const NQ: usize, const NV: usize>(
    (q, v, vdot): State<NQ, NV>,
    rotation_f: fn(&[f64; NQ]) -> Mat3,
    (point, point_in): (&Point<NQ, NV>, &Point<NQ, NV>),
    (frame, frame_in): (&Frame<NQ, NV>, &Frame<NQ, NV>),
) {
    let r = rotation_f(&q);
    let turned = |x: Vec3| transpose_times(&r, &x).to_vec();
    let checks: [(&str, Vec<f64>, Vec<f64>); 7] = [
        (
            "position",
            (point_in.position)(&q).to_vec(),
            turned((point.position)(&q)),
        ),
        (
            "velocity",
            (point_in.velocity)(&q, &v).to_vec(),
            turned((point.velocity)(&q, &v)),
        ),
        (
            "acceleration",
            (point_in.acceleration)(&q, &v, &vdot).to_vec(),
            turned((point.acceleration)(&q, &v, &vdot)),
        ),
        (
            "jacobian",
            (point_in.jacobian)(&q).concat(),
            jacobian_in(&r, &(point.jacobian)(&q)),
        ),
        (
            "rotation",
            flat(&(frame_in.rotation)(&q)).to_vec(),
            flat(&mat_mul(&transpose(&r), &(frame.rotation)(&q))).to_vec(),
        ),
        (
            "angular velocity",
            (frame_in.angular_velocity)(&q, &v).to_vec(),
            turned((frame.angular_velocity)(&q, &v)),
        ),
        (
            "angular jacobian",
            (frame_in.angular_jacobian)(&q).concat(),
            jacobian_in(&r, &(frame.angular_jacobian)(&q)),
        ),
    ];
    for (what, actual, expected) in checks {
        assert_vec(&format!("{what} in F"), &actual, &expected, 1e-14);
    }
}
