//! Name resolution and checking: walks the statements in order, binds each
//! name, evaluates every expression into the engine's pool with its type
//! (scalar, vector, point, frame) and checks each rule of the language where
//! the offending token is at hand.
//!
//! Files, by concern: `statements` (the dispatch by statement kind, with
//! the declarations, masses and loads), one file per larger statement
//! (`frames`, `joints`, `speeds`, `constraints`, `rolling`, `outputs`), `scope`
//! (names and definitions), `evaluate` (typed expressions), `fields` (the
//! `{ field: value }` blocks) and `rules` (one `check_*` function per rule
//! beyond types and names, with the reason for it). They share one
//! [`Resolver`], defined here.

mod constraints;
mod evaluate;
mod fields;
mod frames;
mod joints;
mod outputs;
mod rolling;
mod rules;
mod scope;
mod speeds;
mod statements;
mod vectors;

use super::algebra::Geometry;
use super::{Errors, Frame, Model, NEWTONIAN, Names, ORIGIN, Point, Tree};
use crate::expr::{Pool, Sym};
use crate::kinematics::Kinematics;
use crate::language::ast::System;
use proc_macro2::{Ident, Span};
use scope::{Binding, defined_names};
pub(crate) use scope::{builtin_names, is_builtin, is_plain};
use std::collections::HashMap;

/// Resolves and checks a parsed system: the model and the pool its
/// expressions live in; all errors are reported together.
pub fn resolve(system: &System) -> syn::Result<(Model, Pool)> {
    let mut resolver = Resolver::new(system);
    resolver.check_plain(&system.name);
    for statement in &system.statements {
        resolver.statement(statement);
    }
    resolver.finish()
}

/// The state of one resolution: the pool the expressions go into, the
/// errors so far, the names bound so far and the model being built.
struct Resolver {
    pool: Pool,
    errors: Errors,
    bindings: HashMap<String, (Binding, Span)>,
    /// Every name some statement defines, for "used before its definition".
    defined_anywhere: HashMap<String, Span>,
    /// Whether a `dt(..)` has been read (a `speeds` statement must come
    /// before: it changes what `dt` of its coordinates means).
    used_dt: bool,
    /// The joint that each coordinate moves, by the coordinate's index: a
    /// joint's coordinate is its own.
    joint_of_coordinate: HashMap<u32, Ident>,
    /// Whether a joint statement was rejected: it may have been meant to
    /// make the system's coordinates (a free or spherical joint).
    rejected_joint: bool,
    /// The kinematics of the frames and points so far, with the numbers of
    /// frames and points it was computed for (see [`Resolver::with_geometry`]).
    kinematics: Option<(usize, usize, Kinematics)>,
    model: Model,
}

impl Resolver {
    fn new(system: &System) -> Resolver {
        let pool = Pool::with_positive_sums();
        let zero = pool.zero();
        let mut bindings = HashMap::new();
        let builtin = Span::call_site();
        bindings.insert("N".to_string(), (Binding::Frame(NEWTONIAN), builtin));
        bindings.insert("O".to_string(), (Binding::Point(ORIGIN), builtin));
        bindings.insert("t".to_string(), (Binding::Scalar(Sym::Time), builtin));
        Resolver {
            pool,
            errors: Errors::default(),
            bindings,
            defined_anywhere: defined_names(system),
            used_dt: false,
            joint_of_coordinate: HashMap::new(),
            rejected_joint: false,
            kinematics: None,
            model: Model {
                docs: system.docs.clone(),
                public: system.public,
                name: system.name.clone(),
                parameters: Vec::new(),
                coordinates: Vec::new(),
                speeds: Vec::new(),
                balls: Vec::new(),
                rate_divisors: Vec::new(),
                inputs: Vec::new(),
                frames: vec![Frame { placement: None }],
                points: vec![Point { placement: None }],
                bodies: Vec::new(),
                particles: Vec::new(),
                gravity: None,
                forces: Vec::new(),
                torques: Vec::new(),
                potential: zero,
                dissipation: zero,
                armature: Vec::new(),
                constraints: Vec::new(),
                tree: None,
                outputs: Vec::new(),
                names: Names::default(),
            },
        }
    }

    /// Runs `f` on the model's geometry so far: its kinematics are computed
    /// again only when a frame or point was added since the last call (the
    /// pool's rates are fixed by then: a `speeds` statement comes before
    /// every `dt(..)`, and so before every velocity).
    fn with_geometry<R>(&mut self, f: impl FnOnce(&Geometry<'_>, &mut Pool) -> R) -> R {
        let size = (self.model.frames.len(), self.model.points.len());
        let kinematics = match self.kinematics.take() {
            Some((frames, points, kinematics)) if (frames, points) == size => kinematics,
            _ => Kinematics::new(&self.model, &mut self.pool),
        };
        let geometry = Geometry {
            model: &self.model,
            kinematics: &kinematics,
        };
        let result = f(&geometry, &mut self.pool);
        self.kinematics = Some((size.0, size.1, kinematics));
        result
    }

    fn finish(mut self) -> syn::Result<(Model, Pool)> {
        self.check_has_coordinates();
        self.check_solved_outputs();
        self.model.tree = Tree::of(&self.model, &mut self.pool);
        self.errors.finish((self.model, self.pool))
    }
}

fn list(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    match quoted.as_slice() {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}
