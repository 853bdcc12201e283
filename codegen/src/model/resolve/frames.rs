//! The `frame` and `point` statements: a frame turned from another about
//! one of its axes or a constant axis, a point placed from another.

use super::Resolver;
use super::evaluate::GEOMETRY;
use super::scope::Binding;
use crate::expr::ExprId;
use crate::language::ast::Expr;
use crate::language::keyword::{ROTATE, ROTATIONS};
use crate::model::unit_axis;
use proc_macro2::Ident;

impl Resolver {
    /// `frame B = F.rotate_z(angle);` or `F.rotate([ax, ay, az], angle)`.
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
        let rotation = self.rotation(value, method, args);
        match (parent, rotation) {
            (Some(parent), Some((axis, angle))) => {
                self.define_frame(name, parent, axis, angle, None);
            }
            _ => {
                self.define(name, Binding::Invalid);
            }
        }
    }

    /// The axis and angle of `F.METHOD(args)` (`value`).
    fn rotation(
        &mut self,
        value: &Expr,
        method: &Ident,
        args: &[Expr],
    ) -> Option<([ExprId; 3], ExprId)> {
        match ROTATIONS.iter().position(|r| method == r) {
            Some(axis) => match args {
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
            None if method == ROTATE => match args {
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
        }
    }

    /// `point P = Q + vec;`.
    pub(super) fn point_statement(&mut self, name: &Ident, value: &Expr) {
        match self.point_value(value, GEOMETRY) {
            Some(placement) => {
                self.define_point(name, Some(placement));
            }
            None => {
                self.define(name, Binding::Invalid);
            }
        }
    }
}
