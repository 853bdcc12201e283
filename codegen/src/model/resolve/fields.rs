//! The `{ field: value }` blocks of bodies, particles, joints and
//! closures: which fields there are, and the values only fields take
//! (masses, inertias, axes).

use super::Resolver;
use super::evaluate::{AXES, AXIS, MASS};
use super::list;
use crate::expr::{ExprId, Func, Number, Pool};
use crate::language::ast::{Expr, Field};
use crate::language::keyword::Symbol;
use crate::model::closure::FrameAxis;
use crate::model::unit_axis;
use proc_macro2::{Ident, Span};

impl Resolver {
    /// Picks the named fields out of a `{ ... }` block, reporting unknown,
    /// repeated and missing ones.
    pub(super) fn fields<'a, const K: usize>(
        &mut self,
        owner: &Ident,
        what: &str,
        fields: &'a [Field],
        expected: [Symbol; K],
    ) -> [Option<&'a Expr>; K] {
        self.fields_optional(owner, what, fields, expected, 0)
    }

    /// [`fields`](Resolver::fields) whose last `optional` names may be
    /// left out.
    pub(super) fn fields_optional<'a, const K: usize>(
        &mut self,
        owner: &Ident,
        what: &str,
        fields: &'a [Field],
        expected: [Symbol; K],
        optional: usize,
    ) -> [Option<&'a Expr>; K] {
        let words = expected.map(Symbol::as_str);
        let mut found: [Option<&'a Expr>; K] = [None; K];
        for field in fields {
            match expected.iter().position(|name| field.name == *name) {
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
                        list(&words)
                    ),
                ),
            }
        }
        let missing: Vec<&str> = words
            .iter()
            .zip(&found)
            .take(K - optional)
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
                    list(&words[..K - optional])
                ),
            );
        }
        found
    }

    /// A mass: positive where it is a constant (one of parameters may
    /// take any value at run time); `massless` says what to do instead.
    pub(super) fn mass(&mut self, e: &Expr, massless: &str) -> Option<ExprId> {
        let mass = self.scalar(e, MASS)?;
        if let Some(x) = self.pool.constant_value(mass) {
            if x <= 0.0 {
                self.errors.push(
                    e.range(),
                    format!("a mass must be positive; {massless} at all"),
                );
                return None;
            }
        }
        Some(mass)
    }

    /// `[Ixx, Iyy, Izz]` or `[Ixx, Iyy, Izz, Ixy, Iyz, Izx]`.
    pub(super) fn inertia(&mut self, e: &Expr) -> Option<[[ExprId; 3]; 3]> {
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
        let values: Vec<Option<ExprId>> =
            items.iter().map(|item| self.scalar(item, MASS)).collect();
        let moments = values[..3]
            .iter()
            .map(|v| v.and_then(|v| self.pool.constant_value(v)));
        let scale = moments.flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
        let mut negative_moment = false;
        for (item, value) in items.iter().zip(&values).take(3) {
            if value.is_some_and(|v| self.is_negative_moment(v, scale)) {
                negative_moment = true;
                self.errors.push(
                    item.range(),
                    "a principal moment of inertia cannot be negative",
                );
            }
        }
        let values: Option<Vec<_>> = values.into_iter().collect();
        let v = values?;
        let zero = self.pool.zero();
        let (xy, yz, zx) = if v.len() == 6 {
            (v[3], v[4], v[5])
        } else {
            (zero, zero, zero)
        };
        let tensor = [[v[0], xy, zx], [xy, v[1], yz], [zx, yz, v[2]]];
        if v.len() == 6 && !negative_moment {
            self.check_principal_moments(&tensor, *span);
        }
        Some(tensor)
    }

    /// Whether the principal moment `moment` is a constant below zero:
    /// exactly, for a rational number, and by more than rounding (`1e-12` of
    /// `scale`, the largest constant moment of the body) for an expression
    /// evaluated in floating point (`sqrt(2)^2 - 2` is zero).
    fn is_negative_moment(&self, moment: ExprId, scale: f64) -> bool {
        match self.pool.as_rational(moment) {
            Some(r) => r.num < 0,
            None => self
                .pool
                .constant_value(moment)
                .is_some_and(|x| x < -1e-12 * scale),
        }
    }

    /// With products of inertia, the principal moments are the tensor's
    /// eigenvalues: a numeric tensor must have none negative (be positive
    /// semidefinite), which holds when its principal minors are not
    /// negative (to rounding). The diagonal is checked entry by entry above.
    fn check_principal_moments(&mut self, tensor: &[[ExprId; 3]; 3], span: Span) {
        let numbers = tensor.map(|row| row.map(|e| self.pool.constant_value(e)));
        let Some(i) = numbers
            .iter()
            .map(|row| row.iter().copied().collect::<Option<Vec<f64>>>())
            .collect::<Option<Vec<Vec<f64>>>>()
        else {
            return;
        };
        let scale = i.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
        let minor = |a: usize, b: usize| i[a][a] * i[b][b] - i[a][b] * i[b][a];
        let determinant = i[0][0] * minor(1, 2) - i[0][1] * (i[1][0] * i[2][2] - i[1][2] * i[2][0])
            + i[0][2] * (i[1][0] * i[2][1] - i[1][1] * i[2][0]);
        let tolerance = 1e-12;
        let minors_hold = [minor(0, 1), minor(1, 2), minor(0, 2)]
            .iter()
            .all(|m| *m >= -tolerance * scale * scale);
        if minors_hold && determinant >= -tolerance * scale * scale * scale {
            return;
        }
        self.errors.push(
            span,
            "this inertia has a negative principal moment: its products of inertia are too \
             large for its moments (expected Ixx Iyy ≥ Ixy², Iyy Izz ≥ Iyz², Izz Ixx ≥ Izx² \
             and a determinant not negative)",
        );
    }

    /// A joint axis: `x`, `y`, `z`, or a constant direction `[ax, ay, az]`.
    pub(super) fn axis_name(&mut self, e: &Expr) -> Option<[ExprId; 3]> {
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
    pub(super) fn frame_axis(&mut self, e: &Expr) -> Option<FrameAxis> {
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
    pub(super) fn constant_axis(&mut self, e: &Expr) -> Option<[ExprId; 3]> {
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
}

/// `v / |v|`, exact where the length is rational, in floats for other
/// numeric vectors; `None` for a vector that is zero.
pub(super) fn normalised(pool: &mut Pool, v: [ExprId; 3]) -> Option<[ExprId; 3]> {
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
