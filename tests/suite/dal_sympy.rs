//! dal_sympy's values at one state (the independent SymPy reading of the
//! language, `scripts/dal_sympy.py --values`, 30 digits) and the checks of a
//! system against them (`scripts/acceptance_reference.py` regenerates them and
//! checks them against the tests): `M`, `f`, `T`, `V`, the accelerations and, for
//! constrained systems, `A`, `b` and the residual, all at 1e-11.

use dalembert::constrained::constrained_accelerations;
use dalembert::{ConstrainedSystem, MultibodySystem};
use dalembert_fixtures::reference::{assert_near, assert_near_all};

/// dal_sympy's values at one state.
pub(crate) struct Expected<const N: usize, const NU: usize> {
    pub(crate) t: f64,
    pub(crate) q: [f64; N],
    pub(crate) v: [f64; N],
    pub(crate) u: [f64; NU],
    pub(crate) mass: [[f64; N]; N],
    pub(crate) forcing: [f64; N],
    pub(crate) kinetic: f64,
    pub(crate) potential: f64,
    pub(crate) accelerations: [f64; N],
}

/// dal_sympy's `A`, `b` and residual at the same state.
pub(crate) struct Constraints<const N: usize, const NC: usize> {
    pub(crate) jacobian: [[f64; N]; NC],
    pub(crate) bias: [f64; NC],
    pub(crate) residual: [f64; NC],
}

/// dal_sympy's values are good to 30 digits: every comparison at 1e-11.
const TOLERANCE: f64 = 1e-11;

fn close(what: &str, actual: f64, expected: f64) {
    assert_near(what, actual, expected, TOLERANCE);
}

fn close_all(what: &str, actual: &[f64], expected: &[f64]) {
    assert_near_all(what, actual, expected, TOLERANCE);
}

fn close_rows<const C: usize>(what: &str, actual: &[[f64; C]], expected: &[[f64; C]]) {
    for (k, (a, e)) in actual.iter().zip(expected).enumerate() {
        close_all(&format!("{what}[{k}]"), a, e);
    }
}

/// `M`, `f`, `T` and `V` at the expected state.
fn check_equations<S, const N: usize, const NU: usize>(system: &S, e: &Expected<N, NU>)
where
    S: MultibodySystem<N, N, NU>,
{
    close_rows("M", &system.mass_matrix(&e.q), &e.mass);
    close_all("f", &system.forcing(e.t, &e.q, &e.v, &e.u), &e.forcing);
    close("T", system.kinetic_energy(&e.q, &e.v), e.kinetic);
    close("V", system.potential_energy(&e.q), e.potential);
}

pub(crate) fn check_unconstrained<S, const N: usize, const NU: usize>(
    system: &S,
    e: &Expected<N, NU>,
) where
    S: MultibodySystem<N, N, NU>,
{
    check_equations(system, e);
    let vdot = dalembert::accelerations(system, e.t, &e.q, &e.v, &e.u).expect("regular");
    close_all("accelerations", &vdot, &e.accelerations);
}

pub(crate) fn check_constrained<S, const N: usize, const NU: usize, const NC: usize>(
    system: &S,
    e: &Expected<N, NU>,
    c: &Constraints<N, NC>,
) where
    S: ConstrainedSystem<N, N, NU, NC>,
{
    check_equations(system, e);
    close_rows("A", &system.constraint_jacobian(&e.q), &c.jacobian);
    close_all("b", &system.constraint_bias(e.t, &e.q, &e.v), &c.bias);
    close_all(
        "residual",
        &system.constraint_residual(e.t, &e.q),
        &c.residual,
    );
    let (vdot, _) = constrained_accelerations(system, e.t, &e.q, &e.v, &e.u).expect("regular");
    close_all("accelerations", &vdot, &e.accelerations);
}
