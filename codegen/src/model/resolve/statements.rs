//! One handler per statement, dispatched here by kind: what each adds to
//! the model. The declarations (`parameters`, `coordinates`, `inputs`),
//! the masses (`body`, `particle`) and the loads (`gravity`, `force`,
//! `torque`, `potential`, `dissipation`, `armature`) are here; the other
//! statements have a file each (`frames`, `joints`, `speeds`,
//! `constraints`, `rolling`, `outputs`).

use super::Resolver;
use super::evaluate::{DISSIPATION, GEOMETRY, GRAVITY, LOAD, MASS, POTENTIAL};
use super::scope::Binding;
use crate::expr::{Node, Sym};
use crate::language::ast::{Expr, Field, Statement};
use crate::language::keyword::field;
use crate::model::{Body, Force, FrameId, Particle, Speed, Torque};
use proc_macro2::Ident;

/// The scalars a declaration statement (`parameters`, `coordinates`,
/// `inputs`) makes.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum ScalarKind {
    Parameter,
    Coordinate,
    Input,
}

impl ScalarKind {
    /// The symbol of the `index`-th scalar of this kind.
    fn symbol(self, index: u32) -> Sym {
        match self {
            ScalarKind::Parameter => Sym::Param(index),
            ScalarKind::Coordinate => Sym::Coord(index),
            ScalarKind::Input => Sym::Input(index),
        }
    }
}

impl Resolver {
    pub(super) fn statement(&mut self, statement: &Statement) {
        match statement {
            Statement::Parameters(names) => self.declare_scalars(names, ScalarKind::Parameter),
            Statement::Coordinates(names) => self.declare_scalars(names, ScalarKind::Coordinate),
            Statement::Inputs(names) => self.declare_scalars(names, ScalarKind::Input),
            Statement::Frame { name, value } => self.frame_statement(name, value),
            Statement::Point { name, value } => self.point_statement(name, value),
            Statement::Body { name, fields } => self.body(name, fields),
            Statement::Particle { name, fields } => self.particle(name, fields),
            Statement::Joint { kind, name, fields } => self.joint(kind, name, fields),
            Statement::Gravity { value, .. } => self.gravity(value),
            Statement::Force { value, at, .. } => self.force(value, at),
            Statement::Torque {
                value,
                on,
                reacting,
                ..
            } => self.torque(value, on, reacting.as_ref()),
            Statement::Potential { value, .. } => self.potential(value),
            Statement::Dissipation { value, .. } => self.dissipation(value),
            Statement::Armature { value, speed } => self.armature(value, speed),
            Statement::Constraint {
                keyword, lhs, rhs, ..
            } => self.constraint(keyword, lhs, rhs),
            Statement::Closure { name, fields } => self.closure(name, fields),
            Statement::Rolling { name, fields } => self.rolling(name, fields),
            Statement::Outputs(requests) => requests.iter().for_each(|r| self.output(r)),
            Statement::Speeds {
                keyword,
                names,
                rates,
            } => self.speeds_statement(keyword, names, rates),
        }
    }

    pub(super) fn declare_scalars(&mut self, names: &[Ident], kind: ScalarKind) {
        for name in names {
            let list = match kind {
                ScalarKind::Parameter => &mut self.model.parameters,
                ScalarKind::Coordinate => &mut self.model.coordinates,
                ScalarKind::Input => &mut self.model.inputs,
            };
            let index = list.len() as u32;
            list.push(name.clone());
            self.define(name, Binding::Scalar(kind.symbol(index)));
            if kind == ScalarKind::Coordinate {
                let k = self.add_speed(name, true);
                // While every rate is its own speed, the pool needs no rates
                // (and the speed's symbol is made when first used).
                if k != index || !self.pool.rates_are_speeds() {
                    let speed = self.pool.sym(Sym::Speed(k));
                    self.pool.set_rate(index, speed);
                }
            }
        }
    }

    /// Adds a speed: the rate `dt(name)` of the coordinate `name`, or a
    /// speed of its own called `name`; its index.
    pub(super) fn add_speed(&mut self, name: &Ident, rate_of_coordinate: bool) -> u32 {
        let k = self.model.speeds.len() as u32;
        self.model.speeds.push(Speed {
            name: name.clone(),
            rate_of_coordinate,
        });
        if !rate_of_coordinate {
            self.define(name, Binding::Scalar(Sym::Speed(k)));
        }
        k
    }

    pub(super) fn body(&mut self, name: &Ident, fields: &[Field]) {
        let [mass, center, frame, inertia] = self.fields(
            name,
            "body",
            fields,
            [field::MASS, field::CENTER, field::FRAME, field::INERTIA],
        );
        let mass = mass.and_then(|e| self.mass(e, "a frame without mass needs no body"));
        let center = center.and_then(|e| self.point(e, GEOMETRY));
        let frame = frame.and_then(|e| self.frame(e));
        let inertia = inertia.and_then(|e| self.inertia(e));
        self.define(name, Binding::Body);
        if let (Some(mass), Some(center), Some(frame), Some(inertia)) =
            (mass, center, frame, inertia)
        {
            self.model.bodies.push(Body {
                mass,
                center,
                frame,
                inertia,
            });
            self.model.names.bodies.push(name.clone());
        }
    }

    pub(super) fn particle(&mut self, name: &Ident, fields: &[Field]) {
        let [mass, at] = self.fields(name, "particle", fields, [field::MASS, field::AT]);
        let mass = mass.and_then(|e| self.mass(e, "a point without mass needs no particle"));
        let at = at.and_then(|e| self.point(e, GEOMETRY));
        self.define(name, Binding::Particle);
        if let (Some(mass), Some(at)) = (mass, at) {
            self.model.particles.push(Particle { mass, at });
            self.model.names.particles.push(name.clone());
        }
    }
    /// `gravity vec;`: added to the uniform field of the earlier ones.
    fn gravity(&mut self, value: &Expr) {
        if let Some(g) = self.vector(value, GRAVITY) {
            let total = match self.model.gravity.take() {
                Some(previous) => previous.add(&g, &mut self.pool),
                None => g,
            };
            self.model.gravity = Some(total);
        }
    }

    /// `force vec at P;`.
    fn force(&mut self, value: &Expr, at: &Expr) {
        let vector = self.vector(value, LOAD);
        let at = self.point(at, GEOMETRY);
        if let (Some(vector), Some(at)) = (vector, at) {
            self.model.forces.push(Force { vector, at });
        }
    }

    /// `potential V;`: added to the earlier ones.
    fn potential(&mut self, value: &Expr) {
        if let Some(v) = self.scalar(value, POTENTIAL) {
            self.model.potential = self.pool.add(self.model.potential, v);
        }
    }

    /// `dissipation D;`: added to the earlier ones.
    fn dissipation(&mut self, value: &Expr) {
        if let Some(d) = self.scalar(value, DISSIPATION) {
            self.model.dissipation = self.pool.add(self.model.dissipation, d);
        }
    }

    pub(super) fn torque(&mut self, value: &Expr, on: &Expr, reacting: Option<&Expr>) {
        let vector = self.vector(value, LOAD);
        let on = self.frame(on);
        let reacting = match reacting {
            Some(e) => self.reacting_frame(e, on),
            None => Some(None),
        };
        if let (Some(vector), Some(on), Some(reacting)) = (vector, on, reacting) {
            self.model.torques.push(Torque {
                vector,
                on,
                reacting,
            });
        }
    }

    /// `armature a on v;`: `a` (parameters only) added to `M`'s diagonal
    /// entry of the speed `v`, which is `dt(q)` of a coordinate or a
    /// joint's speed, as a rotor's inertia reflected through its gearbox.
    fn armature(&mut self, value: &Expr, speed: &Expr) {
        let value = self.scalar(value, MASS);
        let target = self.scalar(speed, DISSIPATION);
        let speed_index = target.and_then(|s| match self.pool.node(s) {
            Node::Sym(Sym::Speed(k)) => Some(*k as usize),
            _ => None,
        });
        if target.is_some() && speed_index.is_none() {
            self.errors.push(
                speed.range(),
                "expected a speed after `on`: `dt(q)` of a coordinate whose rate is its speed, \
                 or a joint's speed such as `ball_wx`",
            );
        }
        if let (Some(value), Some(k)) = (value, speed_index) {
            self.model.armature.push((k, value));
        }
    }

    /// The frame `G` of `torque vec on F reacting G;`: another frame than
    /// `F` (on `F` itself, the torque and its reaction would cancel).
    fn reacting_frame(&mut self, e: &Expr, on: Option<FrameId>) -> Option<Option<FrameId>> {
        let reacting = self.frame(e)?;
        if on == Some(reacting) {
            self.errors.push(
                e.range(),
                "a torque cannot react on the frame it acts on (the two would cancel); \
                 expected the other frame of the motor, such as the parent of the driven one",
            );
            return None;
        }
        Some(Some(reacting))
    }
}
