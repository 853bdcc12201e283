//! Vector algebra on the user's vectors: dot and cross products, the vector
//! between two points and the rate of change of a vector in `N`.
//!
//! A [`Vector`] keeps one part per frame; a product takes its parts in
//! pairs and turns the second into the first's axes through the two
//! frames' common ancestor (so `dot(B.x, C.y)` of two frames on one hinge
//! meets that hinge's rotation only, and a planar model no 3-D rotation).
//! A rate is the transport theorem part by part: `d/dt (c in F) =
//! ċ + ω_F × c` in `F`'s axes, so `velocity(P)` keeps the frames its
//! position was written in.

use super::{FrameId, Model, PointId, Vector};
use crate::expr::{ExprId, Func, Pool};
use crate::kinematics::{self, Kinematics};

/// The frames and points of a model with their kinematics: what a product
/// or a rate of vectors reads.
pub struct Geometry<'a> {
    /// The model so far.
    pub model: &'a Model,
    /// Its rotations and angular velocities.
    pub kinematics: &'a Kinematics,
}

impl Geometry<'_> {
    /// `a · b`.
    pub fn dot(&self, pool: &mut Pool, a: &Vector, b: &Vector) -> ExprId {
        let mut terms = Vec::new();
        for (frame, mine) in &a.parts {
            for (from, theirs) in &b.parts {
                let theirs = self
                    .kinematics
                    .rotate_between(pool, self.model, *from, *frame, theirs);
                terms.push(kinematics::dot(pool, mine, &theirs));
            }
        }
        pool.sum(terms)
    }

    /// `a × b`, in the frames of `a`'s parts.
    pub fn cross(&self, pool: &mut Pool, a: &Vector, b: &Vector) -> Vector {
        let mut product = Vector::default();
        for (frame, mine) in &a.parts {
            for (from, theirs) in &b.parts {
                let theirs = self
                    .kinematics
                    .rotate_between(pool, self.model, *from, *frame, theirs);
                let part = kinematics::cross(pool, mine, &theirs);
                product = product.add(&Vector::along(pool, *frame, part), pool);
            }
        }
        product
    }

    /// `|a|`.
    pub fn norm(&self, pool: &mut Pool, a: &Vector) -> ExprId {
        let square = self.dot(pool, a, a);
        pool.func(Func::Sqrt, square)
    }

    /// The rate of change of `v` seen from `N`: `ċ + ω_F × c` for each part
    /// `c` in `F`'s axes.
    pub fn rate(&self, pool: &mut Pool, v: &Vector) -> Vector {
        let mut rate = Vector::default();
        for (frame, components) in &v.parts {
            let omega = self.kinematics.angular_velocity(*frame);
            let turning = kinematics::cross(pool, &omega, components);
            let part = [0, 1, 2].map(|i| {
                let own = pool.time_derivative(components[i]);
                pool.add(own, turning[i])
            });
            rate = rate.add(&Vector::along(pool, *frame, part), pool);
        }
        rate
    }

    /// The angular velocity of `frame` in `N`, in its own axes.
    pub fn angular_velocity(&self, pool: &Pool, frame: FrameId) -> Vector {
        Vector::along(pool, frame, self.kinematics.angular_velocity(frame))
    }
}

/// The vector from `O` to the point `base + offset`: the offsets of its
/// chain of points, each in the frames it was written in.
pub fn from_origin(model: &Model, pool: &mut Pool, base: PointId, offset: &Vector) -> Vector {
    let mut total = offset.clone();
    let mut point = base;
    while let Some((next, offset)) = &model.points[point.0].placement {
        total = total.add(offset, pool);
        point = *next;
    }
    total
}
