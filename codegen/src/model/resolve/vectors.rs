//! The vector functions of expressions: `dot(a, b)`, `norm(a)`,
//! `cross(a, b)`, `velocity(P)` and `angular_velocity(F)`, and the vector
//! `P - Q` between two points, each checked for the kinds of its arguments
//! and for where it is used (a velocity depends on the speeds, so it has no
//! place in geometry or a potential).

use super::Resolver;
use super::evaluate::{GEOMETRY, Use, Value};
use crate::expr::SymKinds;
use crate::language::ast::{Expr, SpanRange};
use crate::model::algebra::from_origin;
use crate::model::{PointId, Vector};
use proc_macro2::Ident;

/// The vector functions, with their numbers of arguments.
pub(super) const VECTOR_FUNCTIONS: [(&str, usize); 5] = [
    ("dot", 2),
    ("norm", 1),
    ("cross", 2),
    ("velocity", 1),
    ("angular_velocity", 1),
];

impl Resolver {
    /// `func(args)` for one of [`VECTOR_FUNCTIONS`] (`arity` its number of
    /// arguments); out of line, as [`Resolver::point_difference`].
    #[inline(never)]
    pub(super) fn vector_call(
        &mut self,
        func: &Ident,
        arity: usize,
        args: &[Expr],
        span: SpanRange,
        usage: Use,
    ) -> Option<Value> {
        if args.len() != arity {
            let expected = match arity {
                1 => "one argument".to_owned(),
                _ => format!("{arity} arguments"),
            };
            self.errors.push(
                span,
                format!("`{func}` takes {expected}; found {}", args.len()),
            );
            return None;
        }
        match func.to_string().as_str() {
            "dot" => {
                let (a, b) = (self.vector(&args[0], usage), self.vector(&args[1], usage));
                let (a, b) = (a?, b?);
                Some(Value::Scalar(
                    self.with_geometry(|geometry, pool| geometry.dot(pool, &a, &b)),
                ))
            }
            "cross" => {
                let (a, b) = (self.vector(&args[0], usage), self.vector(&args[1], usage));
                let (a, b) = (a?, b?);
                Some(Value::Vector(self.with_geometry(|geometry, pool| {
                    geometry.cross(pool, &a, &b)
                })))
            }
            "norm" => {
                let a = self.vector(&args[0], usage)?;
                Some(Value::Scalar(
                    self.with_geometry(|geometry, pool| geometry.norm(pool, &a)),
                ))
            }
            "velocity" => {
                self.check_velocity_allowed(func, usage)?;
                let (base, offset) = self.point_value(&args[0], geometry_within(usage))?;
                Some(Value::Vector(self.velocity(base, &offset)))
            }
            _ => {
                self.check_velocity_allowed(func, usage)?;
                let frame = self.frame(&args[0])?;
                Some(Value::Vector(self.with_geometry(|geometry, pool| {
                    geometry.angular_velocity(pool, frame)
                })))
            }
        }
    }

    /// The velocity in `N` of the point `base + offset`.
    pub(super) fn velocity(&mut self, base: PointId, offset: &Vector) -> Vector {
        self.used_dt = true;
        let position = from_origin(&self.model, &mut self.pool, base, offset);
        self.with_geometry(|geometry, pool| geometry.rate(pool, &position))
    }

    /// `P - Q` of the points `to` and `from`, kept out of line: the
    /// recursion through [`Resolver::binary`] of a long expression keeps a
    /// small frame.
    #[inline(never)]
    pub(super) fn point_difference(&mut self, to: Value, from: Value) -> Value {
        match (to, from) {
            (Value::Point(p, p_offset), Value::Point(q, q_offset)) => {
                Value::Vector(self.between((p, p_offset), (q, q_offset)))
            }
            (to, _) => to,
        }
    }

    /// `P - Q` of two points: the vector from `Q` to `P`.
    pub(super) fn between(&mut self, to: (PointId, Vector), from: (PointId, Vector)) -> Vector {
        let to = from_origin(&self.model, &mut self.pool, to.0, &to.1);
        let from = from_origin(&self.model, &mut self.pool, from.0, &from.1);
        let minus_from = from.neg(&mut self.pool);
        to.add(&minus_from, &mut self.pool)
    }

    /// A velocity depends on the speeds: it is allowed where they are
    /// (loads, dissipation, constraints), not in geometry, masses or
    /// potentials.
    fn check_velocity_allowed(&mut self, func: &Ident, usage: Use) -> Option<()> {
        if usage.allowed.contains(SymKinds::SPEED) {
            return Some(());
        }
        self.errors.push(
            func.span(),
            format!(
                "`{func}(..)` is a velocity, which depends on the speeds; it cannot be used \
                 in {}",
                usage.role
            ),
        );
        None
    }
}

/// Where the point of `velocity(P)` is read: geometry, and only what the
/// enclosing use allows besides (no `t` in a use without time).
fn geometry_within(usage: Use) -> Use {
    Use {
        allowed: usage.allowed.intersection(GEOMETRY.allowed),
        role: GEOMETRY.role,
    }
}
