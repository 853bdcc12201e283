//! The rules of the language beyond types and names: one `check_*`
//! function per rule, with the reason for it, and the questions they ask
//! of the model (whether a point moves, a frame turns with time, a row is
//! linear in the speeds).

use super::Resolver;
use crate::expr::{ExprId, Sym, SymKinds};
use crate::language::ast::{Expr, SpanRange};
use crate::model::{FrameId, NEWTONIAN, PointId, Vector};

impl Resolver {
    /// Everything generated is indexed by the coordinates: a system without
    /// any has no equations to derive. Not reported after a rejected joint
    /// statement (already reported), which may have been the free or
    /// spherical joint meant to make them.
    pub(super) fn check_has_coordinates(&mut self) {
        if self.model.coordinates.is_empty() && !self.rejected_joint {
            self.errors.push(
                self.model.name.span(),
                "a system needs at least one generalized coordinate: add `coordinates q1, ...;`",
            );
        }
    }

    /// A constraint that involves no coordinate or speed holds always or
    /// never: it adds no row of `A`, only a contradiction or nothing.
    /// Whether the constraint (`residual`, written at `span`) passes.
    pub(super) fn check_constrains_something(&mut self, span: SpanRange, residual: ExprId) -> bool {
        let moves = SymKinds::COORD.union(SymKinds::SPEED);
        let passes = self.pool.kinds(residual).intersects(moves);
        if !passes {
            self.errors.push(
                span,
                "this constraint involves no coordinate or speed once simplified (`lhs - rhs` \
                 depends on parameters and `t` only): it holds always or never and constrains \
                 nothing; a constraint relates the coordinates, such as `x == l * sin(theta)`, \
                 or their speeds `dt(q)`",
            );
        }
        passes
    }

    /// A nonholonomic row enters `A v̇ = b` through its coefficients of the
    /// speeds, which is only its whole content if it is linear in them.
    /// Whether the row passes.
    pub(super) fn check_linear_in_speeds(&mut self, span: SpanRange, residual: ExprId) -> bool {
        let passes = self.linear_in_speeds(residual);
        if !passes {
            self.errors.push(
                span,
                "a nonholonomic constraint must be linear in the speeds `dt(q)`: \
                 its coefficients of the speeds may depend on coordinates, parameters and `t` only",
            );
        }
        passes
    }

    /// A free joint's coordinates place its child in the ground's axes
    /// (Pinocchio's free flyer): its parent, written at `field`, must be `N`.
    pub(super) fn check_free_joint_parent(&mut self, field: &Expr, parent: FrameId) {
        if parent != NEWTONIAN {
            self.errors.push(
                field.range(),
                "a free joint joins a floating body to the ground: its parent must be `N` \
                 (a body on another body needs a spherical joint, or a free joint and a \
                 constraint)",
            );
        }
    }

    /// A free joint's position coordinates are measured from its `at`
    /// point (`base + offset`, written at `field`), which must therefore
    /// stay put in `N`.
    pub(super) fn check_free_joint_origin(&mut self, field: &Expr, base: PointId, offset: &Vector) {
        if self.point_moves(base, offset) {
            self.errors.push(
                field.range(),
                "a free joint's `at` must be a point fixed in `N` (its origin's position \
                 is measured from there)",
            );
        }
    }

    /// `linearize(..)` finds its independent entries by
    /// [`chart`](crate::model::output::chart), which says what is wrong
    /// with them.
    pub(super) fn check_solved_outputs(&mut self) {
        use crate::model::OutputKind::Linearize;
        for index in 0..self.model.outputs.len() {
            let output = &self.model.outputs[index];
            if output.kind == Linearize {
                match crate::model::output::chart(&self.model, &mut self.pool, output) {
                    Ok(chart) => self.model.outputs[index].chart = Some(chart),
                    Err((span, message)) => self.errors.push(span, message),
                }
            }
        }
    }

    pub(super) fn linear_in_speeds(&mut self, residual: ExprId) -> bool {
        (0..self.model.speeds.len() as u32).all(|i| {
            let coefficient = self.pool.diff(residual, Sym::Speed(i));
            !self.pool.kinds(coefficient).intersects(SymKinds::SPEED)
        })
    }

    /// Whether the point `base + offset` moves in `N` (depends on a
    /// coordinate or `t`, or lies along a frame that turns).
    pub(super) fn point_moves(&mut self, base: PointId, offset: &Vector) -> bool {
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

    /// Whether `frame` turns relative to `other`: some placement on the
    /// way from either to their common ancestor moves (a ball, or an
    /// angle that is not constant).
    pub(super) fn frame_turns_in(&self, frame: FrameId, other: FrameId) -> bool {
        let path = |mut f: FrameId| {
            let mut path = vec![f];
            while let Some(placement) = &self.model.frames[f.0].placement {
                f = placement.parent;
                path.push(f);
            }
            path
        };
        let (up, other_up) = (path(frame), path(other));
        let moves = |f: &FrameId| {
            self.model.frames[f.0].placement.as_ref().is_some_and(|p| {
                p.ball.is_some() || !SymKinds::PARAM.contains(self.pool.kinds(p.angle))
            })
        };
        let below_common = |path: &[FrameId], other: &[FrameId]| {
            path.iter().take_while(|f| !other.contains(f)).any(moves)
        };
        below_common(&up, &other_up) || below_common(&other_up, &up)
    }

    /// Whether `frame` turns in `N`.
    pub(super) fn frame_turns(&self, mut frame: FrameId) -> bool {
        while let Some(placement) = &self.model.frames[frame.0].placement {
            let kinds = self.pool.kinds(placement.angle);
            if placement.ball.is_some() || !SymKinds::PARAM.contains(kinds) {
                return true;
            }
            frame = placement.parent;
        }
        false
    }
}
