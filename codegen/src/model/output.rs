//! The outputs a model asks for beyond `M`, `f`, the energies and the
//! constraint rows (`outputs ...;`): their kinds, what each needs in
//! parentheses, and the name of the function that computes it.
//!
//! Every output is opt-in, so a model asking for nothing generates nothing
//! more. A new kind of output is one variant of [`OutputKind`] and one row
//! of [`KINDS`].

use super::{FrameId, Model, PointId};
use crate::equations::derivatives::plain_speeds;
use crate::expr::{Pool, Sym};
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
    /// `inverse_dynamics_adjoint`: `μᵀ ∂τ/∂q`, `μᵀ ∂τ/∂v`, `μᵀ ∂τ/∂u` of the
    /// inverse dynamics at given weights `μ`, by one reverse sweep.
    InverseDynamicsAdjoint,
    /// `accelerations_jacobian`: `∂v̇/∂q`, `∂v̇/∂v`, `∂v̇/∂u`.
    AccelerationsJacobian,
    /// `linearize`: the state-space matrices `A`, `B` about a state.
    Linearize,
    /// `accelerations_x4`: the accelerations of four states at once, one
    /// state in each lane of a SIMD vector.
    AccelerationsX4,
    /// `taylor`: the Taylor coefficients of the motion through a state, to
    /// any order (`taylor_coefficients`, for `dalembert::integrate::Taylor`).
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

/// Every output name of the language and what it needs in parentheses.
pub const KINDS: [(&str, Subject); 15] = [
    ("inverse_dynamics", Subject::None),
    ("regressor", Subject::None),
    ("accelerations_jacobian", Subject::None),
    ("linearize", Subject::Coordinates),
    ("taylor", Subject::None),
    ("accelerations_x4", Subject::None),
    ("inverse_dynamics_jacobian", Subject::None),
    ("inverse_dynamics_adjoint", Subject::None),
    ("position", Subject::Point),
    ("velocity", Subject::Point),
    ("acceleration", Subject::Point),
    ("jacobian", Subject::Point),
    ("rotation", Subject::Frame),
    ("angular_velocity", Subject::Frame),
    ("angular_jacobian", Subject::Frame),
];

/// The names of [`KINDS`], quoted, for messages.
pub fn kind_list() -> String {
    KINDS
        .iter()
        .map(|(name, subject)| match subject {
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
        ("inverse_dynamics_adjoint", ..) => OutputKind::InverseDynamicsAdjoint,
        ("accelerations_jacobian", ..) => OutputKind::AccelerationsJacobian,
        ("linearize", ..) => OutputKind::Linearize,
        ("taylor", ..) => OutputKind::Taylor,
        ("accelerations_x4", ..) => OutputKind::AccelerationsX4,
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
    /// `linearize(a, b; ..)`'s independent coordinates, as written: a
    /// coordinate, or a speed of a free or spherical joint for the tangent
    /// direction along it.
    pub independent: Vec<(Sym, Ident)>,
    /// `linearize(..; dt(a), w)`'s independent speeds, as written: the
    /// coordinate of `dt(..)`, or a speed.
    pub independent_speeds: Vec<(Sym, Ident)>,
    /// `linearize(..)`'s independent entries, found by [`chart`] once the
    /// model is checked.
    pub chart: Option<Chart>,
}

/// The independent entries of a linearisation on the constraint manifold:
/// whether each tangent direction of the coordinates (one per speed) and
/// each speed is independent.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chart {
    /// By tangent direction.
    pub coordinates: Vec<bool>,
    /// By speed.
    pub speeds: Vec<bool>,
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

/// The [`Chart`] of a `linearize` output of `model` (whose expressions
/// are in `pool`), or what is wrong with it, at which token: a system with
/// constraints is linearised on the constraint manifold, so it names as
/// many independent coordinates as it has speeds less holonomic rows (the
/// tangent directions of a free or spherical joint by the joint's speeds),
/// and, after `;`, as many independent speeds as it has speeds less rows
/// (by default, with holonomic rows only, the speeds of the independent
/// coordinates); a system without constraints names none.
pub fn chart(model: &Model, pool: &mut Pool, output: &Output) -> Result<Chart, (Span, String)> {
    let name = &output.function;
    let (nv, nc) = (model.nv(), model.acting_constraints().count());
    let holonomic = model
        .acting_constraints()
        .filter(|c| !c.nonholonomic)
        .count();
    if nc == 0 {
        return match output.independent.first() {
            Some((_, first)) => Err((
                first.span(),
                format!(
                    "`{name}` takes independent coordinates only for a system with \
                     constraints: write `{name}` alone"
                ),
            )),
            None => Ok(Chart {
                coordinates: vec![true; nv],
                speeds: vec![true; nv],
            }),
        };
    }
    let coordinates = independent_directions(model, output, holonomic)?;
    if output.independent_speeds.is_empty() && holonomic == nc {
        let speeds = coordinates.clone();
        return Ok(Chart {
            coordinates,
            speeds,
        });
    }
    let speeds = independent_speeds(model, pool, output)?;
    Ok(Chart {
        coordinates,
        speeds,
    })
}

/// The names as written, comma-separated.
fn written(names: &[(Sym, Ident)]) -> String {
    let names: Vec<String> = names.iter().map(|(_, n)| n.to_string()).collect();
    names.join(", ")
}

/// Whether each tangent direction (one per speed) is among the independent
/// coordinates of `output`, which must be as many as the speeds less the
/// `holonomic` rows; or what is wrong, at which token.
fn independent_directions(
    model: &Model,
    output: &Output,
    holonomic: usize,
) -> Result<Vec<bool>, (Span, String)> {
    let (name, nv) = (&output.function, model.nv());
    let plain = plain_speeds(model);
    let ball_speeds: Vec<usize> = model
        .balls
        .iter()
        .flat_map(|b| {
            let linear = b.translation.map(|(_, v)| v);
            b.angular.into_iter().chain(linear.into_iter().flatten())
        })
        .collect();
    let mut coordinates = vec![false; nv];
    for (sym, ident) in &output.independent {
        let direction = match *sym {
            Sym::Coord(c) => plain
                .iter()
                .find(|&&(_, p)| p == c as usize)
                .map(|&(k, _)| k),
            Sym::Speed(k) => ball_speeds.contains(&(k as usize)).then_some(k as usize),
            _ => None,
        };
        let Some(k) = direction else {
            let what = match sym {
                Sym::Coord(_) => "a component of a free or spherical joint's quaternion",
                _ => "a speed that is not a free or spherical joint's",
            };
            return Err((
                ident.span(),
                format!(
                    "`{ident}` is {what}: `{name}(..)` names plain coordinates, and a free or \
                     spherical joint's tangent directions by the joint's speeds \
                     (`J_wx`, `J_vx`, ..)"
                ),
            ));
        };
        coordinates[k] = true;
    }
    let span = output
        .independent
        .first()
        .map_or(name.span(), |(_, first)| first.span());
    if holonomic >= nv {
        return Err((
            span,
            format!(
                "`{name}` linearises on the constraint manifold with one dependent coordinate \
                 per holonomic constraint, but this system has {holonomic} holonomic \
                 constraint(s) for {nv} coordinate(s): redundant constraints (or nothing left \
                 to move), which `{name}` does not support; to linearise it, write the model \
                 without its redundant constraints"
            ),
        ));
    }
    if output.independent.len() + holonomic != nv {
        let plain_names: Vec<String> = plain
            .iter()
            .map(|&(_, c)| model.coordinates[c].to_string())
            .collect();
        return Err((
            span,
            format!(
                "`{name}` linearises a system with constraints on the constraint manifold: \
                 name its {} independent coordinate(s) in parentheses, as `{name}({})` ({}, \
                 less {holonomic} holonomic constraint(s)); the others are found from the \
                 constraints",
                nv.saturating_sub(holonomic),
                plain_names.last().map_or("J_wx", String::as_str),
                match model.balls.is_empty() {
                    true => format!(
                        "{} coordinates `{}`",
                        plain_names.len(),
                        plain_names.join("`, `")
                    ),
                    false => format!(
                        "{nv} tangent directions, a free or spherical joint's named by its \
                         speeds"
                    ),
                },
            ),
        ));
    }
    Ok(coordinates)
}

/// Whether each speed is among the independent speeds of `output` (after
/// `;`), which must be as many as the speeds less the rows; or what is
/// wrong, at which token.
fn independent_speeds(
    model: &Model,
    pool: &mut Pool,
    output: &Output,
) -> Result<Vec<bool>, (Span, String)> {
    let (name, nv, nc) = (
        &output.function,
        model.nv(),
        model.acting_constraints().count(),
    );
    let plain = plain_speeds(model);
    let mut speeds = vec![false; nv];
    for (sym, ident) in &output.independent_speeds {
        let speed = match *sym {
            Sym::Coord(c) => plain
                .iter()
                .find(|&&(k, p)| p == c as usize && pool.rate(c) == pool.sym(Sym::Speed(k as u32)))
                .map(|&(k, _)| k),
            Sym::Speed(k) => Some(k as usize),
            _ => None,
        };
        let Some(k) = speed else {
            return Err((
                ident.span(),
                format!(
                    "`dt({ident})` is not one of the speeds (a `speeds` statement or a joint \
                     gives this coordinate's rate): name the speed itself"
                ),
            ));
        };
        if speeds[k] {
            return Err((
                ident.span(),
                format!("the speed of `{ident}` is named twice"),
            ));
        }
        speeds[k] = true;
    }
    if output.independent_speeds.len() + nc != nv {
        let span = output
            .independent_speeds
            .first()
            .map_or(name.span(), |(_, first)| first.span());
        let example_speeds: Vec<String> = model.speeds[nc.min(nv)..]
            .iter()
            .map(|s| s.written())
            .collect();
        let given = match output.independent_speeds.is_empty() {
            true => String::new(),
            false => format!(
                " (`{}` are {})",
                written(&output.independent_speeds),
                output.independent_speeds.len()
            ),
        };
        return Err((
            span,
            format!(
                "`{name}` linearises a system with nonholonomic constraints: name its {} \
                 independent speed(s) after `;`, as `{name}({}; {})` ({nv} speeds, less \
                 {nc} constraint(s)){given}; the others are found from the constraints",
                nv.saturating_sub(nc),
                written(&output.independent),
                example_speeds.join(", "),
            ),
        ));
    }
    Ok(speeds)
}
