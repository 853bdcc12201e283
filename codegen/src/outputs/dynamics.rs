//! Dynamic outputs: the inverse dynamics `M v̇ − f` and its regressor.

use super::{Argument, Function, Value};
use crate::equations::{Equations, inverse_dynamics as derive_inverse_dynamics};
use crate::expr::Pool;
use crate::model::Model;

use Argument::{Accelerations, Coordinates, Inputs, Speeds, Time};

/// `inverse_dynamics(t, q, v, v̇, u)`.
pub fn inverse_dynamics(model: &Model, equations: &Equations, pool: &mut Pool) -> Function {
    let (tau, recursive) = derive_inverse_dynamics(model, equations, pool);
    let route = match recursive {
        true => {
            "by the Newton–Euler recursion over the kinematic tree (outwards\n\
                 for the motions with `v̇`, inwards for the forces), not through `M`"
        }
        false => "through the mass matrix and the forcing",
    };
    Function::new(
        "inverse_dynamics",
        &format!(
            "The inverse dynamics `M(q) v̇ − f(t, q, v, u)`: the generalized forces\n\
             that the accelerations `v̇` need beyond the applied ones, computed\n\
             {route}."
        ),
        &[Time, Coordinates, Speeds, Accelerations, Inputs],
        Value::vector(tau),
    )
}
