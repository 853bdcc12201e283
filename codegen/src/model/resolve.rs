//! Name resolution and checking: walks the statements in order, binds each
//! name, evaluates every expression into the engine's pool with its type
//! (scalar, vector, point, frame) and checks each rule of the language where
//! the offending token is at hand.

use super::closure::{ClosureKind, FrameAxis, closure_rows};
use super::{
    Ball, Body, Constraint, Errors, Force, Frame, FrameId, FramePlacement, Model, NEWTONIAN,
    ORIGIN, Particle, Point, PointId, Speed, Torque, Tree, Vector, quaternion, unit_axis,
};
use crate::expr::{ExprId, Func, Number, Pool, Sym, SymKinds};
use crate::language::ast::{BinOp, Expr, Field, OutputRequest, SpanRange, Statement, System};
use proc_macro2::{Ident, Span};
use std::collections::HashMap;

/// Resolves and checks a parsed system; all errors are reported together.
pub fn resolve(system: &System) -> syn::Result<Model> {
    let mut resolver = Resolver::new(system);
    for statement in &system.statements {
        resolver.statement(statement);
    }
    resolver.finish()
}

/// The built-in names, which no statement may define again.
const BUILTINS: [&str; 3] = ["N", "O", "t"];

/// The scalar functions of the language, with `dt`.
const FUNCTIONS: [(&str, Option<Func>); 8] = [
    ("sin", Some(Func::Sin)),
    ("cos", Some(Func::Cos)),
    ("tan", Some(Func::Tan)),
    ("sqrt", Some(Func::Sqrt)),
    ("exp", Some(Func::Exp)),
    ("ln", Some(Func::Ln)),
    ("abs", Some(Func::Abs)),
    ("dt", None),
];

/// The rotations a frame statement may use, by axis.
const ROTATIONS: [&str; 3] = ["rotate_x", "rotate_y", "rotate_z"];

/// The rotation of a frame about a constant axis.
const ROTATE: &str = "rotate";

/// Axis names of unit vectors and joint axes.
const AXES: [&str; 3] = ["x", "y", "z"];

/// What a name stands for at the point of use.
#[derive(Clone, Copy, Debug)]
enum Binding {
    Scalar(Sym),
    Frame(FrameId),
    Point(PointId),
    Body,
    Particle,
    Closure,
    /// A name whose definition had an error (already reported): later uses
    /// stay silent instead of repeating it.
    Invalid,
}

impl Binding {
    fn describe(self) -> &'static str {
        match self {
            Binding::Scalar(Sym::Param(_)) => "a parameter",
            Binding::Scalar(Sym::Coord(_)) => "a coordinate",
            Binding::Scalar(Sym::Input(_)) => "an input",
            Binding::Scalar(_) => "a built-in scalar",
            Binding::Frame(_) => "a frame",
            Binding::Point(_) => "a point",
            Binding::Body => "a body",
            Binding::Particle => "a particle",
            Binding::Closure => "a loop closure",
            Binding::Invalid => "a name with an error",
        }
    }
}

/// Where an expression is used, which decides the symbols it may contain.
#[derive(Clone, Copy)]
struct Use {
    allowed: SymKinds,
    role: &'static str,
}

const GEOMETRY: Use = Use {
    allowed: SymKinds::TIME.union(SymKinds::PARAM).union(SymKinds::COORD),
    role: "geometry (frame angles and point positions)",
};
const MASS: Use = Use {
    allowed: SymKinds::PARAM,
    role: "mass and inertia, which may depend on parameters only",
};
const GRAVITY: Use = Use {
    allowed: SymKinds::PARAM,
    role: "gravity, which may depend on parameters only",
};
const LOAD: Use = Use {
    allowed: SymKinds::TIME
        .union(SymKinds::PARAM)
        .union(SymKinds::COORD)
        .union(SymKinds::SPEED)
        .union(SymKinds::INPUT),
    role: "a load",
};
const POTENTIAL: Use = Use {
    allowed: SymKinds::PARAM.union(SymKinds::COORD),
    role: "a potential, which may depend on coordinates and parameters only",
};
const DISSIPATION: Use = Use {
    allowed: SymKinds::PARAM
        .union(SymKinds::COORD)
        .union(SymKinds::SPEED),
    role: "a dissipation function, which may depend on coordinates, speeds and parameters only",
};
const CONSTRAINT: Use = Use {
    allowed: SymKinds::TIME
        .union(SymKinds::PARAM)
        .union(SymKinds::COORD)
        .union(SymKinds::SPEED),
    role: "a constraint, which may not depend on inputs",
};
const KINEMATICS: Use = Use {
    allowed: SymKinds::PARAM
        .union(SymKinds::COORD)
        .union(SymKinds::SPEED),
    role: "a coordinate's rate, which may depend on coordinates, parameters and the new speeds only",
};
const AXIS: Use = Use {
    allowed: SymKinds::PARAM,
    role: "a rotation axis, which must be constant (numbers and parameters)",
};
const EXPONENT: Use = Use {
    allowed: SymKinds::EMPTY,
    role: "an exponent, which must be a constant integer",
};

/// A typed value of an expression.
enum Value {
    Scalar(ExprId),
    Vector(Vector),
    /// A point given as a base point plus an offset.
    Point(PointId, Vector),
    Frame(FrameId),
}

impl Value {
    fn describe(&self) -> &'static str {
        match self {
            Value::Scalar(_) => "a scalar",
            Value::Vector(_) => "a vector",
            Value::Point(..) => "a point",
            Value::Frame(_) => "a frame",
        }
    }
}

struct Resolver {
    pool: Pool,
    errors: Errors,
    bindings: HashMap<String, (Binding, Span)>,
    /// Every name some statement defines, for "used before its definition".
    defined_anywhere: HashMap<String, Span>,
    /// Whether a `dt(..)` has been read (a `speeds` statement must come
    /// before: it changes what `dt` of its coordinates means).
    used_dt: bool,
    model: Model,
}

impl Resolver {
    fn new(system: &System) -> Resolver {
        let pool = Pool::new();
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
                constraints: Vec::new(),
                moving_masses: Vec::new(),
                tree: None,
                outputs: Vec::new(),
                pool: Pool::default(),
            },
        }
    }

    fn finish(mut self) -> syn::Result<Model> {
        if self.model.coordinates.is_empty() {
            self.errors.push(
                self.model.name.span(),
                "a system needs at least one generalized coordinate: add `coordinates q1, ...;`",
            );
        }
        self.check_solved_outputs();
        self.model.tree = Tree::of(&self.model, &mut self.pool);
        self.model.pool = self.pool;
        self.errors.finish(self.model)
    }

    // ----- statements -------------------------------------------------

    fn statement(&mut self, statement: &Statement) {
        match statement {
            Statement::Parameters(names) => self.declare_scalars(names, Sym::Param),
            Statement::Coordinates(names) => self.declare_scalars(names, Sym::Coord),
            Statement::Inputs(names) => self.declare_scalars(names, Sym::Input),
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
            Statement::Constraint {
                keyword, lhs, rhs, ..
            } => self.constraint(keyword, lhs, rhs),
            Statement::Closure { name, fields } => self.closure(name, fields),
            Statement::Outputs(requests) => requests.iter().for_each(|r| self.output(r)),
            Statement::Speeds {
                keyword,
                names,
                rates,
            } => self.speeds_statement(keyword, names, rates),
        }
    }

    fn declare_scalars(&mut self, names: &[Ident], sym: fn(u32) -> Sym) {
        for name in names {
            let list = match sym(0) {
                Sym::Param(_) => &mut self.model.parameters,
                Sym::Coord(_) => &mut self.model.coordinates,
                _ => &mut self.model.inputs,
            };
            let index = list.len() as u32;
            list.push(name.clone());
            self.define(name, Binding::Scalar(sym(index)));
            if let Sym::Coord(_) = sym(0) {
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
    fn add_speed(&mut self, name: &Ident, rate_of_coordinate: bool) -> u32 {
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

    fn frame_statement(&mut self, name: &Ident, value: &Expr) {
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

    fn body(&mut self, name: &Ident, fields: &[Field]) {
        let [mass, center, frame, inertia] =
            self.fields(name, "body", fields, ["mass", "center", "frame", "inertia"]);
        let mass = mass.and_then(|e| self.mass(e));
        let center = center.and_then(|e| self.point(e, GEOMETRY));
        let frame = frame.and_then(|e| self.frame(e));
        let inertia = inertia.and_then(|e| self.inertia(e));
        if let (Some(center), Some(frame)) = (center, frame) {
            self.check_fixed_in_time(name, "body", center, Some(frame));
        }
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

    fn particle(&mut self, name: &Ident, fields: &[Field]) {
        let [mass, at] = self.fields(name, "particle", fields, ["mass", "at"]);
        let mass = mass.and_then(|e| self.mass(e));
        let at = at.and_then(|e| self.point(e, GEOMETRY));
        if let Some(at) = at {
            self.check_fixed_in_time(name, "particle", at, None);
        }
        self.define(name, Binding::Particle);
        if let (Some(mass), Some(at)) = (mass, at) {
            self.model.particles.push(Particle { mass, at });
        }
    }

    /// `joint revolute J { parent: F, child: B, axis: z, coordinate: q, at: P };`
    /// makes frame `B = F.rotate_z(q)` and point `J = P`;
    /// `joint prismatic J { ... }` makes `B` parallel to `F` and
    /// `J = P + q * F.z`.
    fn joint(&mut self, kind: &Ident, name: &Ident, fields: &[Field]) {
        let revolute = match kind.to_string().as_str() {
            "revolute" => true,
            "prismatic" => false,
            "free" => return self.ball_joint(name, fields, true),
            "spherical" => return self.ball_joint(name, fields, false),
            _ => {
                self.errors.push(
                    kind.span(),
                    format!(
                        "unknown joint kind `{kind}`; expected `revolute`, `prismatic`, \
                         `spherical` or `free`"
                    ),
                );
                return;
            }
        };
        let [parent, child, axis, coordinate, at] = self.fields(
            name,
            "joint",
            fields,
            ["parent", "child", "axis", "coordinate", "at"],
        );
        let parent = parent.and_then(|e| self.frame(e));
        let axis = axis.and_then(|e| self.axis_name(e));
        let coordinate = coordinate.and_then(|e| self.scalar(e, GEOMETRY));
        let at = at.and_then(|e| self.point_value(e, GEOMETRY));
        let child = child.and_then(|e| self.child_name(e));
        let (Some(parent), Some(axis), Some(coordinate), Some((base, offset)), Some(child)) =
            (parent, axis, coordinate, at, child)
        else {
            return self.invalid_joint(name, fields);
        };
        if revolute {
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

    /// One item of `outputs`: a known name, with a point or a frame in
    /// parentheses when it needs one, asked for once.
    fn output(&mut self, request: &OutputRequest) {
        use super::output::{Availability, KINDS, Subject, function_name, kind, kind_list};
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
        match (subject, &request.of) {
            (Subject::None, None) => {}
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
            (Subject::Point, Some(of)) => match self.lookup(of) {
                Some(Binding::Point(p)) => point = Some(p),
                Some(other) => {
                    let message =
                        format!("`{of}` is {}; `{name}` expects a point", other.describe());
                    self.errors.push(of.span(), message);
                }
                None => {}
            },
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
        let function = function_name(name, request.of.as_ref(), request.axes.as_ref());
        let same = |o: &&super::Output| o.function == function || (o.kind, o.axes) == (kind, axes);
        if let Some(earlier) = self.model.outputs.iter().find(same) {
            let message = format!(
                "this output is already asked for, as `{}`; ask for it once",
                earlier.function
            );
            self.errors.push(name.span(), message);
            return;
        }
        self.model.outputs.push(super::Output {
            kind,
            axes,
            function,
            subject: request.of.as_ref().map(Ident::to_string),
            axes_name: request
                .axes
                .as_ref()
                .map_or("N".to_string(), Ident::to_string),
        });
    }

    /// `accelerations_jacobian` and `linearize` solve `M v̇ = f`: with
    /// constraints, the accelerations and their derivatives live on the
    /// constraint manifold, which these outputs do not handle yet. The
    /// derivatives by `q` and the regressor are taken in the coordinates,
    /// so they need every speed to be its coordinate's rate.
    fn check_solved_outputs(&mut self) {
        use super::OutputKind::{
            AccelerationsJacobian, InverseDynamicsJacobian, Linearize, Regressor, Taylor,
        };
        if self.model.nq() != self.model.nv() {
            for output in &self.model.outputs {
                if matches!(
                    output.kind,
                    AccelerationsJacobian
                        | InverseDynamicsJacobian
                        | Linearize
                        | Regressor
                        | Taylor
                ) {
                    let name = &output.function;
                    self.errors.push(
                        name.span(),
                        format!(
                            "`{name}` is not available yet for a system whose speeds are not \
                             its coordinates' rates (a free or spherical joint, a `speeds` \
                             statement): remove it from `outputs`"
                        ),
                    );
                }
            }
        }
        if self.model.constraints.is_empty() {
            return;
        }
        for output in &self.model.outputs {
            if matches!(output.kind, AccelerationsJacobian | Linearize | Taylor) {
                let name = &output.function;
                self.errors.push(
                    name.span(),
                    format!(
                        "`{name}` is not available for a system with constraints yet \
                         (the derivatives would have to be taken on the constraint manifold): \
                         remove it from `outputs`, or describe the system with independent \
                         coordinates and no `constraint` statements"
                    ),
                );
            }
        }
    }

    /// `joint spherical J { parent: F, child: B, at: P };` turns `B` from
    /// `F` by the unit quaternion `(J_qx, J_qy, J_qz, J_qw)` about the point
    /// `J = P`, with the speeds `J_wx, J_wy, J_wz` (angular velocity in
    /// `B`'s axes); `joint free J { parent: N, child: B, at: P };` also
    /// moves the point `J = P + J_x N.x + J_y N.y + J_z N.z`, first in the
    /// coordinates, with the speeds `J_vx, J_vy, J_vz` (its velocity in
    /// `B`'s axes) before the angular ones.
    fn ball_joint(&mut self, name: &Ident, fields: &[Field], free: bool) {
        let what = if free {
            "free joint"
        } else {
            "spherical joint"
        };
        let [parent_field, child, at] = self.fields(name, what, fields, ["parent", "child", "at"]);
        let parent = parent_field.and_then(|e| self.frame(e));
        let at_value = at.and_then(|e| self.point_value(e, GEOMETRY));
        if let (true, Some(parent), Some(e)) = (free, parent, parent_field)
            && parent != NEWTONIAN
        {
            self.errors.push(
                e.range(),
                "a free joint joins a floating body to the ground: its parent must be `N` \
                 (a body on another body needs a spherical joint, or a free joint and a \
                 constraint)",
            );
        }
        if let (true, Some((base, offset)), Some(e)) = (free, &at_value, at)
            && self.point_moves(*base, offset)
        {
            self.errors.push(
                e.range(),
                "a free joint's `at` must be a point fixed in `N` (its origin's position \
                 is measured from there)",
            );
        }
        let child = child.and_then(|e| self.child_name(e));
        let (Some(parent), Some((base, offset)), Some(child)) = (parent, at_value, child) else {
            return self.invalid_joint(name, fields);
        };
        let named = |suffix: &str| Ident::new(&format!("{name}_{suffix}"), name.span());
        let position = free.then(|| ["x", "y", "z"].map(|c| self.joint_coordinate(&named(c))));
        let quaternion = ["qx", "qy", "qz", "qw"].map(|c| self.joint_coordinate(&named(c)));
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
    fn child_name<'a>(&mut self, e: &'a Expr) -> Option<&'a Ident> {
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
    fn invalid_joint(&mut self, name: &Ident, fields: &[Field]) {
        self.define(name, Binding::Invalid);
        if let Some(Expr::Name(child)) = fields.iter().find(|f| f.name == "child").map(|f| &f.value)
        {
            self.define(child, Binding::Invalid);
        }
    }

    /// `speeds w1, w2 { q1: rate1, q2: rate2 };`: the speeds `w` replace
    /// those of the coordinates named (`dt(q)`), taking their places in `v`
    /// in order, and `dt(qᵢ) = rateᵢ`, linear in the new speeds.
    fn speeds_statement(&mut self, keyword: &Ident, names: &[Ident], rates: &[Field]) {
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
            let divisors = &mut self.model.rate_divisors;
            super::singular::collect_rate_divisors(&mut self.pool, i as usize, rate, divisors);
        }
    }

    /// The coordinate `name` and its speed, if the speed is still its rate
    /// `dt(name)`.
    fn replaceable_speed(&self, name: &Ident) -> Option<(u32, usize)> {
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

    /// Declares a coordinate a joint makes (its speed comes with the joint).
    fn joint_coordinate(&mut self, name: &Ident) -> u32 {
        let index = self.model.coordinates.len() as u32;
        self.model.coordinates.push(name.clone());
        self.define(name, Binding::Scalar(Sym::Coord(index)));
        index
    }

    /// Whether the point `base + offset` moves in `N` (depends on a
    /// coordinate or `t`, or lies along a frame that turns).
    fn point_moves(&mut self, base: PointId, offset: &Vector) -> bool {
        let moving = SymKinds::COORD | SymKinds::TIME;
        let mut parts = offset.parts.clone();
        let mut point = base;
        while let Some((next, offset)) = &self.model.points[point.0].placement {
            parts.extend(offset.parts.iter().cloned());
            point = *next;
        }
        parts.iter().any(|(frame, components)| {
            components
                .iter()
                .any(|&c| self.pool.kinds(c).intersects(moving))
                || self.frame_turns(*frame)
        })
    }

    /// Whether `frame` turns in `N`.
    fn frame_turns(&self, mut frame: FrameId) -> bool {
        while let Some(placement) = &self.model.frames[frame.0].placement {
            let kinds = self.pool.kinds(placement.angle);
            if placement.ball.is_some() || !SymKinds::PARAM.contains(kinds) {
                return true;
            }
            frame = placement.parent;
        }
        false
    }

    fn torque(&mut self, value: &Expr, on: &Expr, reacting: Option<&Expr>) {
        let vector = self.vector(value, LOAD);
        let on = self.frame(on);
        let reacting = match reacting {
            Some(e) => self.frame(e).map(Some),
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

    fn constraint(&mut self, keyword: &Ident, lhs: &Expr, rhs: &Expr) {
        let (Some(l), Some(r)) = (self.scalar(lhs, CONSTRAINT), self.scalar(rhs, CONSTRAINT))
        else {
            return;
        };
        let residual = self.pool.sub(l, r);
        let kinds = self.pool.kinds(residual);
        let span = SpanRange::new(keyword.span(), rhs.range().end);
        if !kinds.intersects(SymKinds::COORD.union(SymKinds::SPEED)) {
            self.errors.push(
                span,
                "this constraint involves no coordinate or speed: it constrains nothing",
            );
            return;
        }
        let nonholonomic = kinds.intersects(SymKinds::SPEED);
        if nonholonomic && !self.linear_in_speeds(residual) {
            self.errors.push(
                span,
                "a nonholonomic constraint must be linear in the speeds `dt(q)`: \
                 its coefficients of the speeds may depend on coordinates, parameters and `t` only",
            );
            return;
        }
        if self.jacobian_depends_on_time(residual, nonholonomic) {
            self.errors.push(
                span,
                "the Jacobian of this constraint depends on time `t`, but the generated \
                 `constraint_jacobian(q)` has no `t`: time may enter a constraint only as \
                 a term of its own, such as `x == sin(t)`",
            );
            return;
        }
        self.model.constraints.push(Constraint {
            residual,
            nonholonomic,
        });
    }

    /// `closure NAME { at: P, to: Q };` (spherical), with `axis: F.z,
    /// along: G.z` (revolute) or `frame: F, welded: G` (welded): ordinary
    /// holonomic rows, those that vanish identically dropped (see
    /// [`closure_rows`]).
    fn closure(&mut self, name: &Ident, fields: &[Field]) {
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
            if self.jacobian_depends_on_time(row.residual, false) {
                self.errors.push(
                    name.span(),
                    format!(
                        "the Jacobian of closure `{name}` depends on time `t` ({}), but the \
                         generated `constraint_jacobian(q)` has no `t`: close the loop between \
                         points and frames that move with the coordinates only",
                        row.what
                    ),
                );
                rejected += 1;
                continue;
            }
            self.model.constraints.push(Constraint {
                residual: row.residual,
                nonholonomic: false,
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

    /// Whether a row of `A` (the derivatives of a holonomic residual by
    /// the coordinates, or the coefficients of the speeds of a
    /// nonholonomic one) depends on time.
    fn jacobian_depends_on_time(&mut self, residual: ExprId, nonholonomic: bool) -> bool {
        let count = if nonholonomic {
            self.model.speeds.len()
        } else {
            self.model.coordinates.len()
        };
        (0..count as u32).any(|i| {
            let by = if nonholonomic {
                Sym::Speed(i)
            } else {
                Sym::Coord(i)
            };
            let entry = self.pool.diff(residual, by);
            self.pool.kinds(entry).intersects(SymKinds::TIME)
        })
    }

    /// The generated `mass_matrix(q)`, `kinetic_energy(q, q̇)` and
    /// `potential_energy(q)` take no `t`: a mass that moves with time
    /// (prescribed motion of a frame or point that carries it) is recorded,
    /// and reported if `t` does not cancel from them (see
    /// [`Model::moving_masses`]).
    fn check_fixed_in_time(
        &mut self,
        name: &Ident,
        what: &str,
        at: PointId,
        frame: Option<FrameId>,
    ) {
        if self.point_moves_with_time(at) || frame.is_some_and(|f| self.frame_turns_with_time(f)) {
            self.model.moving_masses.push(syn::Error::new(
                name.span(),
                format!(
                    "{what} `{name}` moves with time `t` (its position or frame depends on \
                     `t`), and `t` stays in the mass matrix or the energies, but the generated \
                     `mass_matrix(q)`, `kinetic_energy(q, q̇)` and `potential_energy(q)` have \
                     no `t`: make the motion a coordinate and drive it with a load or a \
                     constraint"
                ),
            ));
        }
    }

    /// Whether a rotation angle on the way from `N` to `frame` depends on
    /// time.
    fn frame_turns_with_time(&self, mut frame: FrameId) -> bool {
        while let Some(placement) = &self.model.frames[frame.0].placement {
            if self.pool.kinds(placement.angle).intersects(SymKinds::TIME) {
                return true;
            }
            frame = placement.parent;
        }
        false
    }

    /// Whether an offset on the way from `O` to `point` depends on time,
    /// or lies along a frame that turns with time.
    fn point_moves_with_time(&self, mut point: PointId) -> bool {
        while let Some((base, offset)) = &self.model.points[point.0].placement {
            let moves = offset.parts.iter().any(|(frame, components)| {
                components
                    .iter()
                    .any(|&c| self.pool.kinds(c).intersects(SymKinds::TIME))
                    || self.frame_turns_with_time(*frame)
            });
            if moves {
                return true;
            }
            point = *base;
        }
        false
    }

    fn linear_in_speeds(&mut self, residual: ExprId) -> bool {
        (0..self.model.speeds.len() as u32).all(|i| {
            let coefficient = self.pool.diff(residual, Sym::Speed(i));
            !self.pool.kinds(coefficient).intersects(SymKinds::SPEED)
        })
    }

    // ----- fields of bodies, particles and joints ------------------------

    /// Picks the named fields out of a `{ ... }` block, reporting unknown,
    /// repeated and missing ones.
    fn fields<'a, const K: usize>(
        &mut self,
        owner: &Ident,
        what: &str,
        fields: &'a [Field],
        expected: [&str; K],
    ) -> [Option<&'a Expr>; K] {
        let mut found: [Option<&'a Expr>; K] = [None; K];
        for field in fields {
            match expected.iter().position(|name| field.name == name) {
                Some(i) if found[i].is_some() => self.errors.push(
                    field.name.span(),
                    format!("field `{}` is given twice", field.name),
                ),
                Some(i) => found[i] = Some(&field.value),
                None => self.errors.push(
                    field.name.span(),
                    format!(
                        "unknown field `{}` of a {what}; expected {}",
                        field.name,
                        list(&expected)
                    ),
                ),
            }
        }
        let missing: Vec<&str> = expected
            .iter()
            .zip(&found)
            .filter(|(_, value)| value.is_none())
            .map(|(name, _)| *name)
            .collect();
        if !missing.is_empty() {
            self.errors.push(
                owner.span(),
                format!(
                    "{what} `{owner}` is missing {} {}; a {what} needs {}",
                    if missing.len() == 1 {
                        "the field"
                    } else {
                        "the fields"
                    },
                    list(&missing),
                    list(&expected)
                ),
            );
        }
        found
    }

    fn mass(&mut self, e: &Expr) -> Option<ExprId> {
        let mass = self.scalar(e, MASS)?;
        if let Some(n) = self.pool.as_number(mass) {
            if n.is_zero() || n.is_negative() {
                self.errors.push(
                    e.range(),
                    "a mass must be positive; a frame without mass needs no body at all",
                );
                return None;
            }
        }
        Some(mass)
    }

    /// `[Ixx, Iyy, Izz]` or `[Ixx, Iyy, Izz, Ixy, Iyz, Izx]`.
    fn inertia(&mut self, e: &Expr) -> Option<[[ExprId; 3]; 3]> {
        let Expr::Array { items, span } = e else {
            self.errors.push(
                e.range(),
                "expected the inertia as a list: `[Ixx, Iyy, Izz]` or `[Ixx, Iyy, Izz, Ixy, Iyz, Izx]`",
            );
            return None;
        };
        if items.len() != 3 && items.len() != 6 {
            self.errors.push(
                *span,
                format!(
                    "an inertia lists 3 principal moments `[Ixx, Iyy, Izz]` or 6 entries \
                     `[Ixx, Iyy, Izz, Ixy, Iyz, Izx]`; found {}",
                    items.len()
                ),
            );
            return None;
        }
        let mut values = Vec::with_capacity(6);
        for (i, item) in items.iter().enumerate() {
            let value = self.scalar(item, MASS);
            if let Some(n) = value.and_then(|v| self.pool.as_number(v)) {
                if i < 3 && n.is_negative() {
                    self.errors.push(
                        item.range(),
                        "a principal moment of inertia cannot be negative",
                    );
                }
            }
            values.push(value);
        }
        let values: Option<Vec<_>> = values.into_iter().collect();
        let v = values?;
        let zero = self.pool.zero();
        let (xy, yz, zx) = if v.len() == 6 {
            (v[3], v[4], v[5])
        } else {
            (zero, zero, zero)
        };
        Some([[v[0], xy, zx], [xy, v[1], yz], [zx, yz, v[2]]])
    }

    /// A joint axis: `x`, `y`, `z`, or a constant direction `[ax, ay, az]`.
    fn axis_name(&mut self, e: &Expr) -> Option<[ExprId; 3]> {
        match e {
            Expr::Name(ident) => {
                if let Some(axis) = AXES.iter().position(|a| ident == a) {
                    return Some(unit_axis(&self.pool, axis));
                }
            }
            Expr::Array { .. } => return self.constant_axis(e),
            _ => {}
        }
        self.errors.push(
            e.range(),
            "expected a joint axis: `x`, `y` or `z` (an axis of the parent frame), or a constant direction `[ax, ay, az]`",
        );
        None
    }

    /// A unit vector of a frame, `F.x`, `F.y` or `F.z` (closure axes).
    fn frame_axis(&mut self, e: &Expr) -> Option<FrameAxis> {
        if let Expr::Member { base, member } = e {
            if let Some(axis) = AXES.iter().position(|a| member == a) {
                return self.frame_name(base).map(|frame| (frame, axis));
            }
        }
        self.errors.push(
            e.range(),
            "expected a unit vector of a frame: `F.x`, `F.y` or `F.z`",
        );
        None
    }

    /// `[ax, ay, az]` of numbers and parameters, normalised to a unit
    /// vector.
    fn constant_axis(&mut self, e: &Expr) -> Option<[ExprId; 3]> {
        let Expr::Array { items, span } = e else {
            self.errors.push(
                e.range(),
                "expected a constant axis `[ax, ay, az]` (its components in the parent frame's axes)",
            );
            return None;
        };
        if items.len() != 3 {
            self.errors.push(
                *span,
                format!(
                    "an axis has three components `[ax, ay, az]`; found {}",
                    items.len()
                ),
            );
            return None;
        }
        let components: Vec<Option<ExprId>> =
            items.iter().map(|item| self.scalar(item, AXIS)).collect();
        let components: [ExprId; 3] = [components[0]?, components[1]?, components[2]?];
        let unit = normalised(&mut self.pool, components);
        if unit.is_none() {
            self.errors.push(
                *span,
                "the axis is zero; expected a non-zero direction `[ax, ay, az]`",
            );
        }
        unit
    }

    // ----- definitions --------------------------------------------------

    fn define(&mut self, name: &Ident, binding: Binding) -> bool {
        let text = name.to_string();
        if BUILTINS.contains(&text.as_str()) || FUNCTIONS.iter().any(|(f, _)| *f == text) {
            self.errors.push(
                name.span(),
                format!(
                    "`{name}` is a built-in name and cannot be defined again; choose another name"
                ),
            );
            return false;
        }
        if let Some((previous, _)) = self.bindings.get(&text) {
            self.errors.push(
                name.span(),
                format!(
                    "`{name}` is already defined as {}; every name must be unique",
                    previous.describe()
                ),
            );
            return false;
        }
        self.bindings.insert(text, (binding, name.span()));
        true
    }

    /// Defines frame `name`; whether it was new.
    fn define_frame(
        &mut self,
        name: &Ident,
        parent: FrameId,
        axis: [ExprId; 3],
        angle: ExprId,
        ball: Option<usize>,
    ) -> bool {
        let id = FrameId(self.model.frames.len());
        let new = self.define(name, Binding::Frame(id));
        if new {
            self.model.frames.push(Frame {
                placement: Some(FramePlacement {
                    parent,
                    axis,
                    angle,
                    ball,
                }),
            });
        }
        new
    }

    /// Defines point `name`; whether it was new.
    fn define_point(&mut self, name: &Ident, placement: Option<(PointId, Vector)>) -> bool {
        let id = PointId(self.model.points.len());
        let new = self.define(name, Binding::Point(id));
        if new {
            self.model.points.push(Point { placement });
        }
        new
    }

    // ----- typed evaluation ---------------------------------------------

    fn scalar(&mut self, e: &Expr, usage: Use) -> Option<ExprId> {
        match self.value(e, usage)? {
            Value::Scalar(s) => Some(s),
            other => self.mismatch(e, "a scalar", &other),
        }
    }

    fn vector(&mut self, e: &Expr, usage: Use) -> Option<Vector> {
        match self.value(e, usage)? {
            Value::Vector(v) => Some(v),
            Value::Scalar(s) if self.pool.is_zero(s) => Some(Vector::default()),
            other => self.mismatch(e, "a vector", &other),
        }
    }

    fn point_value(&mut self, e: &Expr, usage: Use) -> Option<(PointId, Vector)> {
        match self.value(e, usage)? {
            Value::Point(base, offset) => Some((base, offset)),
            other => self.mismatch(e, "a point", &other),
        }
    }

    /// A point, adding an anonymous one where the expression offsets a
    /// named point (`center: J1 + L/2 * B1.x`).
    fn point(&mut self, e: &Expr, usage: Use) -> Option<PointId> {
        let (base, offset) = self.point_value(e, usage)?;
        if offset.parts.is_empty() {
            return Some(base);
        }
        self.model.points.push(Point {
            placement: Some((base, offset)),
        });
        Some(PointId(self.model.points.len() - 1))
    }

    fn frame(&mut self, e: &Expr) -> Option<FrameId> {
        match self.value(e, GEOMETRY)? {
            Value::Frame(f) => Some(f),
            other => self.mismatch(e, "a frame", &other),
        }
    }

    fn frame_name(&mut self, ident: &Ident) -> Option<FrameId> {
        match self.lookup(ident)? {
            Binding::Frame(f) => Some(f),
            other => {
                self.errors.push(
                    ident.span(),
                    format!("`{ident}` is {}; expected a frame", other.describe()),
                );
                None
            }
        }
    }

    fn mismatch<T>(&mut self, e: &Expr, expected: &str, found: &Value) -> Option<T> {
        self.errors.push(
            e.range(),
            format!("expected {expected}, found {}", found.describe()),
        );
        None
    }

    fn lookup(&mut self, ident: &Ident) -> Option<Binding> {
        let text = ident.to_string();
        if let Some((binding, _)) = self.bindings.get(&text) {
            return match binding {
                Binding::Invalid => None,
                valid => Some(*valid),
            };
        }
        let message = if self.defined_anywhere.contains_key(&text) {
            format!("`{ident}` is used before its definition; move its statement above this one")
        } else if FUNCTIONS.iter().any(|(f, _)| *f == text) {
            format!("`{ident}` is a function: call it as `{ident}(...)`")
        } else {
            format!(
                "unknown name `{ident}`; expected a parameter, coordinate, input, frame or point defined above, or `t`"
            )
        };
        self.errors.push(ident.span(), message);
        None
    }

    /// Evaluates an expression to a typed value, reporting what is wrong at
    /// the innermost offending token.
    fn value(&mut self, e: &Expr, usage: Use) -> Option<Value> {
        match e {
            Expr::Number { text, span } => match self.pool.decimal(text) {
                Some(n) => Some(Value::Scalar(n)),
                None => {
                    self.errors.push(*span, format!("`{text}` is not a number"));
                    None
                }
            },
            Expr::Name(ident) => self.name(ident, usage),
            Expr::Member { base, member } => {
                let frame = self.frame_name(base)?;
                match AXES.iter().position(|a| member == a) {
                    Some(axis) => Some(Value::Vector(Vector::unit(&self.pool, frame, axis))),
                    None => {
                        self.errors.push(
                            member.span(),
                            format!(
                                "a frame has unit vectors `.x`, `.y` and `.z`; found `.{member}`"
                            ),
                        );
                        None
                    }
                }
            }
            Expr::Call { func, args, .. } => self.call(func, args, e.range(), usage),
            Expr::MethodCall { method, .. } => {
                self.errors.push(
                    e.range(),
                    format!(
                        "`{method}(..)` is not a value; frames are made only by `frame B = F.rotate_z(angle);`"
                    ),
                );
                None
            }
            Expr::Array { span, .. } => {
                self.errors
                    .push(*span, "a list `[..]` is allowed only as a body's inertia");
                None
            }
            Expr::Paren { inner, .. } => self.value(inner, usage),
            Expr::Neg { operand, .. } => match self.value(operand, usage)? {
                Value::Scalar(s) => Some(Value::Scalar(self.pool.neg(s))),
                Value::Vector(v) => Some(Value::Vector(v.neg(&mut self.pool))),
                other => self.mismatch(operand, "a scalar or a vector", &other),
            },
            Expr::Binary {
                op,
                op_span,
                lhs,
                rhs,
            } => self.binary(*op, *op_span, lhs, rhs, usage),
        }
    }

    fn name(&mut self, ident: &Ident, usage: Use) -> Option<Value> {
        match self.lookup(ident)? {
            Binding::Scalar(sym) => {
                let kind = sym.kind();
                if !usage.allowed.contains(kind) {
                    self.errors.push(
                        ident.span(),
                        format!(
                            "{} `{ident}` cannot be used in {}",
                            describe_kind(kind),
                            usage.role
                        ),
                    );
                    return None;
                }
                Some(Value::Scalar(self.pool.sym(sym)))
            }
            Binding::Frame(f) => Some(Value::Frame(f)),
            Binding::Point(p) => Some(Value::Point(p, Vector::default())),
            Binding::Invalid => None,
            other @ (Binding::Body | Binding::Particle | Binding::Closure) => {
                self.errors.push(
                    ident.span(),
                    format!(
                        "`{ident}` is {} and has no value here; use its frame or its center point",
                        other.describe()
                    ),
                );
                None
            }
        }
    }

    fn call(&mut self, func: &Ident, args: &[Expr], span: SpanRange, usage: Use) -> Option<Value> {
        let Some((_, f)) = FUNCTIONS.iter().find(|(name, _)| func == name) else {
            self.errors.push(
                func.span(),
                format!(
                    "unknown function `{func}`; expected one of {}",
                    list(&FUNCTIONS.map(|(name, _)| name))
                ),
            );
            return None;
        };
        let [arg] = args else {
            self.errors.push(
                span,
                format!("`{func}` takes one argument; found {}", args.len()),
            );
            return None;
        };
        match f {
            Some(f) => {
                let x = self.scalar(arg, usage)?;
                Some(Value::Scalar(self.pool.func(*f, x)))
            }
            None => self.speed(func, arg, usage),
        }
    }

    /// `dt(expr)`: the rate of a geometric expression (usually a coordinate).
    fn speed(&mut self, func: &Ident, arg: &Expr, usage: Use) -> Option<Value> {
        if !usage.allowed.contains(SymKinds::SPEED) {
            self.errors.push(
                func.span(),
                format!("speeds `dt(..)` cannot be used in {}", usage.role),
            );
            return None;
        }
        let inner = Use {
            allowed: usage.allowed.intersection(GEOMETRY.allowed),
            role: "the argument of `dt`, which must be a coordinate or an expression of coordinates, parameters and `t`",
        };
        let x = self.scalar(arg, inner)?;
        if !self.pool.kinds(x).contains(SymKinds::COORD) {
            self.errors.push(
                arg.range(),
                "only coordinates have speeds: the argument of `dt` must be a coordinate (or an expression of coordinates)",
            );
            return None;
        }
        self.used_dt = true;
        Some(Value::Scalar(self.pool.time_derivative(x)))
    }

    fn binary(
        &mut self,
        op: BinOp,
        op_span: Span,
        lhs: &Expr,
        rhs: &Expr,
        usage: Use,
    ) -> Option<Value> {
        if op == BinOp::Pow {
            return self.power(lhs, rhs, usage);
        }
        let a = self.value(lhs, usage);
        let b = self.value(rhs, usage);
        let (a, b) = (a?, b?);
        let pool = &mut self.pool;
        let result = match (op, a, b) {
            (BinOp::Add, Value::Scalar(x), Value::Scalar(y)) => Value::Scalar(pool.add(x, y)),
            (BinOp::Sub, Value::Scalar(x), Value::Scalar(y)) => Value::Scalar(pool.sub(x, y)),
            (BinOp::Mul, Value::Scalar(x), Value::Scalar(y)) => Value::Scalar(pool.mul(x, y)),
            (BinOp::Div, Value::Scalar(x), Value::Scalar(y)) => {
                if pool.is_zero(y) {
                    self.errors.push(rhs.range(), "division by zero");
                    return None;
                }
                Value::Scalar(pool.div(x, y))
            }
            (BinOp::Add, Value::Vector(u), Value::Vector(v)) => Value::Vector(u.add(&v, pool)),
            (BinOp::Sub, Value::Vector(u), Value::Vector(v)) => {
                let minus_v = v.neg(pool);
                Value::Vector(u.add(&minus_v, pool))
            }
            (BinOp::Mul, Value::Scalar(s), Value::Vector(v))
            | (BinOp::Mul, Value::Vector(v), Value::Scalar(s)) => Value::Vector(v.scale(s, pool)),
            (BinOp::Div, Value::Vector(v), Value::Scalar(s)) => {
                if pool.is_zero(s) {
                    self.errors.push(rhs.range(), "division by zero");
                    return None;
                }
                let inverse = pool.powi(s, -1);
                Value::Vector(v.scale(inverse, pool))
            }
            (BinOp::Add, Value::Point(p, offset), Value::Vector(v)) => {
                Value::Point(p, offset.add(&v, pool))
            }
            (BinOp::Sub, Value::Point(p, offset), Value::Vector(v)) => {
                let minus_v = v.neg(pool);
                Value::Point(p, offset.add(&minus_v, pool))
            }
            (op, a, b) => {
                self.errors.push(op_span, operator_mismatch(op, &a, &b));
                return None;
            }
        };
        Some(result)
    }

    /// `base ^ exponent` with a constant integer exponent.
    fn power(&mut self, lhs: &Expr, rhs: &Expr, usage: Use) -> Option<Value> {
        let base = self.scalar(lhs, usage);
        let exponent = self.scalar(rhs, EXPONENT);
        let (base, exponent) = (base?, exponent?);
        let integer = self.pool.as_rational(exponent).filter(|r| r.den == 1);
        let Some(n) = integer.and_then(|r| i32::try_from(r.num).ok()) else {
            let message = match integer {
                Some(r) => format!(
                    "the exponent of `^` must be an integer from {} to {}; found {}",
                    i32::MIN,
                    i32::MAX,
                    r.num
                ),
                None => "the exponent of `^` must be a constant integer (such as `2` or `-1`); \
                         use `sqrt(..)` for square roots"
                    .to_owned(),
            };
            self.errors.push(rhs.range(), message);
            return None;
        };
        if n < 0 && self.pool.is_zero(base) {
            self.errors
                .push(lhs.range(), "division by zero: zero to a negative power");
            return None;
        }
        Some(Value::Scalar(self.pool.powi(base, n)))
    }
}

/// `v / |v|`, exact where the length is rational, in floats for other
/// numeric vectors; `None` for a vector that is zero.
fn normalised(pool: &mut Pool, v: [ExprId; 3]) -> Option<[ExprId; 3]> {
    let squares: Vec<ExprId> = v.iter().map(|&c| pool.mul(c, c)).collect();
    let length_squared = pool.sum(squares);
    if pool.is_zero(length_squared) {
        return None;
    }
    let numbers: Option<Vec<f64>> = v
        .iter()
        .map(|&c| pool.as_number(c).map(|n| n.to_f64()))
        .collect();
    let exact = pool
        .as_rational(length_squared)
        .is_some_and(|r| r.sqrt_exact().is_some());
    match numbers {
        Some(numbers) if !exact => {
            let length = numbers.iter().map(|x| x * x).sum::<f64>().sqrt();
            if length == 0.0 || !length.is_finite() {
                return None;
            }
            Some([0, 1, 2].map(|i| pool.number(Number::Float(numbers[i] / length))))
        }
        _ => {
            let length = pool.func(Func::Sqrt, length_squared);
            let inverse = pool.powi(length, -1);
            Some(v.map(|c| pool.mul(c, inverse)))
        }
    }
}

/// Every name that some statement defines, with its span.
fn defined_names(system: &System) -> HashMap<String, Span> {
    let mut names = HashMap::new();
    let mut add = |ident: &Ident| {
        names.entry(ident.to_string()).or_insert(ident.span());
    };
    for statement in &system.statements {
        match statement {
            Statement::Parameters(list)
            | Statement::Coordinates(list)
            | Statement::Inputs(list) => list.iter().for_each(&mut add),
            Statement::Frame { name, .. }
            | Statement::Point { name, .. }
            | Statement::Body { name, .. }
            | Statement::Particle { name, .. }
            | Statement::Closure { name, .. } => add(name),
            Statement::Joint { name, fields, .. } => {
                add(name);
                for field in fields {
                    if let (true, Expr::Name(child)) = (field.name == "child", &field.value) {
                        add(child);
                    }
                }
            }
            Statement::Speeds { names, .. } => names.iter().for_each(&mut add),
            _ => {}
        }
    }
    names
}

fn describe_kind(kind: SymKinds) -> &'static str {
    if kind == SymKinds::INPUT {
        "the input"
    } else if kind == SymKinds::COORD {
        "the coordinate"
    } else if kind == SymKinds::TIME {
        "time"
    } else {
        "the parameter"
    }
}

fn operator_mismatch(op: BinOp, a: &Value, b: &Value) -> String {
    let (a, b) = (a.describe(), b.describe());
    match op {
        BinOp::Add | BinOp::Sub if a == "a point" || b == "a point" => format!(
            "cannot {} {a} and {b}: a point is written `P + vector` or `P - vector`",
            if op == BinOp::Add { "add" } else { "subtract" }
        ),
        BinOp::Add | BinOp::Sub => format!(
            "cannot {} {a} and {b}: both sides must be scalars, or both vectors",
            if op == BinOp::Add { "add" } else { "subtract" }
        ),
        BinOp::Mul => {
            format!("cannot multiply {a} by {b}: expected a scalar times a scalar or a vector")
        }
        BinOp::Div | BinOp::Pow => {
            format!("cannot divide {a} by {b}: the divisor must be a scalar")
        }
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
