//! Dynamic outputs: the inverse dynamics `M v̇ − f`, its regressor, and the
//! Taylor coefficients of the motion.

use super::{Argument, Body, Function, NameList, Value, doc_lines};
use crate::equations::regressor::regressor as derive_regressor;
use crate::equations::{Equations, inverse_dynamics as derive_inverse_dynamics};
use crate::expr::Pool;
use crate::model::Model;
use proc_macro2::{Ident, Span};

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

/// `regressor(q, v, v̇)`, `base_parameters()` and `BASE_PARAMETERS`;
/// `None` if the model has none (which the checks after the derivation,
/// `crate::checks`, have reported).
pub fn regressor(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
) -> Option<(Vec<Function>, NameList)> {
    let (tau, _) = derive_inverse_dynamics(model, equations, pool);
    let regressor = derive_regressor(pool, &tau).ok()?;
    let names = regressor.names(&model.parameters);
    let nb = names.len();
    let list: String = names
        .iter()
        .enumerate()
        .map(|(j, name)| format!("\n* `π{}` = `{name}`", subscript(j)))
        .collect();
    let regressor_docs = format!(
        "The regressor `Y(q, v, v̇)` of the inverse dynamics: `M v̇ − f = Y π` at\n\
         zero inputs, that is `inverse_dynamics(t, q, v, v̇, 0)`, where `π` are\n\
         the {nb} base parameters that `base_parameters()` computes and\n\
         `BASE_PARAMETERS` names: the products of parameters that `M v̇ − f` is\n\
         linear in, each product whose column is a constant combination of\n\
         others merged into theirs (no motion tells them apart), those whose\n\
         columns vanish left out. The number of columns is the number of base\n\
         parameters, not of the struct's parameters:{list}"
    );
    let pi = regressor.base_parameters(pool);
    let functions = vec![
        Function::new(
            "regressor",
            &regressor_docs,
            &[Coordinates, Speeds, Accelerations],
            Value::matrix(&regressor.rows, nb),
        ),
        Function::new(
            "base_parameters",
            "The base parameters `π` of `regressor`, from the struct's values (see\n\
             `BASE_PARAMETERS`).",
            &[],
            Value::vector(pi),
        ),
    ];
    let constant = NameList {
        name: Ident::new("BASE_PARAMETERS", Span::call_site()),
        docs: doc_lines(
            "The base parameters of `regressor`, as combinations of the struct's\n\
             parameters, in column order.",
        ),
        names,
    };
    Some((functions, constant))
}

/// `taylor_coefficients(t, q, v, u, order)`: the series of `M` and `f`
/// (its results) through a state, `v̇` solved order by order; its docs say
/// how constraints and rates that are not speeds change the solve.
pub fn taylor(model: &Model, equations: &Equations, pool: &Pool) -> Function {
    let nv = model.nv();
    let mut docs = vec![TAYLOR_DOCS];
    if !equations.constraint_jacobian.is_empty() {
        docs.push(CONSTRAINED_TAYLOR_DOCS);
    }
    if !pool.rates_are_speeds() {
        docs.push(RATES_TAYLOR_DOCS);
    }
    Function {
        body: Body::Taylor,
        results: vec![
            Value::matrix(&equations.mass_matrix, nv),
            Value::vector(equations.forcing.clone()),
        ],
        ..Function::new(
            "taylor_coefficients",
            &docs.join("\n\n"),
            &[Time, Coordinates, Speeds, Inputs],
            Value::vector(Vec::new()),
        )
    }
}

/// `accelerations_x4(t, q, v, u)`: four states at once (its body is the
/// emitter's, from the plan's route for the lanes).
pub fn accelerations_x4() -> Function {
    Function {
        body: Body::AccelerationsX4,
        results: Vec::new(),
        ..Function::new(
            "accelerations_x4",
            ACCELERATIONS_X4_DOCS,
            &[Time, Coordinates, Speeds, Inputs],
            Value::vector(Vec::new()),
        )
    }
}

/// The docs of `accelerations_x4`.
const ACCELERATIONS_X4_DOCS: &str =
    "The accelerations of four states at once: entry `k` is `accelerations` of the
state `(t[k], q[k], qd[k], u[k])`. A straight-line solve (the scalar call's
route, or the articulated-body recursion where that is the faster over
lanes), with each number of the four states in one lane of a SIMD vector
(`wide::f64x4`): equal to the scalar call's results to rounding. A state
that is not finite, or whose solve fails a pivot or gives a non-finite
value, is answered by the scalar `accelerations`, with its error.";

/// The docs of `taylor_coefficients`.
const TAYLOR_DOCS: &str =
    "The Taylor coefficients of the motion through the state `(t, q, q̇)` with the
inputs `u` held constant: entry `[i][k]` of the two arrays is the coefficient
of `τᵏ` in `qᵢ(t + τ)` and `q̇ᵢ(t + τ)`, for `k ≤ order` (and `k < K`; the
rest are zero). Every elementary operation of `M` and `f` has its
recurrence in the runtime (Cauchy products, quotients, the `sin`/`cos`
pair, …), computed order by order from the lower orders; order `k` of
`M(q) q̈ = f` gives `M₀ q̈ₖ = fₖ − Σⱼ₌₁ᵏ Mⱼ q̈ₖ₋ⱼ`, solved with the one
`L D Lᵀ` factorisation of `M₀ = M(q)`, and `q̇ₖ₊₁ = q̈ₖ / (k + 1)`,
`qₖ₊₁ = q̇ₖ / (k + 1)`. The errors of `accelerations` (non-finite state,
singular `M`); a non-finite coefficient is left for the caller to see.";

/// What the docs of `taylor_coefficients` add for a system with
/// constraints.
const CONSTRAINED_TAYLOR_DOCS: &str =
    "With constraints, order `k` solves `M₀ q̈ₖ − A₀ᵀ λₖ = fₖ − Σⱼ₌₁ᵏ (Mⱼ q̈ₖ₋ⱼ −
Aⱼᵀ λₖ₋ⱼ)`, `A₀ q̈ₖ = bₖ − Σⱼ₌₁ᵏ Aⱼ q̈ₖ₋ⱼ` with the one factorisation of the
saddle point that `constrained_accelerations` makes
(`dalembert::__private::constrained_series`), with its errors.";

/// What the docs of `taylor_coefficients` add where the speeds are not
/// the coordinates' rates.
const RATES_TAYLOR_DOCS: &str =
    "The coordinates integrate the series of their rates `N(q) q̇` instead of
the speeds: `qₖ₊₁ = (N(q) q̇)ₖ / (k + 1)` (a quaternion is unit to the
integrator's accuracy only).";

/// `j` in subscript digits.
fn subscript(j: usize) -> String {
    j.to_string()
        .chars()
        .map(|d| char::from_u32(0x2080 + d.to_digit(10).unwrap_or(0)).unwrap_or(d))
        .collect()
}
