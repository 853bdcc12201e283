//! A `rolling` statement whose contact row vanishes identically: the thin
//! disc of `tests/suite/rolling_disc.rs` with its centre placed from the contact
//! point, `G = (x, y, 0) + r C.z`, so that the contact's height,
//! `G·N.z − r √(1 − (N.z·C.y)²) = r cos θ − r cos θ` (`1 − sin²θ = cos²θ`,
//! positive at the start), is zero in every configuration the disc can
//! roll through. The statement still adds its three rows:
//! `NC = 3`, the first a zero row (Jacobian, bias, residual and velocity
//! form zero), which the generated system lists in `VANISHING_ROWS` and
//! the solvers treat as absent.
//!
//! Its equations are checked against the same disc written with the
//! contact's height `z` as a coordinate (`HeightDisc`, whose contact row
//! `z = 0` is live): the no-slip rows, the constrained accelerations (by
//! the default rank-revealing solver, by the Schur complement, which
//! stops at a dependent row, and by the sparse solver) and `linearize` on
//! the manifold agree, and
//! the linearisation about upright rolling has the closed-form rows of
//! `tests/suite/rolling_disc.rs` (`θ̈ = 4/5 (g/r) θ + 6/5 Ω ψ̇`, `ψ̈ = −2 Ω θ̇`).

use dalembert::ConstrainedSystem;
use dalembert::constrained::{ConstraintSolver, constrained_accelerations};
use dalembert_fixtures::reference::{assert_close, assert_near_all, flat};

dalembert::dalembert! {
    /// A thin disc whose centre is placed from its contact point.
    pub PlacedDisc {
        parameters m, r, g;
        coordinates x, y, psi, theta, phi;
        frame A = N.rotate_z(psi);
        frame C = A.rotate_x(theta);
        frame B = C.rotate_y(phi);
        point G = O + x * N.x + y * N.y + r * C.z;
        body disc { mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] };
        gravity -g * N.z;
        rolling contact { wheel: B, axle: B.y, center: G, radius: r, plane: N.z };
        outputs linearize(x, y, psi, theta, phi; dt(psi), dt(theta), dt(phi));
    }
}

dalembert::dalembert! {
    /// The same disc with the contact's height `z` a coordinate.
    pub HeightDisc {
        parameters m, r, g;
        coordinates x, y, z, psi, theta, phi;
        frame A = N.rotate_z(psi);
        frame C = A.rotate_x(theta);
        frame B = C.rotate_y(phi);
        point G = O + x * N.x + y * N.y + z * N.z + r * C.z;
        body disc { mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] };
        gravity -g * N.z;
        rolling contact { wheel: B, axle: B.y, center: G, radius: r, plane: N.z };
        outputs linearize(x, y, psi, theta, phi; dt(psi), dt(theta), dt(phi));
    }
}

const PLACED: PlacedDisc = PlacedDisc {
    m: 0.8,
    r: 0.3,
    g: 9.81,
};

const HEIGHT: HeightDisc = HeightDisc {
    m: 0.8,
    r: 0.3,
    g: 9.81,
};

/// `HeightDisc`'s coordinates (or speeds) of `PlacedDisc`'s: `z = 0`.
fn with_height(q: [f64; 5]) -> [f64; 6] {
    [q[0], q[1], 0.0, q[2], q[3], q[4]]
}

/// `PlacedDisc`'s entries of `HeightDisc`'s: `z` dropped.
fn without_height(q: [f64; 6]) -> [f64; 5] {
    [q[0], q[1], q[3], q[4], q[5]]
}

/// States on the manifold, leaning and turning: the speeds of `ψ`, `θ`,
/// `φ` given, `ẋ = r φ̇ cos ψ`, `ẏ = r φ̇ sin ψ`.
fn rolling_states() -> Vec<([f64; 5], [f64; 5])> {
    [
        ([0.3, -0.2, 0.7, 0.4, 1.1], [0.9, -0.5, 4.0]),
        ([-1.0, 2.0, -2.1, -0.6, 0.2], [-1.3, 0.8, -7.5]),
        ([0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 5.0]),
    ]
    .into_iter()
    .map(
        |(q, [psi_rate, theta_rate, phi_rate]): ([f64; 5], [f64; 3])| {
            let rolling = PLACED.r * phi_rate;
            let v = [
                rolling * q[2].cos(),
                rolling * q[2].sin(),
                psi_rate,
                theta_rate,
                phi_rate,
            ];
            (q, v)
        },
    )
    .collect()
}

#[test]
fn the_contact_row_is_kept_as_a_zero_row() {
    assert_eq!(PlacedDisc::NC, 3);
    assert_eq!(
        <PlacedDisc as ConstrainedSystem<5, 5, 0, 3>>::VANISHING_ROWS,
        [true, false, false]
    );
    assert_eq!(
        <HeightDisc as ConstrainedSystem<6, 6, 0, 3>>::VANISHING_ROWS,
        [false; 3]
    );
    // Off the manifold too: the rows are functions of the whole state.
    let (q, v) = ([0.4, -1.2, 2.3, 0.5, -0.8], [0.3, -0.7, 1.1, 0.6, 2.0]);
    let t = 0.0;
    let jacobian = PLACED.constraint_jacobian(&q);
    assert_eq!(jacobian[0], [0.0; 5]);
    for values in [
        PLACED.constraint_bias(t, &q, &v),
        PLACED.constraint_residual(t, &q),
        PLACED.constraint_velocity(t, &q, &v),
    ] {
        assert_eq!(values[0], 0.0);
    }
    // The no-slip rows are the height disc's, without `z`'s column.
    let (qh, vh) = (with_height(q), with_height(v));
    let theirs = HEIGHT.constraint_jacobian(&qh);
    for row in 1..3 {
        assert_close(
            "no-slip row",
            &jacobian[row],
            &without_height(theirs[row]),
            1e-14,
        );
    }
    assert_close(
        "no-slip bias",
        &PLACED.constraint_bias(t, &q, &v)[1..],
        &HEIGHT.constraint_bias(t, &qh, &vh)[1..],
        1e-14,
    );
}

#[test]
fn accelerations_are_the_height_discs() {
    let states = rolling_states();
    assert!(!states.is_empty());
    for (q, v) in states {
        let (vdot, multipliers) =
            constrained_accelerations(&PLACED, 0.0, &q, &v, &[]).expect("solvable");
        assert_eq!(multipliers[0], 0.0, "the zero row carries no force");
        let (theirs, _) =
            constrained_accelerations(&HEIGHT, 0.0, &with_height(q), &with_height(v), &[])
                .expect("solvable");
        assert_near_all("v̇", &vdot, &without_height(theirs), 1e-12);
        let (by_schur, _) = ConstraintSolver::SchurComplement
            .accelerations(&PLACED, 0.0, &q, &v, &[])
            .expect("the zero row is not a dependent row");
        assert_near_all("v̇ by the Schur complement", &by_schur, &vdot, 1e-12);
        let (by_sparse, _) = ConstraintSolver::Sparse
            .accelerations(&PLACED, 0.0, &q, &v, &[])
            .expect("solvable");
        // The sparse solver's stiff factorisation: about 1e-9 relative.
        assert_near_all("v̇ by the sparse solver", &by_sparse, &vdot, 1e-7);
    }
}

#[test]
fn linearize_is_the_height_discs() {
    // Independent entries: every coordinate (and `z` for the height disc),
    // the speeds of ψ, θ, φ.
    let placed_independent = [0, 1, 2, 3, 4, 7, 8, 9];
    let height_independent = [0, 1, 3, 4, 5, 9, 10, 11];
    let states = rolling_states();
    assert!(!states.is_empty());
    for (q, v) in states {
        let (a, b) = PLACED.linearize(0.0, &q, &v, &[]).expect("linearisable");
        let (theirs, _) = HEIGHT
            .linearize(0.0, &with_height(q), &with_height(v), &[])
            .expect("linearisable");
        let ours = placed_independent.map(|i| placed_independent.map(|j| a[i][j]));
        let expected = height_independent.map(|i| height_independent.map(|j| theirs[i][j]));
        assert_near_all("reduced A", &flat(&ours), &flat(&expected), 1e-11);
        assert!(b.iter().all(|row| row.is_empty()));
    }
}

/// About upright rolling at the spin rate `Ω`: `θ̈ = 4/5 (g/r) θ + 6/5 Ω ψ̇`
/// and `ψ̈ = −2 Ω θ̇` (the closed form of `tests/suite/rolling_disc.rs`), `φ̈ = 0`.
#[test]
fn upright_rolling_has_the_closed_form_rows() {
    let (theta, psi_rate, theta_rate, phi_rate) = (3, 7, 8, 9);
    for (psi, omega) in [(0.0_f64, 5.0), (0.7, -2.0), (-2.5, 12.0)] {
        let rolling = PLACED.r * omega;
        let q = [0.4, -1.2, psi, 0.0, 2.0];
        let v = [rolling * psi.cos(), rolling * psi.sin(), 0.0, 0.0, omega];
        let (a, _) = PLACED.linearize(0.0, &q, &v, &[]).expect("linearisable");
        let mut lean = [0.0; 10];
        lean[theta] = 0.8 * PLACED.g / PLACED.r;
        lean[psi_rate] = 1.2 * omega;
        let mut heading = [0.0; 10];
        heading[theta_rate] = -2.0 * omega;
        assert_close("θ̈ row", &a[theta_rate], &lean, 1e-12);
        assert_close("ψ̈ row", &a[psi_rate], &heading, 1e-12);
        assert_near_all("φ̈ row", &a[phi_rate], &[0.0; 10], 1e-12);
    }
}
