//! Wheels that roll, written with the `rolling` statement and the vector
//! functions of expressions, against SymPy's `KanesMethod` on the same
//! systems built independently (`scripts/rolling_wheels_reference.py`,
//! `tests/reference/rolling_wheels.json`): a disc and a torus rolling on a
//! plane, a Chaplygin sleigh, a differential-drive robot and a
//! two-wheeled self-balancing robot.
//!
//! At random states (random `q`, `v`, inputs) `M`, `f`, `A`, `b` and the
//! residual agree to 1e-12; at states on the constraint manifold the
//! constrained accelerations agree with those of `KanesMethod` with the
//! rows as configuration and velocity constraints (its dependent speeds);
//! and the self-balancing robot's `linearize` about upright motion at a
//! forward speed gives SymPy's `Linearizer`'s reduced `A` (1e-12) and its
//! eigenvalues (1e-10).

use dalembert::ConstrainedSystem;
use dalembert::constrained::constrained_accelerations;
use dalembert_fixtures::balancing_robot::{BALANCING_ROBOT, BalancingRobot, INDEPENDENT, upright};
use dalembert_fixtures::reference::{array, assert_close, flat, matrix, reference};
use nalgebra::SMatrix;
use serde_json::Value;

/// `[("m", SYSTEM.m), ...]`: the named parameters' values.
macro_rules! values {
    ($system:expr; $($parameter:ident),+) => {
        [$((stringify!($parameter), $system.$parameter)),+]
    };
}

dalembert::dalembert! {
    /// A thin disc rolling on `z = 0`, its centre `G` at `(x, y, z)`,
    /// driven by a torque `T` about its axle.
    pub Disc {
        parameters m, r, g;
        coordinates x, y, z, psi, theta, phi;
        inputs T;
        frame A = N.rotate_z(psi);
        frame C = A.rotate_x(theta);
        frame B = C.rotate_y(phi);
        point G = O + x * N.x + y * N.y + z * N.z;
        body disc { mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] };
        gravity -g * N.z;
        torque T * C.y on B;
        rolling contact { wheel: B, axle: B.y, center: G, radius: r, plane: N.z };
    }
}

dalembert::dalembert! {
    /// A torus (tire radius `rt`) rolling on the plane `z = h`, with a
    /// viscous drag on its centre.
    pub Torus {
        parameters m, r, g, rt, h, c, Ia, Id;
        coordinates x, y, z, psi, theta, phi;
        inputs T;
        frame A = N.rotate_z(psi);
        frame C = A.rotate_x(theta);
        frame B = C.rotate_y(phi);
        point G = O + x * N.x + y * N.y + z * N.z;
        body torus { mass: m, center: G, frame: B, inertia: [Id, Ia, Id] };
        gravity -g * N.z;
        force -c * velocity(G) at G;
        torque T * C.y on B;
        rolling contact { wheel: B, axle: B.y, center: G, radius: r, plane: N.z, tire: rt, through: O + h * N.z };
    }
}

dalembert::dalembert! {
    /// A Chaplygin sleigh: the blade at `P` does not slip sideways, the
    /// centre of mass `a` ahead, a spring to `O`, a push `F`, a turn `T`.
    pub Sleigh {
        parameters m, I, a, k;
        coordinates x, y, theta;
        inputs F, T;
        frame B = N.rotate_z(theta);
        point P = O + x * N.x + y * N.y;
        body sleigh { mass: m, center: P + a * B.x, frame: B, inertia: [0, 0, I] };
        potential k / 2 * dot(P + a * B.x - O, P + a * B.x - O);
        force F * B.x at P;
        torque T * N.z on B;
        constraint dot(velocity(P), B.y) == 0;
    }
}

dalembert::dalembert! {
    /// A differential-drive robot: a level chassis (centre `b` ahead of
    /// the axle) on two driven wheels, each a `rolling` contact (their
    /// contact rows vanish and their sideways rows coincide: six rows of
    /// rank three).
    pub DifferentialDrive {
        parameters mb, mw, Iwa, Iwd, r, d, g, b, Ib;
        coordinates x, y, psi, phiL, phiR;
        inputs TL, TR;
        frame A = N.rotate_z(psi);
        frame WL = A.rotate_y(phiL);
        frame WR = A.rotate_y(phiR);
        point G0 = O + x * N.x + y * N.y + r * N.z;
        point PL = G0 + d * A.y;
        point PR = G0 - d * A.y;
        body chassis { mass: mb, center: G0 + b * A.x, frame: A, inertia: [Ib/2, Ib/2, Ib] };
        body left { mass: mw, center: PL, frame: WL, inertia: [Iwd, Iwa, Iwd] };
        body right { mass: mw, center: PR, frame: WR, inertia: [Iwd, Iwa, Iwd] };
        gravity -g * N.z;
        torque TL * A.y on WL reacting A;
        torque TR * A.y on WR reacting A;
        rolling left_contact { wheel: WL, axle: WL.y, center: PL, radius: r, plane: N.z };
        rolling right_contact { wheel: WR, axle: WR.y, center: PR, radius: r, plane: N.z };
    }
}

const DISC: Disc = Disc {
    m: 0.8,
    r: 0.3,
    g: 9.81,
};

const TORUS: Torus = Torus {
    m: 0.8,
    r: 0.3,
    g: 9.81,
    rt: 0.05,
    h: 0.2,
    c: 0.15,
    Ia: 0.04,
    Id: 0.025,
};

const SLEIGH: Sleigh = Sleigh {
    m: 2.5,
    I: 0.3,
    a: 0.4,
    k: 1.7,
};

const DIFFERENTIAL_DRIVE: DifferentialDrive = DifferentialDrive {
    mb: 12.0,
    mw: 1.1,
    Iwa: 0.012,
    Iwd: 0.007,
    r: 0.15,
    d: 0.25,
    g: 9.81,
    b: 0.12,
    Ib: 0.6,
};

/// The reference entry of `system`, its parameters checked against ours.
fn system(name: &str, parameters: &[(&str, f64)]) -> Value {
    let entry = reference("rolling_wheels.json")["systems"][name].clone();
    for (parameter, value) in parameters {
        assert_eq!(
            entry["parameters"][*parameter].as_f64(),
            Some(*value),
            "{name}.{parameter}"
        );
    }
    entry
}

/// The reference's `rows` (of `A`, `b` or the residual) with a `zero` row
/// inserted at each of our rows that vanishes identically (a wheel's
/// contact on a level axle at height `r`): SymPy's models leave out the
/// rows that say `0 = 0`, each `rolling` statement keeps its three.
fn with_vanishing_rows(rows: &Value, zero: &Value, vanishing: &[bool]) -> Value {
    let mut given = rows.as_array().expect("rows").iter();
    let rows: Vec<Value> = vanishing
        .iter()
        .map(|&vanishes| match vanishes {
            true => zero.clone(),
            false => given.next().expect("a reference row").clone(),
        })
        .collect();
    assert!(given.next().is_none(), "reference rows left over");
    Value::from(rows)
}

/// `M`, `f`, `A`, `b` and the residual at every stored state, to 1e-12
/// (zero in the rows of `S::VANISHING_ROWS`); then the constrained
/// accelerations at the manifold's states.
fn agrees_with_sympy<S, const NQ: usize, const NU: usize, const NC: usize>(
    system: &S,
    entry: &Value,
) where
    S: ConstrainedSystem<NQ, NQ, NU, NC>,
{
    let zero_row = Value::from(vec![0.0; NQ]);
    let vanishing =
        |rows: &Value, zero: &Value| with_vanishing_rows(rows, zero, &S::VANISHING_ROWS);
    let states = entry["states"].as_array().expect("states");
    assert!(!states.is_empty(), "no reference states");
    for state in states {
        let (q, v, u) = (
            array::<NQ>(&state["q"]),
            array(&state["v"]),
            array(&state["u"]),
        );
        let mass: [[f64; NQ]; NQ] = matrix(&state["M"]);
        assert_close("M", &flat(&system.mass_matrix(&q)), &flat(&mass), 1e-12);
        let forcing: [f64; NQ] = array(&state["f"]);
        assert_close("f", &system.forcing(0.0, &q, &v, &u), &forcing, 1e-12);
        let jacobian: [[f64; NQ]; NC] = matrix(&vanishing(&state["A"], &zero_row));
        assert_close(
            "A",
            &flat(&system.constraint_jacobian(&q)),
            &flat(&jacobian),
            1e-12,
        );
        let bias: [f64; NC] = array(&vanishing(&state["b"], &Value::from(0.0)));
        assert_close("b", &system.constraint_bias(0.0, &q, &v), &bias, 1e-12);
        let residual: [f64; NC] = array(&vanishing(&state["residual"], &Value::from(0.0)));
        let scale = q.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (ours, theirs) in system.constraint_residual(0.0, &q).iter().zip(residual) {
            assert!(
                (ours - theirs).abs() < 1e-12 * scale,
                "residual {ours} vs {theirs}"
            );
        }
    }
    let constrained = entry["constrained"].as_array().expect("constrained states");
    assert!(!constrained.is_empty(), "no states on the manifold");
    for state in constrained {
        let (q, v, u) = (
            array::<NQ>(&state["q"]),
            array(&state["v"]),
            array(&state["u"]),
        );
        let drift = system.constraint_velocity(0.0, &q, &v);
        assert!(
            drift.iter().all(|d| d.abs() < 1e-12),
            "off the manifold: {drift:?}"
        );
        let (vdot, _) = constrained_accelerations(system, 0.0, &q, &v, &u).expect("solvable");
        let expected: [f64; NQ] = array(&state["vdot"]);
        assert_close("v̇", &vdot, &expected, 1e-11);
    }
}

#[test]
fn a_disc_rolls_as_sympys() {
    assert_eq!(Disc::NC, 3);
    assert_eq!(
        <Disc as ConstrainedSystem<6, 6, 1, 3>>::VANISHING_ROWS,
        [false; 3]
    );
    let entry = system("disc", &values!(DISC; m, r, g));
    agrees_with_sympy(&DISC, &entry);
}

#[test]
fn a_torus_rolls_as_sympys() {
    let entry = system("torus", &values!(TORUS; m, r, g, rt, h, c, Ia, Id));
    agrees_with_sympy(&TORUS, &entry);
}

#[test]
fn a_chaplygin_sleigh_slides_as_sympys() {
    let entry = system("sleigh", &values!(SLEIGH; m, I, a, k));
    agrees_with_sympy(&SLEIGH, &entry);
}

#[test]
fn a_differential_drive_robot_rolls_as_sympys() {
    // Three rows per wheel; each wheel's contact row vanishes (the axle is
    // level at height r), and its two sideways rows coincide: six rows of
    // rank three.
    assert_eq!(DifferentialDrive::NC, 6);
    assert_eq!(
        <DifferentialDrive as ConstrainedSystem<5, 5, 2, 6>>::VANISHING_ROWS,
        [true, false, false, true, false, false]
    );
    let robot = DIFFERENTIAL_DRIVE;
    let entry = system(
        "differential_drive",
        &values!(robot; mb, mw, Iwa, Iwd, r, d, g, b, Ib),
    );
    agrees_with_sympy(&robot, &entry);
}

/// The robot's parameters as the reference names them.
fn balancing_entry() -> Value {
    let robot = BALANCING_ROBOT;
    system(
        "balancing_robot",
        &values!(robot; mb, mw, Iwa, Iwd, r, d, g, l, Ibx, Iby, Ibz),
    )
}

#[test]
fn a_self_balancing_robot_rolls_as_sympys() {
    // The left wheel's three rows (its contact vanishing), then the right
    // wheel's forward row.
    assert_eq!(
        <BalancingRobot as ConstrainedSystem<6, 6, 2, 4>>::VANISHING_ROWS,
        [true, false, false, false]
    );
    agrees_with_sympy(&BALANCING_ROBOT, &balancing_entry());
}

/// Eigenvalues of a 9 × 9 matrix, largest magnitude first, with those
/// below `1e-6` (the zeros of Jordan blocks, which an eigensolver returns
/// as `±√ε`) dropped.
fn nonzero_eigenvalues(a: &[[f64; 9]; 9]) -> Vec<(f64, f64)> {
    let mut eigenvalues: Vec<(f64, f64)> = SMatrix::<f64, 9, 9>::from_fn(|i, j| a[i][j])
        .complex_eigenvalues()
        .iter()
        .filter(|z| z.norm() > 1e-6)
        .map(|z| (z.re, z.im))
        .collect();
    eigenvalues.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1.total_cmp(&q.1)));
    eigenvalues
}

#[test]
fn upright_motion_linearises_as_sympys_linearizer() {
    let entry = balancing_entry();
    let points = entry["linearization"].as_array().expect("linearizations");
    assert!(!points.is_empty(), "no linearization points");
    for point in points {
        let speed = point["speed"].as_f64().expect("speed");
        let (q, v) = upright(speed);
        assert_eq!((q, v), (array(&point["q"]), array(&point["v"])));
        let (a, _) = BALANCING_ROBOT
            .linearize(0.0, &q, &v, &[0.0; 2])
            .expect("linearisable");
        let reduced = INDEPENDENT.map(|i| INDEPENDENT.map(|j| a[i][j]));
        let expected: [[f64; 9]; 9] = matrix(&point["reduced_A"]);
        assert_close("reduced A", &flat(&reduced), &flat(&expected), 1e-12);
        let theirs: Vec<(f64, f64)> = {
            let mut all: Vec<(f64, f64)> = point["eigenvalues"]
                .as_array()
                .expect("eigenvalues")
                .iter()
                .map(|z| (z[0].as_f64().expect("re"), z[1].as_f64().expect("im")))
                .filter(|(re, im)| re.hypot(*im) > 1e-6)
                .collect();
            all.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1.total_cmp(&q.1)));
            all
        };
        let ours = nonzero_eigenvalues(&reduced);
        assert!(!theirs.is_empty(), "no nonzero eigenvalue at {speed} m/s");
        assert_eq!(
            ours.len(),
            theirs.len(),
            "at {speed} m/s: {ours:?} vs {theirs:?}"
        );
        for ((re, im), (their_re, their_im)) in ours.iter().zip(&theirs) {
            let scale = their_re.hypot(*their_im);
            assert!(
                (re - their_re).abs() <= 1e-10 * scale && (im - their_im).abs() <= 1e-10 * scale,
                "at {speed} m/s: {re} + {im}i vs {their_re} + {their_im}i"
            );
        }
    }
}
