//! The `rolling` statement: a wheel rolling without slipping on a fixed
//! plane, checked field by field and added as three constraint rows (see
//! [`crate::model::rolling`]).

use super::Resolver;
use super::evaluate::{GEOMETRY, Use};
use super::scope::Binding;
use crate::expr::{ExprId, SymKinds};
use crate::language::ast::{Expr, Field, SpanRange};
use crate::language::keyword::field::{AXLE, CENTER, PLANE, RADIUS, THROUGH, TIRE, WHEEL};
use crate::model::rolling::{Wheel, at_reference, rolling_rows};
use crate::model::{Constraint, ORIGIN, Vector};
use proc_macro2::Ident;

/// A wheel's radii: constants of the model.
const SHAPE: Use = Use {
    allowed: SymKinds::PARAM,
    role: "a wheel's radius, which may depend on parameters only",
};

impl Resolver {
    /// `rolling NAME { wheel: F, axle: F.y, center: P, radius: r, plane: N.z };`
    /// with the optional `tire: rt` and `through: Q`.
    pub(super) fn rolling(&mut self, name: &Ident, fields: &[Field]) {
        self.define(name, Binding::Rolling);
        let [wheel, axle, center, radius, plane, tire, through] = self.fields_optional(
            name,
            "rolling contact",
            fields,
            [WHEEL, AXLE, CENTER, RADIUS, PLANE, TIRE, THROUGH],
            2,
        );
        let frame = wheel.and_then(|e| self.frame(e));
        let axle_axis = axle.and_then(|e| self.frame_axis(e));
        let axle_axis = match (frame, axle, axle_axis) {
            (Some(frame), Some(e), Some(axis)) => self.fixed_axle(e, axis, frame),
            _ => axle_axis,
        };
        let center = center.and_then(|e| self.point_value(e, GEOMETRY));
        let radius = radius.and_then(|e| self.size(e, "a wheel's radius", false));
        let plane_axis = plane.and_then(|e| self.fixed_normal(e));
        let tire = match tire {
            Some(e) => self.size(e, "a tire's radius", true),
            None => Some(self.pool.zero()),
        };
        let through = match through {
            Some(e) => self.fixed_point(e),
            None => Some((ORIGIN, Vector::default())),
        };
        let (Some(frame), Some(axle_axis), Some(center), Some(radius)) =
            (frame, axle_axis, center, radius)
        else {
            return;
        };
        let (Some(plane_axis), Some(tire), Some(through), Some(axle)) =
            (plane_axis, tire, through, axle)
        else {
            return;
        };
        let wheel = Wheel {
            frame,
            axle: axle_axis,
            radius,
            tire,
            plane: plane_axis,
        };
        let height = self.between(center.clone(), through);
        let velocity = self.velocity(center.0, &center.1);
        let scalar_parts = self.scalar_parts();
        let rows = self.with_geometry(|geometry, pool| {
            rolling_rows(geometry, pool, &wheel, (&height, &velocity), &scalar_parts)
        });
        if !self.check_axle_leaves_the_normal(axle, rows.tilt, &scalar_parts) {
            return;
        }
        let span = SpanRange::from(name.span());
        self.push_rolling_row(span, rows.contact, false);
        for row in rows.slip {
            self.push_rolling_row(span, row, true);
        }
    }

    /// A radius of the wheel (`what`): parameters only, and where it is a
    /// number, positive (zero too if `zero_allowed`): a negative radius
    /// puts the contact point on the wrong side of the centre.
    fn size(&mut self, e: &Expr, what: &str, zero_allowed: bool) -> Option<ExprId> {
        let value = self.scalar(e, SHAPE)?;
        let Some(v) = self.pool.constant_value(value) else {
            return Some(value);
        };
        if v > 0.0 || (zero_allowed && v == 0.0) {
            return Some(value);
        }
        let expected = match zero_allowed {
            true => "zero or positive",
            false => "positive",
        };
        self.errors
            .push(e.range(), format!("{what} must be {expected}; found {v}"));
        None
    }

    /// A row of a rolling contact. One that vanishes identically (the
    /// contact of a wheel whose centre is placed from its contact point, a
    /// planar model's slip across its plane) is kept as a zero row, marked
    /// so, for the rows to stay three.
    fn push_rolling_row(&mut self, span: SpanRange, residual: ExprId, nonholonomic: bool) {
        let vanishes = self.pool.is_zero(residual);
        if !vanishes && !self.check_constrains_something(span, residual) {
            return;
        }
        self.model.constraints.push(Constraint {
            residual,
            nonholonomic,
            vanishes,
        });
    }

    /// The contact point is undefined where the axle is along the normal
    /// (`1 − (n·a)² = 0`): an error if it is so in every configuration, or
    /// at the start, the reference configuration (every coordinate zero,
    /// each quaternion the identity, `t = 0`) where that can be decided
    /// without the parameters' values. Whether the check passes.
    fn check_axle_leaves_the_normal(
        &mut self,
        axle: &Expr,
        tilt: ExprId,
        scalar_parts: &[usize],
    ) -> bool {
        let at_start = at_reference(&mut self.pool, tilt, scalar_parts);
        let when = if self.pool.is_zero(tilt) {
            "in every configuration"
        } else if self.pool.is_zero(at_start) {
            "at the start (every coordinate zero, each quaternion the identity)"
        } else {
            return true;
        };
        self.errors.push(
            axle.range(),
            format!(
                "the wheel's axle is parallel to the plane's normal {when}, where the contact \
                 point is undefined; expected an axle that lies in, or leans from, the plane \
                 (such as `F.y` of a wheel standing on `N.z`)"
            ),
        );
        false
    }

    /// The coordinates of the quaternions' `w` parts (one at the
    /// reference configuration).
    fn scalar_parts(&self) -> Vec<usize> {
        self.model.balls.iter().map(|b| b.quaternion[3]).collect()
    }

    /// The axle: a unit vector of a frame that does not turn in the
    /// wheel's frame (the wheel turns about it).
    fn fixed_axle(
        &mut self,
        e: &Expr,
        axis: crate::model::closure::FrameAxis,
        wheel: crate::model::FrameId,
    ) -> Option<crate::model::closure::FrameAxis> {
        if self.frame_turns_in(axis.0, wheel) && !self.axis_fixed_in(axis, wheel) {
            self.errors.push(
                e.range(),
                "the wheel turns about its axle: expected a unit vector of the wheel's frame \
                 or of a frame fixed in it, such as `F.y` of `wheel: F`",
            );
            return None;
        }
        Some(axis)
    }

    /// Whether the unit vector `axis` has constant components in
    /// `frame`'s axes (`C.y` in `B = C.rotate_y(phi)`).
    fn axis_fixed_in(
        &mut self,
        axis: crate::model::closure::FrameAxis,
        frame: crate::model::FrameId,
    ) -> bool {
        let components = self.with_geometry(|geometry, pool| {
            let a = Vector::unit(pool, axis.0, axis.1);
            (0..3)
                .map(|i| {
                    let e = Vector::unit(pool, frame, i);
                    geometry.dot(pool, &a, &e)
                })
                .collect::<Vec<_>>()
        });
        let moving = SymKinds::COORD | SymKinds::TIME;
        components
            .iter()
            .all(|&c| !self.pool.kinds(c).intersects(moving))
    }

    /// The plane's normal: a unit vector of a frame that does not turn.
    fn fixed_normal(&mut self, e: &Expr) -> Option<crate::model::closure::FrameAxis> {
        let (frame, axis) = self.frame_axis(e)?;
        if self.frame_turns(frame) {
            self.errors.push(
                e.range(),
                "a wheel rolls on a fixed plane: expected a unit vector of `N` or of a frame \
                 that does not turn, such as `N.z`",
            );
            return None;
        }
        Some((frame, axis))
    }

    /// A point of the plane: one that does not move.
    fn fixed_point(&mut self, e: &Expr) -> Option<(crate::model::PointId, Vector)> {
        let (base, offset) = self.point_value(e, GEOMETRY)?;
        if self.point_moves(base, &offset) {
            self.errors.push(
                e.range(),
                "a wheel rolls on a fixed plane: expected a point fixed in `N` (`O`, or one \
                 placed by constants) for `through`",
            );
            return None;
        }
        Some((base, offset))
    }
}
