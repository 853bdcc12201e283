//! Generated systems given NaN or infinite parameters or states: every
//! runtime solver returns an error instead of propagating NaN, and
//! `energy`, a plain `f64` diagnostic, returns a non-finite value (never a
//! finite wrong one).

use dalembert::constrained::{constrained_accelerations, project_onto_constraints};
use dalembert::integrate::Failure;
use dalembert::{
    Constrained, DynamicsError, Stabilisation, State, Unconstrained, accelerations, energy,
    integrate,
};

use dalembert_fixtures::seeds::{ConstrainedPendulum, DoublePendulum};

const BAD: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

#[test]
fn non_finite_parameters_are_errors() {
    for bad in BAD {
        let pendulum = DoublePendulum {
            m: 1.0,
            L: bad,
            g: 9.81,
        };
        let (q, qd) = ([0.3, -0.4], [0.5, 0.1]);
        assert_eq!(
            accelerations(&pendulum, 0.0, &q, &qd, &[]),
            Err(DynamicsError::NonFiniteEquations)
        );
        let state = State { t: 0.0, q, v: qd };
        let error = integrate::Rk4::step(&Unconstrained::without_inputs(&pendulum), &state, 1e-3)
            .unwrap_err();
        assert_eq!(
            error.cause,
            Failure::Dynamics(DynamicsError::NonFiniteEquations)
        );
        assert!(!energy(&pendulum, &q, &qd).is_finite());

        let constrained = ConstrainedPendulum {
            m: 1.0,
            l: bad,
            g: 9.81,
        };
        let cq = [0.0, -1.0, 0.0];
        let result = constrained_accelerations(&constrained, 0.0, &cq, &[0.0; 3], &[0.0]);
        assert!(
            matches!(
                result,
                Err(DynamicsError::NonFiniteEquations | DynamicsError::NonFiniteConstraints)
            ),
            "{result:?}"
        );
        let start = State {
            t: 0.0,
            q: cq,
            v: [0.0; 3],
        };
        assert!(project_onto_constraints(&constrained, &start, 1e-12, 10).is_err());
        let projection = Stabilisation::Projection {
            tolerance: 1e-12,
            max_iterations: 10,
        };
        assert!(
            integrate::Rk4::step(
                &Constrained::without_inputs(&constrained, projection),
                &start,
                1e-3
            )
            .is_err()
        );
    }
}

/// The emitted `L D Lᵀ` solve tests `M` and `f` only when a pivot fails or
/// `q̈` is not finite; it reports what the runtime's checks before the
/// factorisation report.
#[test]
fn non_finite_equations_come_before_a_singular_or_non_finite_solve() {
    let (q, qd) = ([0.3, -0.4], [0.5, 0.1]);
    let solved =
        |m: f64, g: f64| accelerations(&DoublePendulum { m, L: 1.0, g }, 0.0, &q, &qd, &[]);
    for bad in BAD {
        // `f` alone, then `M` and `f`, then `f` with a singular `M`.
        assert_eq!(solved(1.0, bad), Err(DynamicsError::NonFiniteEquations));
        assert_eq!(solved(bad, 9.81), Err(DynamicsError::NonFiniteEquations));
        assert_eq!(solved(0.0, bad), Err(DynamicsError::NonFiniteEquations));
    }
    assert!(matches!(
        solved(0.0, 9.81),
        Err(DynamicsError::SingularMassMatrix { index: 0, .. })
    ));
}

#[test]
fn non_finite_states_and_inputs_are_errors() {
    let pendulum = DoublePendulum {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    let constrained = ConstrainedPendulum {
        m: 1.0,
        l: 2.0,
        g: 9.81,
    };
    for bad in BAD {
        assert_eq!(
            accelerations(&pendulum, 0.0, &[bad, 0.0], &[0.0; 2], &[]),
            Err(DynamicsError::NonFiniteState)
        );
        let state = State {
            t: bad,
            q: [0.1, 0.2],
            v: [0.0; 2],
        };
        assert!(
            integrate::Rk4::step(&Unconstrained::without_inputs(&pendulum), &state, 1e-3).is_err()
        );
        let step = integrate::Rk4::step(
            &Unconstrained::without_inputs(&pendulum),
            &State { t: 0.0, ..state },
            bad,
        );
        assert!(step.is_err(), "a non-finite step size: {step:?}");
        let (q, qd) = ([1.0_f64.sin(), -1.0_f64.cos(), 1.0], [0.0, 0.0, bad]);
        assert_eq!(
            constrained_accelerations(&constrained, 0.0, &q, &qd, &[0.0]),
            Err(DynamicsError::NonFiniteState)
        );
        assert_eq!(
            constrained_accelerations(&constrained, 0.0, &q, &[0.0; 3], &[bad]),
            Err(DynamicsError::NonFiniteState)
        );
        let start = State { t: 0.0, q, v: qd };
        assert_eq!(
            project_onto_constraints(&constrained, &start, 1e-12, 10),
            Err(DynamicsError::NonFiniteState)
        );
    }
}
