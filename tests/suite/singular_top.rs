//! A heavy top in Z-X-Z Euler angles released upright (`θ = 0`): there the
//! precession `ψ` and the spin `φ` turn about the same axis, their columns
//! of `M` coincide, and `ψ̇ = −φ̇` moves no mass. The error says so — it
//! names both coordinates and suggests a quaternion joint or another
//! start — instead of blaming `phi` for having no inertia of its own. A
//! body that really has no inertia about an axis is still named alone.

use dalembert::integrate::{Integration, Rk4};
use dalembert::{DynamicsError, State, Unconstrained};

dalembert::dalembert! {
    /// A symmetric heavy top on a fixed point, Z-X-Z Euler angles.
    pub UprightTop {
        parameters m, h, I1, I3, g;
        coordinates psi, theta, phi;
        frame A = N.rotate_z(psi);
        frame B = A.rotate_x(theta);
        frame C = B.rotate_z(phi);
        body top { mass: m, center: O + h * C.z, frame: C, inertia: [I1, I1, I3] };
        gravity -g * N.z;
    }
}

dalembert::dalembert! {
    /// A slender rod turned about its own axis: no inertia about it.
    pub SpunRod {
        parameters m, l;
        coordinates a, b;
        frame A = N.rotate_z(a);
        frame B = A.rotate_x(b);
        body rod { mass: m, center: O, frame: B, inertia: [m*l^2/12, m*l^2/12, 0] };
    }
}

const TOP: UprightTop = UprightTop {
    m: 0.5,
    h: 0.04,
    I1: 2e-4,
    I3: 1e-4,
    g: 9.81,
};

fn names_psi_and_phi(error: &DynamicsError) {
    let DynamicsError::SingularMassMatrix { null_motion, .. } = error else {
        panic!("expected a singular mass matrix, got {error:?}");
    };
    assert_eq!(null_motion.names(), ["psi", "phi"], "{null_motion:?}");
    let [psi, phi] = [null_motion.weights()[0], null_motion.weights()[1]];
    assert!(
        (psi - 1.0).abs() < 1e-6 && (phi + 1.0).abs() < 1e-6,
        "{psi} {phi}"
    );
    let message = error.to_string();
    for expected in [
        "the columns of `psi` and `phi` are dependent",
        "+1.000 psi -1.000 phi",
        "turn about the same axis",
        "quaternion joint",
        "start elsewhere",
    ] {
        assert!(message.contains(expected), "{expected:?} not in: {message}");
    }
    assert!(!message.contains("no inertia of its own"), "{message}");
}

#[test]
fn the_upright_top_names_the_two_angles_that_turn_about_one_axis() {
    let q = [0.3, 0.0, -0.7];
    let error = dalembert::accelerations(&TOP, 0.0, &q, &[0.0, 0.1, 30.0], &[]).unwrap_err();
    names_psi_and_phi(&error);
    // The runtime's own Cholesky route says the same.
    let error = dalembert::__private::cholesky_accelerations(&TOP, 0.0, &q, &[0.0, 0.1, 30.0], &[])
        .unwrap_err();
    names_psi_and_phi(&error);
    // And an integration started there stops at its start with it.
    let start = State {
        t: 0.0,
        q,
        v: [0.0, 0.0, 30.0],
    };
    let stopped = Integration::new(
        &Unconstrained::without_inputs(&TOP),
        start,
        1.0,
        Rk4 { steps: 10 },
    )
    .run()
    .unwrap_err();
    assert_eq!(stopped.t, 0.0);
    assert!(stopped.to_string().contains("`psi` and `phi`"), "{stopped}");
}

#[test]
fn a_tilted_top_is_regular() {
    let q = [0.3, 0.2, -0.7];
    assert!(dalembert::accelerations(&TOP, 0.0, &q, &[0.0, 0.1, 30.0], &[]).is_ok());
}

#[test]
fn a_coordinate_that_moves_no_mass_is_named_alone() {
    let rod = SpunRod { m: 1.0, l: 1.0 };
    // At b = 0 the rod stands along N.z, about which `a` turns it: `a`
    // moves no mass.
    let error = dalembert::accelerations(&rod, 0.0, &[0.4, 0.0], &[1.0, 0.0], &[]).unwrap_err();
    let DynamicsError::SingularMassMatrix {
        coordinate,
        null_motion,
        ..
    } = error
    else {
        panic!("expected a singular mass matrix, got {error:?}");
    };
    assert_eq!(coordinate, "a");
    assert_eq!(null_motion.names(), ["a"]);
    let message = error.to_string();
    assert!(
        message.contains("coordinate `a` (index 0) has no inertia of its own"),
        "{message}"
    );
}
