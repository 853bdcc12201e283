//! The outputs a model asks for beyond `M`, `f`, the energies and the
//! constraint rows (`outputs ...;`): their kinds, what each needs in
//! parentheses, and the name of the function that computes it.
//!
//! Every output is opt-in, so a model asking for nothing generates nothing
//! more. A new kind of output is one variant of [`OutputKind`] and one row
//! of [`KINDS`].

use super::{FrameId, Model, PointId};
use crate::expr::Pool;
use proc_macro2::{Ident, Span};
use quote::format_ident;

/// What a model asks to compute.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputKind {
    /// `inverse_dynamics`: `M v̇ − f` for given accelerations.
    InverseDynamics,
    /// `regressor`: `Y` with `M v̇ − f = Y π`, `π` the base parameters.
    Regressor,
    /// `inverse_dynamics_jacobian`: `∂τ/∂q`, `∂τ/∂v` and `∂τ/∂v̇ = M` of the
    /// inverse dynamics `τ = M v̇ − f`.
    InverseDynamicsJacobian,
    /// `accelerations_jacobian`: `∂v̇/∂q`, `∂v̇/∂v`, `∂v̇/∂u`.
    AccelerationsJacobian,
    /// `linearize`: the state-space matrices `A`, `B` about a state.
    Linearize,
    /// `taylor`: the Taylor coefficients of the motion through a state, to
    /// any order (`taylor_coefficients`, for `dalembert::integrate::taylor`).
    Taylor,
    /// `position(P)`: where a point is, from `O`.
    Position(PointId),
    /// `velocity(P)`: its velocity in `N`.
    Velocity(PointId),
    /// `acceleration(P)`: its acceleration in `N`.
    Acceleration(PointId),
    /// `jacobian(P)`: `∂v_P/∂v`, its velocity's partials by the speeds.
    Jacobian(PointId),
    /// `rotation(B)`: the matrix taking `B`'s components to the axes'.
    Rotation(FrameId),
    /// `angular_velocity(B)`: `B`'s angular velocity in `N`.
    AngularVelocity(FrameId),
    /// `angular_jacobian(B)`: `∂ω_B/∂v`.
    AngularJacobian(FrameId),
}

/// What an output needs in parentheses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Subject {
    /// Nothing: `inverse_dynamics`.
    None,
    /// A point: `position(P)`.
    Point,
    /// A frame: `rotation(B)`.
    Frame,
    /// Coordinates, optional: `linearize(theta)`, the independent
    /// coordinates of a system with constraints.
    Coordinates,
}

/// Whether an output can be generated today.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Availability {
    /// Generated.
    Ready,
    /// Part of the language, not generated yet: an error says so.
    NotYet,
}

/// Every output name of the language, what it needs in parentheses and
/// whether it is generated.
pub const KINDS: [(&str, Subject, Availability); 13] = [
    ("inverse_dynamics", Subject::None, Availability::Ready),
    ("regressor", Subject::None, Availability::Ready),
    ("accelerations_jacobian", Subject::None, Availability::Ready),
    ("linearize", Subject::Coordinates, Availability::Ready),
    ("taylor", Subject::None, Availability::Ready),
    (
        "inverse_dynamics_jacobian",
        Subject::None,
        Availability::Ready,
    ),
    ("position", Subject::Point, Availability::Ready),
    ("velocity", Subject::Point, Availability::Ready),
    ("acceleration", Subject::Point, Availability::Ready),
    ("jacobian", Subject::Point, Availability::Ready),
    ("rotation", Subject::Frame, Availability::Ready),
    ("angular_velocity", Subject::Frame, Availability::Ready),
    ("angular_jacobian", Subject::Frame, Availability::Ready),
];

/// The names of [`KINDS`], quoted, for messages.
pub fn kind_list() -> String {
    KINDS
        .iter()
        .map(|(name, subject, _)| match subject {
            Subject::None => format!("`{name}`"),
            Subject::Coordinates => format!("`{name}`"),
            Subject::Point => format!("`{name}(P)`"),
            Subject::Frame => format!("`{name}(B)`"),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The kind called `name` with its subject resolved: a point for
/// [`Subject::Point`] kinds, a frame for [`Subject::Frame`] kinds.
pub fn kind(name: &str, point: Option<PointId>, frame: Option<FrameId>) -> Option<OutputKind> {
    Some(match (name, point, frame) {
        ("inverse_dynamics", ..) => OutputKind::InverseDynamics,
        ("regressor", ..) => OutputKind::Regressor,
        ("inverse_dynamics_jacobian", ..) => OutputKind::InverseDynamicsJacobian,
        ("accelerations_jacobian", ..) => OutputKind::AccelerationsJacobian,
        ("linearize", ..) => OutputKind::Linearize,
        ("taylor", ..) => OutputKind::Taylor,
        ("position", Some(p), _) => OutputKind::Position(p),
        ("velocity", Some(p), _) => OutputKind::Velocity(p),
        ("acceleration", Some(p), _) => OutputKind::Acceleration(p),
        ("jacobian", Some(p), _) => OutputKind::Jacobian(p),
        ("rotation", _, Some(f)) => OutputKind::Rotation(f),
        ("angular_velocity", _, Some(f)) => OutputKind::AngularVelocity(f),
        ("angular_jacobian", _, Some(f)) => OutputKind::AngularJacobian(f),
        _ => return None,
    })
}

/// One output of a model.
#[derive(Clone, Debug)]
pub struct Output {
    /// What to compute.
    pub kind: OutputKind,
    /// The frame whose axes a vector or matrix is given in (`N` unless
    /// `in F` says otherwise).
    pub axes: FrameId,
    /// The generated function's name: the output's (`inverse_dynamics`),
    /// or with its subject and axes (`position_P`, `velocity_P_in_B`).
    pub function: Ident,
    /// The point or frame in parentheses as written, for the docs.
    pub subject: Option<String>,
    /// The name of the frame of [`Output::axes`], for the docs.
    pub axes_name: String,
    /// `linearize(a, b)`'s independent coordinates, as written, with their
    /// indices.
    pub independent: Vec<(usize, Ident)>,
}

/// The function name of an output written `name`, `name(subject)` or
/// `name(subject in axes)`.
pub fn function_name(name: &Ident, subject: Option<&Ident>, axes: Option<&Ident>) -> Ident {
    let span: Span = name.span();
    let mut ident = match subject {
        None => format_ident!("{}", name),
        Some(s) => format_ident!("{}_{}", name, s),
    };
    if let Some(f) = axes {
        ident = format_ident!("{}_in_{}", ident, f);
    }
    ident.set_span(span);
    ident
}

/// What is wrong with a `linearize` output of `model` (whose expressions
/// are in `pool`), at which token: a
/// system with constraints is linearised on the constraint manifold, so
/// it names as many independent coordinates as it has degrees of freedom
/// (`NQ − NC`; the others are found from the holonomic constraints), and
/// a system without names none.
pub fn linearize_problem(model: &Model, pool: &Pool, output: &Output) -> Option<(Span, String)> {
    let name = &output.function;
    let (nq, nc) = (model.nq(), model.constraints.len());
    if nc == 0 {
        let (_, first) = output.independent.first()?;
        return Some((
            first.span(),
            format!(
                "`{name}` takes independent coordinates only for a system with constraints: \
                 write `{name}` alone"
            ),
        ));
    }
    let problem = if model.constraints.iter().any(|c| c.nonholonomic) {
        "is not available yet for a system with nonholonomic constraints: remove it from \
         `outputs`"
            .to_string()
    } else if nq != model.nv() || !model.balls.is_empty() || !pool.rates_are_speeds() {
        "is not available yet for a system with constraints whose speeds are not its \
         coordinates' rates (a free or spherical joint, a `speeds` statement): remove it \
         from `outputs`"
            .to_string()
    } else if output.independent.len() + nc != nq {
        let written: Vec<String> = model.coordinates.iter().map(ToString::to_string).collect();
        format!(
            "linearises a system with constraints on the constraint manifold: name its \
             {} independent coordinate(s) in parentheses, as `{name}({})` ({nq} coordinates \
             `{}`, less {nc} constraint(s)); the others are found from the constraints",
            nq.saturating_sub(nc),
            written.last().map_or("", String::as_str),
            written.join("`, `"),
        )
    } else {
        return None;
    };
    let span = match output.independent.first() {
        Some((_, first)) if nq == model.nv() && output.independent.len() + nc != nq => first.span(),
        _ => name.span(),
    };
    Some((span, format!("`{name}` {problem}")))
}
