//! One handler per statement: what each adds to the model (names,
//! coordinates and speeds, frames and points, masses, loads, constraints,
//! outputs), checking on the way what only that statement can get wrong.

use super::Resolver;
use super::evaluate::{
    CONSTRAINT, DISSIPATION, GEOMETRY, GRAVITY, KINEMATICS, LOAD, MASS, POTENTIAL,
};
use super::list;
use super::scope::{Binding, is_plain};
use crate::expr::{ExprId, Node, Sym, SymKinds};
use crate::language::ast::{Expr, Field, OutputRequest, SpanRange, Statement};
use crate::model::closure::{ClosureKind, closure_rows};
use crate::model::{
    Ball, Body, Constraint, Force, FrameId, JointKind, NEWTONIAN, Particle, PointId, Speed, Torque,
    Vector, quaternion, unit_axis,
};
use proc_macro2::Ident;

/// The rotations a frame statement may use, by axis.
pub(super) const ROTATIONS: [&str; 3] = ["rotate_x", "rotate_y", "rotate_z"];

/// The rotation of a frame about a constant axis.
pub(super) const ROTATE: &str = "rotate";

/// The kinds of `joint KIND NAME { .. }`, by keyword.
const JOINT_KINDS: [(&str, JointKind); 4] = [
    ("revolute", JointKind::Revolute),
    ("prismatic", JointKind::Prismatic),
    ("spherical", JointKind::Spherical),
    ("free", JointKind::Free),
];

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

/// What `linearize(..)` names as independent: coordinates (before `;`,
/// where a free or spherical joint's speeds stand for its tangent
/// directions) or speeds (after `;`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Independent {
    Coordinates,
    Speeds,
}

impl Independent {
    /// The word for them in messages.
    fn noun(self) -> &'static str {
        match self {
            Independent::Coordinates => "coordinates",
            Independent::Speeds => "speeds",
        }
    }

    /// Whether a coordinate's name, written as its rate `dt(..)` or not,
    /// names one of them: any coordinate among the coordinates, only its
    /// rate among the speeds.
    fn takes_coordinate(self, rate: bool) -> bool {
        rate || self == Independent::Coordinates
    }
}

impl Resolver {
    pub(super) fn statement(&mut self, statement: &Statement) {
        match statement {
            Statement::Parameters(names) => self.declare_scalars(names, ScalarKind::Parameter),
            Statement::Coordinates(names) => self.declare_scalars(names, ScalarKind::Coordinate),
            Statement::Inputs(names) => self.declare_scalars(names, ScalarKind::Input),
            Statement::Frame { name, value } => self.frame_statement(name, value),
            Statement::Point { name, value } => match self.point_value(value, GEOMETRY) {
                Some(placement) => {
                    self.define_point(name, Some(placement));
                }
                None => {
                    self.define(name, Binding::Invalid);
                }
            },
            Statement::Body { name, fields } => self.body(name, fields),
            Statement::Particle { name, fields } => self.particle(name, fields),
            Statement::Joint { kind, name, fields } => self.joint(kind, name, fields),
            Statement::Gravity { value, .. } => {
                if let Some(g) = self.vector(value, GRAVITY) {
                    let total = match self.model.gravity.take() {
                        Some(previous) => previous.add(&g, &mut self.pool),
                        None => g,
                    };
                    self.model.gravity = Some(total);
                }
            }
            Statement::Force { value, at, .. } => {
                let vector = self.vector(value, LOAD);
                let at = self.point(at, GEOMETRY);
                if let (Some(vector), Some(at)) = (vector, at) {
                    self.model.forces.push(Force { vector, at });
                }
            }
            Statement::Torque {
                value,
                on,
                reacting,
                ..
            } => self.torque(value, on, reacting.as_ref()),
            Statement::Potential { value, .. } => {
                if let Some(v) = self.scalar(value, POTENTIAL) {
                    self.model.potential = self.pool.add(self.model.potential, v);
                }
            }
            Statement::Dissipation { value, .. } => {
                if let Some(d) = self.scalar(value, DISSIPATION) {
                    self.model.dissipation = self.pool.add(self.model.dissipation, d);
                }
            }
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

    pub(super) fn frame_statement(&mut self, name: &Ident, value: &Expr) {
        let Expr::MethodCall {
            receiver,
            method,
            args,
            ..
        } = value
        else {
            self.define(name, Binding::Invalid);
            self.errors.push(
                value.range(),
                format!(
                    "expected a rotation of a frame, such as `N.rotate_z(angle)`, for frame `{name}`"
                ),
            );
            return;
        };
        let parent = self.frame_name(receiver);
        let rotation = match ROTATIONS.iter().position(|r| method == r) {
            Some(axis) => match args.as_slice() {
                [angle] => {
                    let axis = unit_axis(&self.pool, axis);
                    self.scalar(angle, GEOMETRY).map(|angle| (axis, angle))
                }
                _ => {
                    self.errors.push(
                        value.range(),
                        format!(
                            "`{method}` takes one argument, the angle; found {}",
                            args.len()
                        ),
                    );
                    None
                }
            },
            None if method == ROTATE => match args.as_slice() {
                [axis, angle] => {
                    let axis = self.constant_axis(axis);
                    let angle = self.scalar(angle, GEOMETRY);
                    axis.zip(angle)
                }
                _ => {
                    self.errors.push(
                        value.range(),
                        format!(
                            "`rotate` takes two arguments, the axis `[ax, ay, az]` and the angle; found {}",
                            args.len()
                        ),
                    );
                    None
                }
            },
            None => {
                self.errors.push(
                    method.span(),
                    format!(
                        "unknown method `{method}`; a frame is made with `rotate_x`, `rotate_y`, `rotate_z` or `rotate([ax, ay, az], angle)`"
                    ),
                );
                None
            }
        };
        match (parent, rotation) {
            (Some(parent), Some((axis, angle))) => {
                self.define_frame(name, parent, axis, angle, None);
            }
            _ => {
                self.define(name, Binding::Invalid);
            }
        }
    }

    pub(super) fn body(&mut self, name: &Ident, fields: &[Field]) {
        let [mass, center, frame, inertia] =
            self.fields(name, "body", fields, ["mass", "center", "frame", "inertia"]);
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
        }
    }

    pub(super) fn particle(&mut self, name: &Ident, fields: &[Field]) {
        let [mass, at] = self.fields(name, "particle", fields, ["mass", "at"]);
        let mass = mass.and_then(|e| self.mass(e, "a point without mass needs no particle"));
        let at = at.and_then(|e| self.point(e, GEOMETRY));
        self.define(name, Binding::Particle);
        if let (Some(mass), Some(at)) = (mass, at) {
            self.model.particles.push(Particle { mass, at });
        }
    }

    /// `joint revolute J { parent: F, child: B, axis: z, coordinate: q, at: P };`
    /// makes frame `B = F.rotate_z(q)` and point `J = P`;
    /// `joint prismatic J { ... }` makes `B` parallel to `F` and
    /// `J = P + q * F.z`.
    pub(super) fn joint(&mut self, keyword: &Ident, name: &Ident, fields: &[Field]) {
        let Some(&(_, kind)) = JOINT_KINDS.iter().find(|(k, _)| keyword == k) else {
            self.errors.push(
                keyword.span(),
                format!(
                    "unknown joint kind `{keyword}`; expected `revolute`, `prismatic`, \
                     `spherical` or `free`"
                ),
            );
            return self.invalid_joint(name, fields);
        };
        if matches!(kind, JointKind::Spherical | JointKind::Free) {
            return self.ball_joint(name, fields, kind);
        }
        let [parent, child, axis, coordinate, at] = self.fields(
            name,
            "joint",
            fields,
            ["parent", "child", "axis", "coordinate", "at"],
        );
        let parent = parent.and_then(|e| self.frame(e));
        let axis = axis.and_then(|e| self.axis_name(e));
        let coordinate = coordinate.and_then(|e| self.joint_coordinate_name(e));
        let at = at.and_then(|e| self.point_value(e, GEOMETRY));
        let child = child.and_then(|e| self.child_name(e));
        let (
            Some(parent),
            Some(axis),
            Some((index, coordinate)),
            Some((base, offset)),
            Some(child),
        ) = (parent, axis, coordinate, at, child)
        else {
            return self.invalid_joint(name, fields);
        };
        self.joint_of_coordinate.insert(index, name.clone());
        if kind == JointKind::Revolute {
            if self.define_frame(child, parent, axis, coordinate, None) {
                self.define_point(name, Some((base, offset)));
            }
        } else {
            let zero = self.pool.zero();
            self.define_frame(child, parent, axis, zero, None);
            let slide = Vector {
                parts: vec![(parent, axis)],
            }
            .scale(coordinate, &mut self.pool);
            let offset = offset.add(&slide, &mut self.pool);
            self.define_point(name, Some((base, offset)));
        }
    }

    /// `joint spherical J { parent: F, child: B, at: P };` turns `B` from
    /// `F` by the unit quaternion `(J_qx, J_qy, J_qz, J_qw)` about the point
    /// `J = P`, with the speeds `J_wx, J_wy, J_wz` (angular velocity in
    /// `B`'s axes); `joint free J { parent: N, child: B, at: P };` also
    /// moves the point `J = P + J_x N.x + J_y N.y + J_z N.z`, first in the
    /// coordinates, with the speeds `J_vx, J_vy, J_vz` (its velocity in
    /// `B`'s axes) before the angular ones.
    pub(super) fn ball_joint(&mut self, name: &Ident, fields: &[Field], kind: JointKind) {
        let free = kind == JointKind::Free;
        let what = if free {
            "free joint"
        } else {
            "spherical joint"
        };
        let [parent_field, child, at] = self.fields(name, what, fields, ["parent", "child", "at"]);
        let parent = parent_field.and_then(|e| self.frame(e));
        let at_value = at.and_then(|e| self.point_value(e, GEOMETRY));
        if let (true, Some(parent), Some(e)) = (free, parent, parent_field) {
            self.check_free_joint_parent(e, parent);
        }
        if let (true, Some((base, offset)), Some(e)) = (free, &at_value, at) {
            self.check_free_joint_origin(e, *base, offset);
        }
        let child = child.and_then(|e| self.child_name(e));
        let (Some(parent), Some((base, offset)), Some(child), true) =
            (parent, at_value, child, is_plain(&name.to_string()))
        else {
            return self.invalid_joint(name, fields);
        };
        let named = |suffix: &str| Ident::new(&format!("{name}_{suffix}"), name.span());
        let position = free.then(|| ["x", "y", "z"].map(|c| self.joint_coordinate(&named(c))));
        let quaternion = ["qx", "qy", "qz", "qw"].map(|c| self.joint_coordinate(&named(c)));
        for &i in position.iter().flatten().chain(&quaternion) {
            self.joint_of_coordinate.insert(i, name.clone());
        }
        let velocity = free.then(|| ["vx", "vy", "vz"].map(|c| self.add_speed(&named(c), false)));
        let angular = ["wx", "wy", "wz"].map(|c| self.add_speed(&named(c), false));
        let q = quaternion.map(|i| self.pool.sym(Sym::Coord(i)));
        let omega = angular.map(|k| self.pool.sym(Sym::Speed(k)));
        let rates = quaternion::rates(&mut self.pool, q, omega);
        for (&i, rate) in quaternion.iter().zip(rates) {
            self.pool.set_rate(i, rate);
        }
        let mut origin = offset;
        if let (Some(position), Some(velocity)) = (position, velocity) {
            // ṙ = R v: the origin's velocity, given in the child's axes.
            let r = quaternion::rotation(&mut self.pool, q);
            let v = velocity.map(|k| self.pool.sym(Sym::Speed(k)));
            for (i, &coordinate) in position.iter().enumerate() {
                let terms: Vec<ExprId> = (0..3).map(|j| self.pool.mul(r[i][j], v[j])).collect();
                let rate = self.pool.sum(terms);
                self.pool.set_rate(coordinate, rate);
            }
            let components = position.map(|i| self.pool.sym(Sym::Coord(i)));
            let moved = Vector {
                parts: vec![(parent, components)],
            };
            origin = origin.add(&moved, &mut self.pool);
        }
        let ball = self.model.balls.len();
        let axis = unit_axis(&self.pool, 0);
        let zero = self.pool.zero();
        if self.define_frame(child, parent, axis, zero, Some(ball))
            && self.define_point(name, Some((base, origin)))
        {
            let as_index = |a: [u32; 3]| a.map(|i| i as usize);
            self.model.balls.push(Ball {
                frame: FrameId(self.model.frames.len() - 1),
                origin: PointId(self.model.points.len() - 1),
                quaternion: quaternion.map(|i| i as usize),
                angular: as_index(angular),
                translation: position
                    .zip(velocity)
                    .map(|(p, v)| (as_index(p), as_index(v))),
            });
        }
    }

    /// The name of a joint's new child frame.
    pub(super) fn child_name<'a>(&mut self, e: &'a Expr) -> Option<&'a Ident> {
        match e {
            Expr::Name(ident) => Some(ident),
            other => {
                self.errors
                    .push(other.range(), "expected the name of the new child frame");
                None
            }
        }
    }

    /// Defines the names of a joint with errors (already reported) as
    /// invalid, so that their uses stay silent.
    pub(super) fn invalid_joint(&mut self, name: &Ident, fields: &[Field]) {
        self.rejected_joint = true;
        self.define(name, Binding::Invalid);
        if let Some(Expr::Name(child)) = fields.iter().find(|f| f.name == "child").map(|f| &f.value)
        {
            self.define(child, Binding::Invalid);
        }
    }

    /// A revolute or prismatic joint's `coordinate`: the name of a declared
    /// coordinate that no other joint moves (its index and symbol). A
    /// parameter, `t` or an expression would make a fixed or driven joint
    /// whose frame has no coordinate of its own; a coordinate shared with
    /// another joint couples them, which `frame` statements spell out.
    fn joint_coordinate_name(&mut self, e: &Expr) -> Option<(u32, ExprId)> {
        let Expr::Name(ident) = e else {
            self.errors.push(
                e.range(),
                "expected the name of a coordinate: a joint turns or slides by one declared \
                 coordinate (for a motion given by an expression, write the `frame` and \
                 `point` statements)",
            );
            return None;
        };
        let index = match self.lookup(ident)? {
            Binding::Scalar(Sym::Coord(index)) => index,
            other => {
                self.errors.push(
                    ident.span(),
                    format!(
                        "`{ident}` is {}; a joint's coordinate must be one of the declared \
                         coordinates (`coordinates q1, ...;`)",
                        other.describe()
                    ),
                );
                return None;
            }
        };
        if let Some(joint) = self.joint_of_coordinate.get(&index) {
            let message = format!(
                "coordinate `{ident}` already moves joint `{joint}`; each joint needs a \
                 coordinate of its own (for joints that move together, write their `frame` \
                 and `point` statements)"
            );
            self.errors.push(ident.span(), message);
            return None;
        }
        Some((index, self.pool.sym(Sym::Coord(index))))
    }

    /// Declares a coordinate a joint makes (its speed comes with the joint).
    pub(super) fn joint_coordinate(&mut self, name: &Ident) -> u32 {
        let index = self.model.coordinates.len() as u32;
        self.model.coordinates.push(name.clone());
        self.define(name, Binding::Scalar(Sym::Coord(index)));
        index
    }

    /// `speeds w1, w2 { q1: rate1, q2: rate2 };`: the speeds `w` replace
    /// those of the coordinates named (`dt(q)`), taking their places in `v`
    /// in order, and `dt(qᵢ) = rateᵢ`, linear in the new speeds.
    pub(super) fn speeds_statement(&mut self, keyword: &Ident, names: &[Ident], rates: &[Field]) {
        if self.used_dt {
            self.errors.push(
                keyword.span(),
                "a `speeds` statement must come before every `dt(..)`: it changes what \
                 the speeds of its coordinates are",
            );
        }
        let mut replaced: Vec<(u32, usize)> = Vec::new();
        for field in rates {
            match self.replaceable_speed(&field.name) {
                Some(pair) if replaced.iter().all(|&(i, _)| i != pair.0) => replaced.push(pair),
                Some(_) => self.errors.push(
                    field.name.span(),
                    format!("the rate of `{}` is given twice", field.name),
                ),
                None => self.errors.push(
                    field.name.span(),
                    format!(
                        "`{}` is not a coordinate whose speed is still `dt({})`: a `speeds` \
                         statement gives the rates of coordinates of `coordinates` \
                         statements, once",
                        field.name, field.name
                    ),
                ),
            }
        }
        if names.len() != rates.len() {
            self.errors.push(
                keyword.span(),
                format!(
                    "{} new speed(s) for the rates of {} coordinate(s): a `speeds` \
                     statement replaces as many speeds as it names",
                    names.len(),
                    rates.len()
                ),
            );
        }
        if names.len() != replaced.len() {
            names.iter().for_each(|name| {
                self.define(name, Binding::Invalid);
            });
            return;
        }
        let mut slots: Vec<usize> = replaced.iter().map(|&(_, k)| k).collect();
        slots.sort_unstable();
        for (name, &k) in names.iter().zip(&slots) {
            self.model.speeds[k] = Speed {
                name: name.clone(),
                rate_of_coordinate: false,
            };
            self.define(name, Binding::Scalar(Sym::Speed(k as u32)));
        }
        for (field, &(i, _)) in rates.iter().zip(&replaced) {
            let read_dt = std::mem::replace(&mut self.used_dt, false);
            let rate = self.scalar(&field.value, KINEMATICS);
            if std::mem::replace(&mut self.used_dt, read_dt) {
                self.errors.push(
                    field.value.range(),
                    "a rate is written in the new speeds, without `dt(..)`",
                );
                continue;
            }
            let Some(rate) = rate else { continue };
            let foreign = self
                .pool
                .free_symbols(rate)
                .into_iter()
                .any(|sym| matches!(sym, Sym::Speed(k) if !slots.contains(&(k as usize))));
            let linear = slots.iter().all(|&k| {
                let d = self.pool.diff(rate, Sym::Speed(k as u32));
                !self.pool.kinds(d).intersects(SymKinds::SPEED)
            });
            if foreign || !linear {
                let written: Vec<String> = names.iter().map(ToString::to_string).collect();
                let written: Vec<&str> = written.iter().map(String::as_str).collect();
                self.errors.push(
                    field.value.range(),
                    format!(
                        "the rate of `{}` must be linear in the speeds of this statement ({}), \
                         with coefficients of coordinates and parameters",
                        field.name,
                        list(&written)
                    ),
                );
                continue;
            }
            self.pool.set_rate(i, rate);
            // Angular velocities computed before read the old rate.
            self.kinematics = None;
            let divisors = &mut self.model.rate_divisors;
            crate::model::singular::collect_rate_divisors(
                &mut self.pool,
                i as usize,
                rate,
                divisors,
            );
        }
    }

    /// The coordinate `name` and its speed, if the speed is still its rate
    /// `dt(name)`.
    pub(super) fn replaceable_speed(&self, name: &Ident) -> Option<(u32, usize)> {
        let Some((Binding::Scalar(Sym::Coord(i)), _)) = self.bindings.get(&name.to_string()) else {
            return None;
        };
        let k = self
            .model
            .speeds
            .iter()
            .position(|s| s.rate_of_coordinate && s.name == *name)?;
        Some((*i, k))
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

    pub(super) fn constraint(&mut self, keyword: &Ident, lhs: &Expr, rhs: &Expr) {
        let (Some(l), Some(r)) = (self.scalar(lhs, CONSTRAINT), self.scalar(rhs, CONSTRAINT))
        else {
            return;
        };
        let residual = self.pool.sub(l, r);
        let span = SpanRange::new(keyword.span(), rhs.range().end);
        if !self.check_constrains_something(span, residual) {
            return;
        }
        let nonholonomic = self.pool.kinds(residual).intersects(SymKinds::SPEED);
        if nonholonomic && !self.check_linear_in_speeds(span, residual) {
            return;
        }
        self.model.constraints.push(Constraint {
            residual,
            nonholonomic,
            vanishes: false,
        });
    }

    /// `closure NAME { at: P, to: Q };` (spherical), with `axis: F.z,
    /// along: G.z` (revolute) or `frame: F, welded: G` (welded): ordinary
    /// holonomic rows, those that vanish identically dropped (see
    /// [`closure_rows`]).
    pub(super) fn closure(&mut self, name: &Ident, fields: &[Field]) {
        let has = |pair: [&str; 2]| fields.iter().any(|f| pair.iter().any(|n| f.name == n));
        let (revolute, welded) = (has(["axis", "along"]), has(["frame", "welded"]));
        self.define(name, Binding::Closure);
        if revolute && welded {
            self.errors.push(
                name.span(),
                format!(
                    "closure `{name}` mixes the fields of a revolute closure (`axis`, `along`) \
                     and of a welded one (`frame`, `welded`); give one pair, or neither for a \
                     spherical closure"
                ),
            );
            return;
        }
        let (at, to, kind) = if revolute {
            let [at, to, axis, along] = self.fields(
                name,
                "revolute closure",
                fields,
                ["at", "to", "axis", "along"],
            );
            let axis = axis.and_then(|e| self.frame_axis(e));
            let along = along.and_then(|e| self.frame_axis(e));
            let kind = axis
                .zip(along)
                .map(|(axis, along)| ClosureKind::Revolute { axis, along });
            (at, to, kind)
        } else if welded {
            let [at, to, frame, welded] = self.fields(
                name,
                "welded closure",
                fields,
                ["at", "to", "frame", "welded"],
            );
            let frame = frame.and_then(|e| self.frame(e));
            let welded = welded.and_then(|e| self.frame(e));
            let kind = frame
                .zip(welded)
                .map(|(frame, welded)| ClosureKind::Welded { frame, welded });
            (at, to, kind)
        } else {
            let [at, to] = self.fields(name, "closure", fields, ["at", "to"]);
            (at, to, Some(ClosureKind::Spherical))
        };
        let at = at.and_then(|e| self.point(e, GEOMETRY));
        let to = to.and_then(|e| self.point(e, GEOMETRY));
        let (Some(at), Some(to), Some(kind)) = (at, to, kind) else {
            return;
        };
        let (mut added, mut rejected) = (0, 0);
        for row in closure_rows(&self.model, &mut self.pool, at, to, kind) {
            if self.pool.is_zero(row.residual) {
                continue;
            }
            if !self.pool.kinds(row.residual).intersects(SymKinds::COORD) {
                self.errors.push(
                    name.span(),
                    format!(
                        "closure `{name}` can never hold: {} involves no coordinate and is \
                         not identically zero; join points (and frames) that the coordinates move",
                        row.what
                    ),
                );
                rejected += 1;
                continue;
            }
            self.model.constraints.push(Constraint {
                residual: row.residual,
                nonholonomic: false,
                vanishes: false,
            });
            added += 1;
        }
        if added + rejected == 0 {
            self.errors.push(
                name.span(),
                format!(
                    "closure `{name}` constrains nothing: what it joins coincides in every \
                     configuration"
                ),
            );
        }
    }

    /// One item of `outputs`: a known name, with a point or a frame in
    /// parentheses when it needs one, asked for once.
    pub(super) fn output(&mut self, request: &OutputRequest) {
        use crate::model::output::{Availability, KINDS, Subject, function_name, kind, kind_list};
        let name = &request.name;
        let Some(&(_, subject, availability)) = KINDS.iter().find(|(k, ..)| name == k) else {
            self.errors.push(
                name.span(),
                format!("unknown output `{name}`; expected one of {}", kind_list()),
            );
            return;
        };
        if availability == Availability::NotYet {
            self.errors.push(
                name.span(),
                format!("the output `{name}` is not generated yet; remove it from `outputs`"),
            );
            return;
        }
        let (mut point, mut frame) = (None, None);
        let (mut independent, mut independent_speeds) = (Vec::new(), Vec::new());
        if let (false, Some(extra)) = (subject == Subject::Coordinates, request.more.first()) {
            let message = format!("`{name}` takes one point or frame: remove `, {extra}`");
            self.errors.push(extra.span(), message);
            return;
        }
        if let (false, Some(extra)) = (subject == Subject::Coordinates, request.speeds.first()) {
            let message = format!("`{name}` takes no speeds: remove `; {}`", extra.name);
            self.errors.push(extra.name.span(), message);
            return;
        }
        match (subject, &request.of) {
            (Subject::None | Subject::Coordinates, None) => {}
            (Subject::Coordinates, Some(of)) => {
                independent = self.independent_coordinates(of, &request.more);
                let speeds: Vec<(Ident, bool)> = request
                    .speeds
                    .iter()
                    .map(|s| (s.name.clone(), s.rate))
                    .collect();
                independent_speeds = self.independent_symbols(&speeds, Independent::Speeds);
                if independent.len() != 1 + request.more.len()
                    || independent_speeds.len() != speeds.len()
                {
                    return;
                }
            }
            (Subject::None, Some(of)) => {
                let message = format!("`{name}` takes no point or frame: write `{name}` alone");
                self.errors.push(of.span(), message);
                return;
            }
            (_, None) => {
                let what = if subject == Subject::Point {
                    "a point: `(P)`"
                } else {
                    "a frame: `(B)`"
                };
                self.errors
                    .push(name.span(), format!("`{name}` needs {what} after its name"));
                return;
            }
            (Subject::Point, Some(of)) => {
                match self.lookup_expecting(of, "a point defined above") {
                    Some(Binding::Point(p)) => point = Some(p),
                    Some(other) => {
                        let message =
                            format!("`{of}` is {}; `{name}` expects a point", other.describe());
                        self.errors.push(of.span(), message);
                    }
                    None => {}
                }
            }
            (Subject::Frame, Some(of)) => frame = self.frame_name(of),
        }
        let axes = match &request.axes {
            Some(f) => self.frame_name(f),
            None => Some(NEWTONIAN),
        };
        let (Some(kind), Some(axes)) = (kind(&name.to_string(), point, frame), axes) else {
            return;
        };
        if request.axes.is_some() && subject == Subject::None {
            self.errors.push(
                name.span(),
                format!("`{name}` has no axes to choose: remove `in`"),
            );
            return;
        }
        let of = request
            .of
            .as_ref()
            .filter(|_| subject != Subject::Coordinates);
        let function = function_name(name, of, request.axes.as_ref());
        let same =
            |o: &&crate::model::Output| o.function == function || (o.kind, o.axes) == (kind, axes);
        if let Some(earlier) = self.model.outputs.iter().find(same) {
            let message = format!(
                "this output is already asked for, as `{}`; ask for it once",
                earlier.function
            );
            self.errors.push(name.span(), message);
            return;
        }
        self.model.outputs.push(crate::model::Output {
            kind,
            axes,
            function,
            subject: of.map(Ident::to_string),
            axes_name: request
                .axes
                .as_ref()
                .map_or("N".to_string(), Ident::to_string),
            independent,
            independent_speeds,
            chart: None,
        });
    }

    /// `linearize(a, b)`'s names as coordinates (or a free or spherical
    /// joint's speeds, for its tangent directions), each once; an error at
    /// each name that is neither.
    fn independent_coordinates(&mut self, first: &Ident, more: &[Ident]) -> Vec<(Sym, Ident)> {
        let names: Vec<(Ident, bool)> = std::iter::once(first)
            .chain(more)
            .map(|n| (n.clone(), false))
            .collect();
        self.independent_symbols(&names, Independent::Coordinates)
    }

    /// The symbols of `names` (with whether each was written `dt(..)`) as
    /// `linearize(..)` names its independent coordinates or speeds (`which`);
    /// each once, an error at each that is neither.
    fn independent_symbols(
        &mut self,
        names: &[(Ident, bool)],
        which: Independent,
    ) -> Vec<(Sym, Ident)> {
        let mut independent: Vec<(Sym, Ident)> = Vec::new();
        for (name, rate) in names {
            let sym = match self.lookup(name) {
                Some(Binding::Scalar(sym @ Sym::Coord(_))) if which.takes_coordinate(*rate) => {
                    Some(sym)
                }
                Some(Binding::Scalar(sym @ Sym::Speed(_))) if !rate => Some(sym),
                Some(other) => {
                    let hint = match which {
                        Independent::Speeds => format!(" (a coordinate's speed as `dt({name})`)"),
                        Independent::Coordinates => String::new(),
                    };
                    let message = format!(
                        "`{name}` is {}; `linearize(..)` names the independent {}{hint}",
                        other.describe(),
                        which.noun()
                    );
                    self.errors.push(name.span(), message);
                    None
                }
                None => None,
            };
            match sym {
                Some(sym) if independent.iter().any(|(s, _)| *s == sym) => {
                    self.errors
                        .push(name.span(), format!("`{name}` is named twice"));
                }
                Some(sym) => independent.push((sym, name.clone())),
                None => {}
            }
        }
        independent
    }
}
