//! The exact derivatives as outputs: `inverse_dynamics_jacobian`,
//! `accelerations_jacobian` and `linearize`, all from the partials of the
//! inverse dynamics `τ = M v̇ − f` (see
//! [`crate::equations::derivatives`]).

use super::adjoint::inverse_dynamics_adjoint;
use super::{Argument, Body, Function, PairedTree, Value, doc_lines};
use crate::equations::derivatives::{
    ResidualJacobian, TangentDirections, along, direction_names, plain_speeds, residual_jacobian,
    tangent_directions, tangent_kinematics,
};
use crate::equations::{Equations, LinkState, TreeJacobian, depth_first, inverse_dynamics};
use crate::expr::{ExprId, Pool, Sym};
use crate::model::Chart;
use crate::model::Model;
use crate::plan::partials::TauPartials;
use crate::plan::{Partials, adjoint_rows};
use proc_macro2::{Ident, Span};

use Argument::{Accelerations, Coordinates, Inputs, Speeds, Time};

/// How the partials of `τ` were found, for the docs.
fn how(partials: &TauPartials) -> &'static str {
    match (partials.route, partials.recursive_tau) {
        (Partials::Recursive | Partials::Looped, _) => {
            "the inertia and gravity terms of `τ` differentiated by the\n\
             recursion of Carpentier and Mansard over the kinematic tree in\n\
             the axes of `N`, its loads, springs and dampers symbolically"
        }
        (Partials::Symbolic, true) => {
            "`τ`, derived by the Newton–Euler recursion over the kinematic tree,\n\
             differentiated symbolically"
        }
        (Partials::Symbolic, false) => {
            "`τ`, derived by the mass matrix and the forcing,\ndifferentiated symbolically"
        }
    }
}

/// The results of an `accelerations_jacobian` that computes the inertia
/// and gravity terms of `tree`'s partials at run time (see
/// [`PairedTree`]), of which `combined` are the partials in full.
fn paired_results(
    tree: &TreeJacobian,
    combined: &ResidualJacobian,
    pool: &Pool,
) -> (Vec<Value>, PairedTree) {
    let nonzero = |block: &[Vec<ExprId>]| -> Vec<bool> {
        (0..block.len())
            .map(|j| block.iter().any(|row| !pool.is_zero(row[j])))
            .collect()
    };
    let parents: Vec<Option<usize>> = tree.links.iter().map(|l| l.parent).collect();
    // Depth-first, as the runtime's `TreeRecursion::mass_and_bias` takes
    // them: each subtree's links together.
    let order = depth_first(&parents);
    let position = |link: usize| order.iter().position(|&l| l == link);
    let paired = PairedTree {
        parents: order
            .iter()
            .map(|&l| parents[l].and_then(position))
            .collect(),
        joints: order
            .iter()
            .map(|&l| position(tree.links[l].joint).unwrap_or(l))
            .collect(),
        speeds: order.iter().map(|&l| tree.links[l].speed).collect(),
        nonzero: [nonzero(&combined.coordinates), nonzero(&combined.speeds)],
    };
    let states: Vec<Vec<ExprId>> = order
        .iter()
        .map(|&l| tree.states[l].entries().to_vec())
        .collect();
    let (nv, nu) = (
        combined.speeds.len(),
        combined.inputs.first().map_or(0, Vec::len),
    );
    let results = vec![
        Value::matrix(&tree.rest.coordinates, nv),
        Value::matrix(&tree.rest.speeds, nv),
        Value::matrix(&tree.rest.inputs, nu),
        Value::matrix(&states, LinkState::ENTRIES),
        Value::vector(tree.gravity.to_vec()),
        Value::vector(tree.residual.clone()),
    ];
    (results, paired)
}

/// A function named `name` computing `results` as `body` says.
fn function(
    name: &str,
    docs: &str,
    arguments: &[Argument],
    results: Vec<Value>,
    body: Body,
) -> Function {
    Function {
        name: Ident::new(name, Span::call_site()),
        docs: doc_lines(docs),
        arguments: arguments.to_vec(),
        results,
        body,
    }
}

/// `inverse_dynamics_jacobian(t, q, v, v̇, u) -> (∂τ/∂q, ∂τ/∂v, M)`.
pub fn inverse_dynamics_jacobian(
    model: &Model,
    equations: &Equations,
    partials: &TauPartials,
) -> Function {
    let nv = model.nv();
    let (jacobian, how) = (&partials.jacobian, how(partials));
    let tangent = tangent_note(model);
    function(
        "inverse_dynamics_jacobian",
        &format!(
            "The derivatives of the inverse dynamics `τ(t, q, v, v̇, u) = M v̇ − f`:\n\
             `(∂τ/∂q, ∂τ/∂v, ∂τ/∂v̇ = M)`, entry `[i][j]` the derivative of `τᵢ` by\n\
             the `j`-th variable. Exact: {how}, the shared subexpressions computed\n\
             once.{tangent}"
        ),
        &[Time, Coordinates, Speeds, Accelerations, Inputs],
        vec![
            Value::matrix(&jacobian.coordinates, nv),
            Value::matrix(&jacobian.speeds, nv),
            Value::matrix(&equations.mass_matrix, nv),
        ],
        Body::Explicit,
    )
}

/// `accelerations_jacobian(t, q, v, u) -> Result<(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u), _>`.
pub fn accelerations_jacobian(
    model: &Model,
    equations: &Equations,
    partials: &TauPartials,
    pool: &mut Pool,
) -> Function {
    let (nv, nu) = (model.nv(), model.inputs.len());
    let TauPartials { jacobian, tree, .. } = partials;
    let (mut how, tangent) = (how(partials).to_string(), tangent_note(model));
    // The rows as adjoints where the plan says so: the sweep is derived
    // only on the loops' route, where it may be chosen.
    let adjoint = (partials.route == Partials::Looped && model.balls.is_empty())
        .then(|| inverse_dynamics_adjoint(model, equations, pool))
        .filter(|adjoint| adjoint_rows(model, partials, &adjoint.roots(), pool));
    let (results, body) = match (tree, adjoint) {
        (_, Some(adjoint)) => {
            how = "each row by one reverse sweep over `τ` (its vector–jacobian\n\
                   product at the row of `−M⁻¹`), as many rows at once as the target's\n\
                   SIMD registers hold"
                .to_string();
            (adjoint.results, Body::AdjointRows)
        }
        (Some(tree), None) => {
            let (results, paired) = paired_results(tree, jacobian, pool);
            (results, Body::AccelerationsJacobian(Some(paired)))
        }
        (None, None) => (
            vec![
                Value::matrix(&jacobian.coordinates, nv),
                Value::matrix(&jacobian.speeds, nv),
                Value::matrix(&jacobian.inputs, nu),
            ],
            Body::AccelerationsJacobian(None),
        ),
    };
    function(
        "accelerations_jacobian",
        &format!(
            "The derivatives of the accelerations `v̇(t, q, v, u)` at a state:\n\
             `(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u)`, entry `[i][j]` the derivative of `v̇ᵢ` by the\n\
             `j`-th variable. Exact: differentiating `M v̇ = f` gives\n\
             `M ∂v̇/∂x = −∂τ/∂x` with `τ = M v̇ − f` at the solved `v̇`; the partials\n\
             are exact ({how}), and every column but those of\n\
             structural zeros goes through the `L D Lᵀ` factorisation of `M` that\n\
             solved for `v̇`. The errors of `accelerations`, and\n\
             `NonFiniteEquations` for a non-finite derivative.{tangent}"
        ),
        &[Time, Coordinates, Speeds, Inputs],
        results,
        body,
    )
}

/// `linearize(t, q, v, u) -> Result<(A, B), _>`: its results are the
/// kinematic rows `(K_δ, K_v)` of `A`; the rest comes from
/// `accelerations_jacobian`.
pub fn linearize(model: &Model, pool: &mut Pool) -> Function {
    let nv = model.nv();
    let directions = tangent_directions(model, pool);
    let (by_coordinates, by_speeds) = tangent_kinematics(model, pool, &directions);
    let tangent = tangent_note(model);
    let own_rates = match plain_speeds(model).into_iter().all(|(k, c)| {
        let rate = pool.rate(c as u32);
        rate == pool.sym(Sym::Speed(k as u32))
    }) {
        true => "",
        false => ", `(∂(N v)/∂q, N)` for rates `q̇ = N(q) v` of a `speeds` statement",
    };
    let balls = match model.balls.is_empty() {
        true => "",
        false => {
            ", and `δ̇ = δν − ad(ν̄) δ` for a quaternion joint of twist `ν̄` (its\n\
             angular velocity `ω̄`, and for a free joint its velocity `v̄`, in the\n\
             child's axes): `δ̇_ω = δω − ω̄ × δ_ω`, `δ̇_v = δv − ω̄ × δ_v − v̄ × δ_ω`"
        }
    };
    function(
        "linearize",
        &format!(
            "The linearisation `δẋ = A δx + B δu` of the equations of motion about a\n\
             state `x = (q, v)` and input `u`, with `q = q̄ ⊕ δ` and `v = v̄ + δv`\n\
             (`δ` in the tangent space, one entry per speed):\n\
             `A = [[K_δ, K_v], [∂v̇/∂q, ∂v̇/∂v]]` and `B = [[0], [∂v̇/∂u]]`, from\n\
             `accelerations_jacobian` (and with its errors). The kinematic rows\n\
             `δ̇ = K_δ δ + K_v δv` are `(0, I)` where the speeds are the coordinates'\n\
             rates{own_rates}{balls}. About an equilibrium, the eigenvalues of `A` are the\n\
             exponents of the small motions.{tangent}"
        ),
        &[Time, Coordinates, Speeds, Inputs],
        vec![
            Value::matrix(&by_coordinates, nv),
            Value::matrix(&by_speeds, nv),
        ],
        Body::Linearize,
    )
}

/// `linearize(t, q, v, u) -> Result<(A, B), _>` of a system with
/// constraints, on the constraint manifold with the independent entries of
/// `chart`: its results are the partials, at the solved `v̇` and `λ`, of
/// the residuals `r = M v̇ − f − Aᵀ λ` (by `q` in the tangent space, `v`,
/// `u`) and `c = A v̇ − b` (by `q`, `v`), then `∂ψ/∂δ` of the constraints'
/// velocity form `ψ`, `∂φ/∂δ` of their holonomic residuals and the
/// kinematic rows `(K_δ, K_v)`; the runtime's `linearize_on_constraints`
/// does the rest.
pub fn constrained_linearize(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
    chart: &Chart,
) -> Function {
    let nv = model.nv();
    let directions = tangent_directions(model, pool);
    let mut results = acceleration_partials(model, equations, pool, &directions);
    for rows in [
        &equations.constraint_velocity,
        &equations.constraint_residual,
    ] {
        let block: Vec<Vec<ExprId>> = rows
            .iter()
            .map(|&e| directions.iter().map(|d| along(pool, e, d)).collect())
            .collect();
        results.push(Value::matrix(&block, nv));
    }
    let (by_coordinates, by_speeds) = tangent_kinematics(model, pool, &directions);
    results.push(Value::matrix(&by_coordinates, nv));
    results.push(Value::matrix(&by_speeds, nv));
    let speed_names: Vec<String> = model.speeds.iter().map(|s| s.written()).collect();
    let split = |names: &[String], independent: &[bool], want: bool| -> String {
        let chosen: Vec<&str> = names
            .iter()
            .zip(independent)
            .filter(|&(_, &i)| i == want)
            .map(|(n, _)| n.as_str())
            .collect();
        chosen.join("`, `")
    };
    let coordinate_names = direction_names(model);
    function(
        "linearize",
        &format!(
            "The linearisation `δẋ = A δx + B δu` of the equations of motion about a\n\
             state `x = (q, v)` on the constraint manifold and input `u`, with `q = q̄ ⊕ δ`\n\
             (`δ` in the tangent space, one entry per speed) and `v = v̄ + δv`, the\n\
             independent coordinates `{}` (the dependent `{}` follow from the holonomic\n\
             constraints) and the independent speeds `{}` (the dependent `{}` from all\n\
             the constraints' velocity forms), by the method of Peterson, Gede and\n\
             Hubbard (2014), as SymPy's `Linearizer`. The accelerations `v̇(t, q, v, u)`\n\
             of `M v̇ = f + Aᵀ λ`, `A v̇ = b` are differentiated exactly (the partials of\n\
             `M v̇ − f − Aᵀ λ` and `A v̇ − b` at the solved `v̇`, `λ`, through the\n\
             saddle-point system). A perturbation that keeps the constraints is\n\
             `δ = E_q δ`, `δv = E_v δv + F δ`, where `E_q`, `E_v` and `F` read only the\n\
             independent entries (`δ_D = −Φ_D⁻¹ Φ_I δ_I` for `Φ = ∂φ/∂δ` of the\n\
             holonomic rows, `δv_D = −A_D⁻¹ (A_I δv_I + ∂ψ/∂δ δ)`), so with the\n\
             kinematic rows `δ̇ = K_δ δ + K_v δv`\n\
             `A = [[K_δ E_q + K_v F, K_v E_v], [∂v̇/∂q E_q + ∂v̇/∂v F, ∂v̇/∂v E_v]]` and\n\
             `B = [[0], [∂v̇/∂u]]`: the columns of the dependent entries are zero, and\n\
             the rows and columns of the independent ones are the reduced `A` of\n\
             SymPy's `Linearizer`, whose eigenvalues about an equilibrium are the\n\
             nonzero ones of `A`. The state must be on the manifold. Errors: those of\n\
             `dalembert::constrained::constrained_accelerations`, and\n\
             `SingularDependentCoordinates` or `SingularDependentSpeeds` naming a\n\
             dependent entry where the independent ones do not determine it.",
            split(&coordinate_names, &chart.coordinates, true),
            split(&coordinate_names, &chart.coordinates, false),
            split(&speed_names, &chart.speeds, true),
            split(&speed_names, &chart.speeds, false),
        ),
        &[Time, Coordinates, Speeds, Inputs],
        results,
        Body::ConstrainedLinearize,
    )
}

/// The partials, at the solved `v̇` and `λ`, of the residuals
/// `r = M v̇ − f − Aᵀ λ` (by `q` along the tangent `directions`, `v`, `u`)
/// and `c = A v̇ − b` (by `q` along them, `v`) of a system with
/// constraints: what the runtime's `AccelerationPartials` holds.
fn acceleration_partials(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
    directions: &TangentDirections,
) -> Vec<Value> {
    let (nv, nu) = (model.nv(), model.inputs.len());
    let (tau, _) = inverse_dynamics(model, equations, pool);
    let jacobian = &equations.constraint_jacobian;
    let multipliers: Vec<ExprId> = (0..jacobian.len())
        .map(|j| pool.sym(Sym::Multiplier(j as u32)))
        .collect();
    let residual: Vec<ExprId> = tau
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let reactions: Vec<ExprId> = jacobian
                .iter()
                .zip(&multipliers)
                .map(|(row, &lambda)| pool.mul(row[i], lambda))
                .collect();
            let reaction = pool.sum(reactions);
            let minus = pool.neg(reaction);
            pool.add(t, minus)
        })
        .collect();
    let constraint: Vec<ExprId> = jacobian
        .iter()
        .zip(&equations.constraint_bias)
        .map(|(row, &b)| {
            let mut terms: Vec<ExprId> = row
                .iter()
                .enumerate()
                .map(|(k, &a)| {
                    let accel = pool.sym(Sym::Accel(k as u32));
                    pool.mul(a, accel)
                })
                .collect();
            terms.push(pool.neg(b));
            pool.sum(terms)
        })
        .collect();
    let residual = residual_jacobian(pool, &residual, directions, nu);
    let constraint = residual_jacobian(pool, &constraint, directions, 0);
    vec![
        Value::matrix(&residual.coordinates, nv),
        Value::matrix(&residual.speeds, nv),
        Value::matrix(&residual.inputs, nu),
        Value::matrix(&constraint.coordinates, nv),
        Value::matrix(&constraint.speeds, nv),
    ]
}

/// `accelerations_jacobian(t, q, v, u)` of a system with constraints: its
/// results are the partials of the residuals (see
/// [`acceleration_partials`]), and the runtime's
/// `constrained_accelerations_jacobian` solves them through the
/// saddle-point system.
pub fn constrained_accelerations_jacobian(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
) -> Function {
    let directions = tangent_directions(model, pool);
    let tangent = tangent_note(model);
    function(
        "accelerations_jacobian",
        &format!(
            "The derivatives of the accelerations `v̇(t, q, v, u)` of\n\
         `M v̇ = f + Aᵀ λ`, `A v̇ = b` at a state: `(∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u)`, entry\n\
         `[i][j]` the derivative of `v̇ᵢ` by the `j`-th variable. Exact: the\n\
         partials of the residuals `M v̇ − f − Aᵀ λ` and `A v̇ − b`, derived\n\
         symbolically and evaluated at the `v̇`, `λ` of\n\
         `dalembert::constrained::constrained_accelerations`, go through the\n\
         saddle-point system `M ∂v̇ − Aᵀ ∂λ = −∂r`, `A ∂v̇ = −∂c`. They hold off the\n\
         constraint manifold too: `v̇` is a function of the whole state. Dependent\n\
         rows of `A` (redundant, or at a singular position) are solved as the\n\
         accelerations are. Errors: those of `constrained_accelerations`, a mass\n\
         matrix that is not positive definite, `NonFiniteEquations` for a\n\
         non-finite derivative.{tangent}"
        ),
        &[Time, Coordinates, Speeds, Inputs],
        acceleration_partials(model, equations, pool, &directions),
        Body::ConstrainedAccelerationsJacobian,
    )
}

/// What `∂/∂q` means, for the docs of a model with quaternion joints.
fn tangent_note(model: &Model) -> &'static str {
    if model.balls.is_empty() {
        return "";
    }
    "\n`∂/∂q` is in the tangent space, one column per speed, along `q ⊕ δ` as\n\
     `integrate_configuration` moves (Pinocchio's convention): a free or\n\
     spherical joint's quaternion `p` turns to `p ⊗ exp(δ_ω / 2)` (`δ_ω` in\n\
     the child's axes) and a free joint's position moves by `R(p) δ_v`;\n\
     other coordinates move by `δ`. At a unit quaternion."
}

#[cfg(test)]
mod tests {
    /// Seed example 3 with `outputs` added before its closing brace.
    fn constrained_pendulum_asking_for(outputs: &str) -> String {
        let source = crate::seeds::CONSTRAINED_PENDULUM;
        let end = source.rfind('}').expect("a closing brace");
        format!(
            "{}    outputs {outputs};\n{}",
            &source[..end],
            &source[end..]
        )
    }

    #[test]
    fn a_constrained_system_names_its_independent_coordinates_and_the_error_says_where() {
        let source = constrained_pendulum_asking_for("inverse_dynamics_jacobian, linearize");
        let error = crate::check(&source).expect_err("constraints");
        let message = error.to_string();
        assert!(
            message.contains("name its 1 independent coordinate(s) in parentheses"),
            "{message}"
        );
        let line = source
            .lines()
            .position(|l| l.contains("outputs"))
            .expect("the line")
            + 1;
        let start = error.span().start();
        assert_eq!(start.line, line, "{message}");
        let column = source
            .lines()
            .nth(line - 1)
            .and_then(|l| l.find("linearize"));
        assert_eq!(Some(start.column), column, "{message}");
    }

    #[test]
    fn a_constrained_system_with_its_independent_coordinate_is_linearised() {
        let source = constrained_pendulum_asking_for("linearize(theta)");
        let code = crate::generate(&source).expect("generates");
        assert!(code.contains("pub fn linearize("), "{code}");
        assert!(code.contains("linearize_on_constraints"), "{code}");
        assert!(code.contains("coordinates: [false, false, true]"), "{code}");
        assert!(code.contains("speeds: [false, false, true]"), "{code}");
    }

    #[test]
    fn a_constrained_system_has_its_inverse_dynamics_jacobian() {
        let source = constrained_pendulum_asking_for("inverse_dynamics_jacobian");
        let code = crate::generate(&source).expect("generates");
        assert!(code.contains("pub fn inverse_dynamics_jacobian("));
        assert!(!code.contains("pub fn accelerations_jacobian("));
    }
}
