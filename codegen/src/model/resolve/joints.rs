//! The `joint` statement: a revolute or prismatic joint (a child frame
//! turned or slid by a coordinate of its own) and a spherical or free one
//! (a child frame turned by a unit quaternion, with speeds of its own).

use super::Resolver;
use super::evaluate::GEOMETRY;
use super::scope::{Binding, is_plain};
use crate::expr::{ExprId, Sym};
use crate::language::ast::{Expr, Field};
use crate::language::keyword::field::{AT, AXIS, CHILD, COORDINATE, PARENT};
use crate::language::keyword::{Symbol, joint};
use crate::model::{Ball, FrameId, JointKind, PointId, Vector, quaternion, unit_axis};
use proc_macro2::Ident;

/// The kinds of `joint KIND NAME { .. }`, by keyword.
const JOINT_KINDS: [(Symbol, JointKind); 4] = [
    (joint::REVOLUTE, JointKind::Revolute),
    (joint::PRISMATIC, JointKind::Prismatic),
    (joint::SPHERICAL, JointKind::Spherical),
    (joint::FREE, JointKind::Free),
];

/// What a spherical or free joint adds: the indices of its coordinates and
/// speeds.
struct BallSymbols {
    /// A free joint's position `(x, y, z)` (coordinates).
    position: Option<[u32; 3]>,
    /// The quaternion `(qx, qy, qz, qw)` (coordinates).
    quaternion: [u32; 4],
    /// A free joint's velocity `(vx, vy, vz)` in the child's axes (speeds).
    velocity: Option<[u32; 3]>,
    /// The angular velocity `(wx, wy, wz)` in the child's axes (speeds).
    angular: [u32; 3],
}

impl Resolver {
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
        let [parent, child, axis, coordinate, at] =
            self.fields(name, "joint", fields, [PARENT, CHILD, AXIS, COORDINATE, AT]);
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
        let [parent_field, child, at] = self.fields(name, what, fields, [PARENT, CHILD, AT]);
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
        let symbols = self.ball_symbols(name, free);
        self.set_quaternion_rates(&symbols);
        let mut origin = offset;
        if let (Some(position), Some(velocity)) = (symbols.position, symbols.velocity) {
            let moved = self.free_translation(parent, &symbols.quaternion, position, velocity);
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
                quaternion: symbols.quaternion.map(|i| i as usize),
                angular: as_index(symbols.angular),
                translation: symbols
                    .position
                    .zip(symbols.velocity)
                    .map(|(p, v)| (as_index(p), as_index(v))),
            });
        }
    }

    /// Declares the coordinates and speeds of the spherical or `free`
    /// joint `name`: `name_x`.., `name_qx`.., `name_vx`.., `name_wx`...
    fn ball_symbols(&mut self, name: &Ident, free: bool) -> BallSymbols {
        let named = |suffix: &str| Ident::new(&format!("{name}_{suffix}"), name.span());
        let position = free.then(|| ["x", "y", "z"].map(|c| self.joint_coordinate(&named(c))));
        let quaternion = ["qx", "qy", "qz", "qw"].map(|c| self.joint_coordinate(&named(c)));
        for &i in position.iter().flatten().chain(&quaternion) {
            self.joint_of_coordinate.insert(i, name.clone());
        }
        let velocity = free.then(|| ["vx", "vy", "vz"].map(|c| self.add_speed(&named(c), false)));
        let angular = ["wx", "wy", "wz"].map(|c| self.add_speed(&named(c), false));
        BallSymbols {
            position,
            quaternion,
            velocity,
            angular,
        }
    }

    /// `q̇ = ½ q ⊗ (0, ω)`: the quaternion's rates in the angular speeds.
    fn set_quaternion_rates(&mut self, symbols: &BallSymbols) {
        let q = symbols.quaternion.map(|i| self.pool.sym(Sym::Coord(i)));
        let omega = symbols.angular.map(|k| self.pool.sym(Sym::Speed(k)));
        let rates = quaternion::rates(&mut self.pool, q, omega);
        for (&i, rate) in symbols.quaternion.iter().zip(rates) {
            self.pool.set_rate(i, rate);
        }
    }

    /// A free joint's translation `x N.x + y N.y + z N.z` (in the parent's
    /// axes), with the position's rates `ṙ = R v` set from the velocity,
    /// given in the child's axes.
    fn free_translation(
        &mut self,
        parent: FrameId,
        quaternion: &[u32; 4],
        position: [u32; 3],
        velocity: [u32; 3],
    ) -> Vector {
        let q = quaternion.map(|i| self.pool.sym(Sym::Coord(i)));
        let r = quaternion::rotation(&mut self.pool, q);
        let v = velocity.map(|k| self.pool.sym(Sym::Speed(k)));
        for (i, &coordinate) in position.iter().enumerate() {
            let terms: Vec<ExprId> = (0..3).map(|j| self.pool.mul(r[i][j], v[j])).collect();
            let rate = self.pool.sum(terms);
            self.pool.set_rate(coordinate, rate);
        }
        let components = position.map(|i| self.pool.sym(Sym::Coord(i)));
        Vector {
            parts: vec![(parent, components)],
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
        if let Some(Expr::Name(child)) = fields.iter().find(|f| f.name == CHILD).map(|f| &f.value) {
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
}
