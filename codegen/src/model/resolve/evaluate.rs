//! Typed evaluation: every expression into the pool with its type
//! (scalar, vector, point, frame), the symbols its use allows, and an error
//! at the innermost offending token.

use super::Resolver;
use super::list;
use super::scope::Binding;
use super::vectors::VECTOR_FUNCTIONS;
use crate::expr::{ExprId, Func, SymKinds};
use crate::language::ast::{BinOp, Expr, SpanRange};
use crate::language::keyword::DT;
use crate::model::{FrameId, Point, PointId, Vector};
use proc_macro2::{Ident, Span};

/// The scalar functions of the language, with `dt`.
pub(super) const FUNCTIONS: [(&str, Option<Func>); 8] = [
    ("sin", Some(Func::Sin)),
    ("cos", Some(Func::Cos)),
    ("tan", Some(Func::Tan)),
    ("sqrt", Some(Func::Sqrt)),
    ("exp", Some(Func::Exp)),
    ("ln", Some(Func::Ln)),
    ("abs", Some(Func::Abs)),
    (DT.as_str(), None),
];

/// Axis names of unit vectors and joint axes.
pub(super) const AXES: [&str; 3] = ["x", "y", "z"];

/// Where an expression is used, which decides the symbols it may contain.
#[derive(Clone, Copy)]
pub(super) struct Use {
    pub(super) allowed: SymKinds,
    pub(super) role: &'static str,
}

pub(super) const GEOMETRY: Use = Use {
    allowed: SymKinds::TIME.union(SymKinds::PARAM).union(SymKinds::COORD),
    role: "geometry (frame angles and point positions)",
};

pub(super) const MASS: Use = Use {
    allowed: SymKinds::PARAM,
    role: "mass and inertia, which may depend on parameters only",
};

pub(super) const GRAVITY: Use = Use {
    allowed: SymKinds::PARAM,
    role: "gravity, which may depend on parameters only",
};

pub(super) const LOAD: Use = Use {
    allowed: SymKinds::TIME
        .union(SymKinds::PARAM)
        .union(SymKinds::COORD)
        .union(SymKinds::SPEED)
        .union(SymKinds::INPUT),
    role: "a load",
};

pub(super) const POTENTIAL: Use = Use {
    allowed: SymKinds::PARAM.union(SymKinds::COORD),
    role: "a potential, which may depend on coordinates and parameters only",
};

pub(super) const DISSIPATION: Use = Use {
    allowed: SymKinds::PARAM
        .union(SymKinds::COORD)
        .union(SymKinds::SPEED),
    role: "a dissipation function, which may depend on coordinates, speeds and parameters only",
};

pub(super) const CONSTRAINT: Use = Use {
    allowed: SymKinds::TIME
        .union(SymKinds::PARAM)
        .union(SymKinds::COORD)
        .union(SymKinds::SPEED),
    role: "a constraint, which may not depend on inputs",
};

pub(super) const KINEMATICS: Use = Use {
    allowed: SymKinds::PARAM
        .union(SymKinds::COORD)
        .union(SymKinds::SPEED),
    role: "a coordinate's rate, which may depend on coordinates, parameters and the new speeds only",
};

pub(super) const AXIS: Use = Use {
    allowed: SymKinds::PARAM,
    role: "a rotation axis, which must be constant (numbers and parameters)",
};

pub(super) const EXPONENT: Use = Use {
    allowed: SymKinds::EMPTY,
    role: "an exponent, which must be a constant integer",
};

/// A typed value of an expression.
pub(super) enum Value {
    Scalar(ExprId),
    Vector(Vector),
    /// A point given as a base point plus an offset.
    Point(PointId, Vector),
    Frame(FrameId),
}

impl Value {
    pub(super) fn describe(&self) -> &'static str {
        match self {
            Value::Scalar(_) => "a scalar",
            Value::Vector(_) => "a vector",
            Value::Point(..) => "a point",
            Value::Frame(_) => "a frame",
        }
    }
}

impl Resolver {
    pub(super) fn scalar(&mut self, e: &Expr, usage: Use) -> Option<ExprId> {
        match self.value(e, usage)? {
            Value::Scalar(s) => Some(s),
            other => self.mismatch(e, "a scalar", &other),
        }
    }

    pub(super) fn vector(&mut self, e: &Expr, usage: Use) -> Option<Vector> {
        match self.value(e, usage)? {
            Value::Vector(v) => Some(v),
            Value::Scalar(s) if self.pool.is_zero(s) => Some(Vector::default()),
            other => self.mismatch(e, "a vector", &other),
        }
    }

    pub(super) fn point_value(&mut self, e: &Expr, usage: Use) -> Option<(PointId, Vector)> {
        match self.value(e, usage)? {
            Value::Point(base, offset) => Some((base, offset)),
            other => self.mismatch(e, "a point", &other),
        }
    }

    /// A point, adding an anonymous one where the expression offsets a
    /// named point (`center: J1 + L/2 * B1.x`).
    pub(super) fn point(&mut self, e: &Expr, usage: Use) -> Option<PointId> {
        let (base, offset) = self.point_value(e, usage)?;
        if offset.parts.is_empty() {
            return Some(base);
        }
        self.model.points.push(Point {
            placement: Some((base, offset)),
        });
        Some(PointId(self.model.points.len() - 1))
    }

    pub(super) fn frame(&mut self, e: &Expr) -> Option<FrameId> {
        match self.value(e, GEOMETRY)? {
            Value::Frame(f) => Some(f),
            other => self.mismatch(e, "a frame", &other),
        }
    }

    pub(super) fn mismatch<T>(&mut self, e: &Expr, expected: &str, found: &Value) -> Option<T> {
        self.errors.push(
            e.range(),
            format!("expected {expected}, found {}", found.describe()),
        );
        None
    }

    /// Evaluates an expression to a typed value, reporting what is wrong at
    /// the innermost offending token.
    pub(super) fn value(&mut self, e: &Expr, usage: Use) -> Option<Value> {
        let value = self.typed_value(e, usage)?;
        self.finite_constant(e, value)
    }

    /// `value`, unless it is a constant scalar without a finite value (a
    /// literal beyond the range of `f64`, `ln(0)`, `sqrt(-1)`, `exp(1000)`):
    /// emitted, it would make `M` or `f` infinite or NaN at every state.
    fn finite_constant(&mut self, e: &Expr, value: Value) -> Option<Value> {
        let Value::Scalar(s) = value else {
            return Some(value);
        };
        let x = match self.pool.constant_value(s) {
            Some(x) if !x.is_finite() => x,
            _ => return Some(value),
        };
        let message = match e {
            Expr::Number { text, .. } => format!(
                "the number `{text}` is too large for a 64-bit float; expected a magnitude below about 1.8e308"
            ),
            _ => format!(
                "this constant has no finite value (it is {x}); expected arguments in each function's domain (`ln` of a positive number, `sqrt` of one not negative) and values within the range of a 64-bit float"
            ),
        };
        self.errors.push(e.range(), message);
        None
    }

    fn typed_value(&mut self, e: &Expr, usage: Use) -> Option<Value> {
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
                self.errors.push(
                    *span,
                    "a list `[..]` is not a value: it is allowed only as a body's inertia \
                     and as a constant axis `[ax, ay, az]` (of a joint or of `F.rotate`); \
                     expected a scalar or a vector, such as `ax * N.x + ay * N.y`",
                );
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

    pub(super) fn name(&mut self, ident: &Ident, usage: Use) -> Option<Value> {
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
            other @ (Binding::Body | Binding::Particle | Binding::Closure | Binding::Rolling) => {
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

    pub(super) fn call(
        &mut self,
        func: &Ident,
        args: &[Expr],
        span: SpanRange,
        usage: Use,
    ) -> Option<Value> {
        if let Some((_, arity)) = VECTOR_FUNCTIONS.iter().find(|(name, _)| func == name) {
            return self.vector_call(func, *arity, args, span, usage);
        }
        let Some((_, f)) = FUNCTIONS.iter().find(|(name, _)| func == name) else {
            let known: Vec<&str> = FUNCTIONS
                .map(|(name, _)| name)
                .into_iter()
                .chain(VECTOR_FUNCTIONS.map(|(name, _)| name))
                .collect();
            self.errors.push(
                func.span(),
                format!(
                    "unknown function `{func}`; expected one of {}",
                    list(&known)
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
    pub(super) fn speed(&mut self, func: &Ident, arg: &Expr, usage: Use) -> Option<Value> {
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

    pub(super) fn binary(
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
        if let (BinOp::Sub, Value::Point(..), Value::Point(..)) = (op, &a, &b) {
            return Some(self.point_difference(a, b));
        }
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
                // A frame where a point is meant: the frame is the mistake.
                let at = match a {
                    Value::Frame(_) => lhs.range(),
                    _ => op_span.into(),
                };
                self.errors.push(at, operator_mismatch(op, &a, &b));
                return None;
            }
        };
        Some(result)
    }

    /// `base ^ exponent` with a constant integer exponent.
    pub(super) fn power(&mut self, lhs: &Expr, rhs: &Expr, usage: Use) -> Option<Value> {
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

pub(super) fn describe_kind(kind: SymKinds) -> &'static str {
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

pub(super) fn operator_mismatch(op: BinOp, a: &Value, b: &Value) -> String {
    let point = matches!(a, Value::Point(..)) || matches!(b, Value::Point(..));
    let frame_first = matches!(a, Value::Frame(_));
    let (a, b) = (a.describe(), b.describe());
    match op {
        BinOp::Add | BinOp::Sub => {
            let verb = if op == BinOp::Add { "add" } else { "subtract" };
            let expected = if point {
                "a point is written `P + vector` or `P - vector`, and `P - Q` of two points is the vector from `Q` to `P`"
            } else if frame_first {
                "a frame has no position of its own; a point is written `P + vector` from a \
                 point (`O` or one defined above)"
            } else {
                "both sides must be scalars, or both vectors"
            };
            format!("cannot {verb} {a} and {b}: {expected}")
        }
        BinOp::Mul => {
            format!("cannot multiply {a} by {b}: expected a scalar times a scalar or a vector")
        }
        BinOp::Div | BinOp::Pow => {
            format!("cannot divide {a} by {b}: the divisor must be a scalar")
        }
    }
}
