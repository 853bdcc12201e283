//! The outputs a model asks for beyond `M`, `f`, the energies and the
//! constraint rows (`outputs ...;`): their kinds, what each needs in
//! parentheses, and the name of the function that computes it.
//!
//! Every output is opt-in, so a model asking for nothing generates nothing
//! more. A new kind of output is one variant of [`OutputKind`] and one row
//! of [`KINDS`].

use super::{FrameId, PointId};
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
    ("linearize", Subject::None, Availability::Ready),
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
