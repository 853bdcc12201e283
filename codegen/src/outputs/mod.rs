//! The generated functions as values: each output of a system (the mass
//! matrix, the forcing, the energies, the constraint rows, and what the
//! model's `outputs` statement asks for) is a [`Function`] — its name,
//! docs, arguments and the expressions it returns — that one routine of
//! the emitter writes. A new output is one more value here, not a new
//! emitter; the results of one function are computed by one straight-line
//! body, so they share their subexpressions.

mod adjoint;
mod derivatives;
mod dynamics;
mod kinematic;
mod mass;

use crate::equations::Equations;
use crate::expr::{ExprId, Pool};
use crate::model::{Model, OutputKind};
use crate::plan::partials::TauPartials;
use crate::plan::{self, MassMatrix};
use proc_macro2::Ident;

/// One generated inherent function.
pub struct Function {
    /// Its name.
    pub name: Ident,
    /// Its doc comment, one entry a line (each with its leading space).
    pub docs: Vec<String>,
    /// The arguments it takes after `&self`, in order.
    pub arguments: Vec<Argument>,
    /// What it returns: one value, or a tuple of several.
    pub results: Vec<Value>,
    /// How it computes them.
    pub body: Body,
}

/// The tree of an `accelerations_jacobian` that computes the inertia and
/// gravity terms of its partials at run time, link by link and pair of
/// joints by pair, and its mass matrix and forcing by the same recursion
/// at `q̈ = 0`: its fourth result holds each link's state (the entries of
/// the runtime's `LinkState`, a row a link), its fifth gravity, its sixth
/// the rest of `τ` (loads, potentials, dissipation: minus their share of
/// `f`), its first two only the rest of `∂τ/∂q` and `∂τ/∂v`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PairedTree {
    /// Each link's parent among the links (depth-first: parents before
    /// children, each subtree's links together).
    pub parents: Vec<Option<usize>>,
    /// The link of each one's joint's first speed (a joint of several
    /// speeds is as many links, each the parent of the next).
    pub joints: Vec<usize>,
    /// Each link's speed.
    pub speeds: Vec<usize>,
    /// Whether each column of `∂τ/∂q` and of `∂τ/∂v`, pairs included, can
    /// be nonzero.
    pub nonzero: [Vec<bool>; 2],
}

/// The tree of a `mass_matrix` whose pairs of speeds a loop of the runtime
/// takes: its first result holds each speed's `Sⱼ` and `Fⱼ` (12 entries a
/// row), its second (if any armature) the armatures added to the diagonal.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpeedTree {
    /// Where each speed's subtree ends among the speeds (depth-first: the
    /// speeds it moves are those from it to before its end).
    pub ends: Vec<usize>,
    /// The index of each speed.
    pub speeds: Vec<usize>,
    /// The speed of each `armature` statement, in the order of the second
    /// result's entries.
    pub armature: Vec<usize>,
}

/// How a generated function computes what it returns.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Body {
    /// Its results, by one straight-line body.
    Explicit,
    /// `accelerations_jacobian`: its results are the partials `∂τ/∂q`,
    /// `∂τ/∂v`, `∂τ/∂u` of the inverse dynamics, evaluated at the
    /// accelerations solved from `M v̇ = f`, and it returns
    /// `−M⁻¹` times each (the factorisation that solved for `v̇` reused);
    /// with a [`PairedTree`], the inertia and gravity terms are added at
    /// run time from its links' states.
    AccelerationsJacobian(Option<PairedTree>),
    /// `accelerations_jacobian` of a fixed-base tree by its rows: its
    /// results are `inverse_dynamics_adjoint`'s, `μᵀ ∂τ/∂q`, `μᵀ ∂τ/∂v`,
    /// `μᵀ ∂τ/∂u` at the solved accelerations, and row `i` of the jacobian
    /// is them at `μ = −M⁻¹ eᵢ`, a few rows a pass in SIMD lanes (see
    /// [`crate::plan::ADJOINT_ROW_AT_MOST`]).
    AdjointRows,
    /// `mass_matrix` of a large tree: its result is each speed's vectors,
    /// whose dot products a loop of the runtime puts into `M`.
    MassPairs(SpeedTree),
    /// `linearize`: its results are the kinematic rows of `A`; the rest is
    /// assembled from `accelerations_jacobian`.
    Linearize,
    /// `linearize` of a system with constraints: its results are the
    /// partials of the residuals that the runtime's
    /// `linearize_on_constraints` takes.
    ConstrainedLinearize,
    /// `accelerations_jacobian` of a system with constraints: its results
    /// are the partials of the residuals that the runtime's
    /// `constrained_accelerations_jacobian` takes.
    ConstrainedAccelerationsJacobian,
    /// `accelerations_x4`: `accelerations` written again over SIMD lanes,
    /// one state a lane, by the route the plan chose for `accelerations`
    /// (it has no results of its own).
    AccelerationsX4,
    /// `taylor_coefficients`: its results are `M` and `f`, whose Taylor
    /// coefficients it computes order by order, solving each order with one
    /// factorisation of `M`.
    Taylor,
}

/// An argument of a generated function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Argument {
    /// `t: f64`.
    Time,
    /// `q: &[f64; NQ]`.
    Coordinates,
    /// `qd: &[f64; NV]`, the speeds.
    Speeds,
    /// `qdd: &[f64; NV]`, the speeds' rates.
    Accelerations,
    /// `u: &[f64; NU]`.
    Inputs,
    /// `mu: &[f64; NV]`, the weights of a vector–jacobian product, one per
    /// speed (the symbols [`Sym::Multiplier`](crate::expr::Sym::Multiplier)).
    Weights,
}

/// A returned value: a scalar, an array or an array of rows.
pub struct Value {
    /// How the expressions are arranged.
    pub shape: Shape,
    /// The entries, row by row.
    pub expressions: Vec<ExprId>,
}

/// The arrangement of a returned value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// `f64`.
    Scalar,
    /// `[f64; n]`.
    Vector,
    /// `[[f64; columns]; rows]`.
    Matrix {
        /// Entries per row.
        columns: usize,
    },
}

impl Value {
    /// A scalar.
    pub fn scalar(e: ExprId) -> Value {
        Value {
            shape: Shape::Scalar,
            expressions: vec![e],
        }
    }

    /// An array.
    pub fn vector(entries: Vec<ExprId>) -> Value {
        Value {
            shape: Shape::Vector,
            expressions: entries,
        }
    }

    /// An array of rows, each of `columns` entries.
    pub fn matrix(rows: &[Vec<ExprId>], columns: usize) -> Value {
        Value {
            shape: Shape::Matrix { columns },
            expressions: rows.iter().flatten().copied().collect(),
        }
    }
}

impl Function {
    /// A function of `arguments` returning one value.
    fn new(name: &str, docs: &str, arguments: &[Argument], result: Value) -> Function {
        Function {
            name: Ident::new(name, proc_macro2::Span::call_site()),
            docs: doc_lines(docs),
            arguments: arguments.to_vec(),
            results: vec![result],
            body: Body::Explicit,
        }
    }

    /// The same function at time `t`: named `NAME_at`, with `t` its first
    /// argument (the form of a [time-dependent](Equations::time_dependent)
    /// system's `M`, `T`, `V` and `A`).
    fn at_time(mut self) -> Function {
        self.name = quote::format_ident!("{}_at", self.name);
        self.arguments.insert(0, Time);
        self.docs.extend(doc_lines(
            "\nAt time `t`: the model moves a mass, or turns a constraint, with\n\
             `t` (the struct is `TIME_DEPENDENT`).",
        ));
        self
    }

    /// Every expression it returns, in order: the roots of its body.
    pub fn roots(&self) -> Vec<ExprId> {
        self.results
            .iter()
            .flat_map(|v| v.expressions.iter().copied())
            .collect()
    }

    /// Every expression it returns, in order, for passes that rewrite them.
    pub fn expressions_mut(&mut self) -> impl Iterator<Item = &mut ExprId> {
        self.results
            .iter_mut()
            .flat_map(|v| v.expressions.iter_mut())
    }
}

/// `text`'s lines, each with a leading space (as `///` comments give).
pub fn doc_lines(text: &str) -> Vec<String> {
    text.lines().map(|line| format!(" {line}")).collect()
}

use Argument::{Coordinates, Inputs, Speeds, Time};

/// The functions every system has: `M`, `f`, `T`, `V`, and with
/// constraints `A`, `b`, the residuals and the velocity forms; `M` by
/// the plan's route (see [`mass::mass_matrix`]). A
/// [time-dependent](Equations::time_dependent) system's `M`, `T`, `V` and
/// `A` take `t` first and end in `_at`.
pub fn standard(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
    mass: MassMatrix,
) -> Vec<Function> {
    let nv = model.nv();
    let timed = equations.time_dependent(pool);
    let at_time = |function: Function| if timed { function.at_time() } else { function };
    let mut functions = vec![
        at_time(mass::mass_matrix(model, equations, pool, mass)),
        Function::new(
            "forcing",
            "The forcing `f(t, q, q̇, u)` of `M(q) q̈ = f`: applied and\n\
             gravity forces, minus the velocity-dependent inertia terms.",
            &[Time, Coordinates, Speeds, Inputs],
            Value::vector(equations.forcing.clone()),
        ),
        at_time(Function::new(
            "kinetic_energy",
            "The kinetic energy `T(q, q̇)`.",
            &[Coordinates, Speeds],
            Value::scalar(equations.kinetic_energy),
        )),
        at_time(Function::new(
            "potential_energy",
            "The potential energy `V(q)`: gravity (from `O`) and the\n\
             `potential` statements.",
            &[Coordinates],
            Value::scalar(equations.potential_energy),
        )),
    ];
    if model.constraints.is_empty() {
        return functions;
    }
    functions.extend([
        at_time(Function::new(
            "constraint_jacobian",
            "The constraint Jacobian `A(q)` of `M q̈ = f + Aᵀλ`, `A q̈ = b`;\n\
             rows in declaration order.",
            &[Coordinates],
            Value::matrix(&equations.constraint_jacobian, nv),
        )),
        Function::new(
            "constraint_bias",
            "The constraint bias `b(t, q, q̇)` of `A q̈ = b`.",
            &[Time, Coordinates, Speeds],
            Value::vector(equations.constraint_bias.clone()),
        ),
        Function::new(
            "constraint_residual",
            "The residual `lhs − rhs` of each holonomic constraint (0 for\n\
             nonholonomic rows).",
            &[Time, Coordinates],
            Value::vector(equations.constraint_residual.clone()),
        ),
        Function::new(
            "constraint_velocity",
            "The velocity form of each constraint, `A q̇ + ψ₀(t, q)`: the time\n\
             derivative of a holonomic row's residual, a nonholonomic row\n\
             itself. Zero on the constraint manifold.",
            &[Time, Coordinates, Speeds],
            Value::vector(equations.constraint_velocity.clone()),
        ),
    ]);
    functions
}

/// A constant list of names (`BASE_PARAMETERS`).
pub struct NameList {
    /// The constant's name.
    pub name: Ident,
    /// Its doc comment, one entry a line.
    pub docs: Vec<String>,
    /// The names.
    pub names: Vec<String>,
}

/// What the model's `outputs` statement asks for: functions, and the
/// constants that name their entries.
#[derive(Default)]
pub struct Requested {
    /// The functions, in the order asked for.
    pub functions: Vec<Function>,
    /// The constants.
    pub constants: Vec<NameList>,
}

/// What the model's `outputs` statement asks for, in the order written
/// (`linearize` brings `accelerations_jacobian`, which it calls); what the
/// model cannot give has been refused by the checks after the derivation
/// (`crate::checks`).
pub fn requested(model: &Model, equations: &Equations, pool: &mut Pool) -> Requested {
    let mut requested = Requested::default();
    if model.outputs.is_empty() {
        return requested;
    }
    let kinematics = &equations.mechanics.kinematics;
    // The partials of `τ`, found at the first output that needs them.
    let mut partials = None;
    let asked = |kind: OutputKind| model.outputs.iter().any(|o| o.kind == kind);
    for output in &model.outputs {
        match output.kind {
            OutputKind::InverseDynamics => requested
                .functions
                .push(dynamics::inverse_dynamics(model, equations, pool)),
            OutputKind::Regressor => {
                if let Some((functions, names)) = dynamics::regressor(model, equations, pool) {
                    requested.functions.extend(functions);
                    requested.constants.push(names);
                }
            }
            OutputKind::InverseDynamicsJacobian => {
                let partials = tau_partials(&mut partials, model, equations, pool);
                requested
                    .functions
                    .push(derivatives::inverse_dynamics_jacobian(
                        model, equations, partials,
                    ))
            }
            OutputKind::InverseDynamicsAdjoint => requested
                .functions
                .push(adjoint::inverse_dynamics_adjoint(model, equations, pool)),
            OutputKind::AccelerationsJacobian if !model.constraints.is_empty() => requested
                .functions
                .push(derivatives::constrained_accelerations_jacobian(
                    model, equations, pool,
                )),
            OutputKind::AccelerationsJacobian => {
                let partials = tau_partials(&mut partials, model, equations, pool);
                requested
                    .functions
                    .push(derivatives::accelerations_jacobian(
                        model, equations, partials, pool,
                    ))
            }
            OutputKind::Linearize if !model.constraints.is_empty() => {
                if let Some(chart) = &output.chart {
                    requested.functions.push(derivatives::constrained_linearize(
                        model, equations, pool, chart,
                    ))
                }
            }
            OutputKind::Linearize => {
                if !asked(OutputKind::AccelerationsJacobian) {
                    let partials = tau_partials(&mut partials, model, equations, pool);
                    requested
                        .functions
                        .push(derivatives::accelerations_jacobian(
                            model, equations, partials, pool,
                        ));
                }
                requested
                    .functions
                    .push(derivatives::linearize(model, pool));
            }
            OutputKind::Taylor => requested
                .functions
                .push(dynamics::taylor(model, equations, pool)),
            OutputKind::AccelerationsX4 => requested.functions.push(dynamics::accelerations_x4()),
            _ => requested
                .functions
                .extend(kinematic::function(model, kinematics, pool, output)),
        }
    }
    requested
}

/// The partials of `τ` in `found`, found there first if they are not yet.
fn tau_partials<'a>(
    found: &'a mut Option<TauPartials>,
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
) -> &'a TauPartials {
    found.get_or_insert_with(|| plan::partials::tau_partials(model, equations, pool))
}
