//! Rolling contacts: the three constraint rows of a wheel (a disc, or a
//! torus) rolling without slipping on a fixed plane.
//!
//! With `n` the plane's unit normal and `a` the wheel's unit axle, the
//! wheel's point nearest the plane is `C = P − r u − rₜ n`, where
//! `u = (n − (n·a) a) / |n − (n·a) a|` is the unit vector of the wheel's
//! plane nearest the normal and `|n − (n·a) a| = √(1 − (n·a)²)` (`rₜ = 0`
//! for a disc). The rows are the height of `C` above the plane
//! (holonomic), then the velocity of the wheel's material point at `C`,
//! `v_P + ω × (C − P)`, along the plane's two in-plane axes in cyclic
//! order (nonholonomic, linear in the speeds).

use super::algebra::Geometry;
use super::closure::FrameAxis;
use super::{FrameId, Vector};
use crate::expr::{ExprId, Func, Node, Pool, Sym};
use crate::readable::ReadableForms;

/// A wheel and the plane it rolls on, resolved.
pub struct Wheel {
    /// The frame the wheel turns with.
    pub frame: FrameId,
    /// Its axle, a unit vector fixed in `frame`.
    pub axle: FrameAxis,
    /// The radius of the disc (of the torus' centre circle).
    pub radius: ExprId,
    /// The torus' tire radius (zero for a disc).
    pub tire: ExprId,
    /// The plane's unit normal, a unit vector of a frame fixed in `N`.
    pub plane: FrameAxis,
}

/// The rows of a rolling contact, and the squared length `1 − (n·a)²` they
/// divide by.
pub struct RollingRows {
    /// The height of the contact point above the plane.
    pub contact: ExprId,
    /// The slip velocity along the plane's two in-plane axes.
    pub slip: [ExprId; 2],
    /// `1 − (n·a)²`: zero where the axle is along the normal (the contact
    /// point is then undefined).
    pub tilt: ExprId,
}

/// The rows of `wheel` whose centre is at `center` from a point of the
/// plane, moving at `velocity` in `N`; `scalar_parts` lists the
/// quaternions' `w` coordinates (see [`at_reference`]).
pub fn rolling_rows(
    geometry: &Geometry<'_>,
    pool: &mut Pool,
    wheel: &Wheel,
    (center, velocity): (&Vector, &Vector),
    scalar_parts: &[usize],
) -> RollingRows {
    let n = Vector::unit(pool, wheel.plane.0, wheel.plane.1);
    let a = Vector::unit(pool, wheel.axle.0, wheel.axle.1);
    let along = geometry.dot(pool, &n, &a);
    let along_squared = pool.powi(along, 2);
    let one = pool.one();
    let tilt = pool.sub(one, along_squared);
    let length = tilt_length(pool, tilt, scalar_parts);
    // The height of C: (P − Q)·n − r |n − (n·a) a| − rₜ (u·n = |n − (n·a) a|).
    let height = geometry.dot(pool, center, &n);
    let reach = pool.mul(wheel.radius, length);
    let (below, tire_below) = (pool.neg(reach), pool.neg(wheel.tire));
    let contact = pool.sum([height, below, tire_below]);
    // C − P = −(r / |..|) (n − (n·a) a) − rₜ n.
    let minus_along = pool.neg(along);
    let across = a.scale(minus_along, pool);
    let in_plane = n.add(&across, pool);
    let inverse = pool.powi(length, -1);
    let scale = pool.mul(wheel.radius, inverse);
    let minus_scale = pool.neg(scale);
    let arm = in_plane
        .scale(minus_scale, pool)
        .add(&n.scale(tire_below, pool), pool);
    let omega = geometry.angular_velocity(pool, wheel.frame);
    let turning = geometry.cross(pool, &omega, &arm);
    let slip_velocity = velocity.add(&turning, pool);
    let (frame, k) = wheel.plane;
    let slip = [(k + 1) % 3, (k + 2) % 3].map(|i| {
        let axis = Vector::unit(pool, frame, i);
        geometry.dot(pool, &slip_velocity, &axis)
    });
    RollingRows {
        contact,
        slip,
        tilt,
    }
}

/// The most terms the readable form of `1 − (n·a)²` may have when it is
/// looked at for a square.
const TILT_TERMS: usize = 64;

/// `|n − (n·a)a| = √tilt`, `tilt = 1 − (n·a)²`. Where the readable form of
/// `tilt` is the square `e²` of an expression (`1 − sin²θ = cos²θ` for a
/// disc leaning by `θ`), it is `e`, signed to be positive at the reference
/// configuration: the contact point is undefined where `e` vanishes, so a
/// rolling motion from the start keeps its sign, and the contact row of a
/// wheel whose centre is placed from its contact point (`r cos θ − r cos θ`)
/// vanishes identically. Otherwise, or where the sign there depends on the
/// parameters, the square root.
fn tilt_length(pool: &mut Pool, tilt: ExprId, scalar_parts: &[usize]) -> ExprId {
    let root = ReadableForms::default()
        .get(pool, tilt, TILT_TERMS)
        .and_then(|form| match *pool.node(form) {
            Node::Pow(base, exponent) if exponent > 0 && exponent % 2 == 0 => {
                Some(pool.powi(base, exponent / 2))
            }
            _ => None,
        });
    let signed = root.and_then(|root| {
        let start = at_reference(pool, root, scalar_parts);
        match pool.as_number(start)?.to_f64() {
            x if x > 0.0 => Some(root),
            x if x < 0.0 => Some(pool.neg(root)),
            _ => None,
        }
    });
    signed.unwrap_or_else(|| pool.func(Func::Sqrt, tilt))
}

/// `e` at the reference configuration: every coordinate zero but each
/// quaternion's `w` (listed in `scalar_parts`), which is one, and `t = 0`.
pub fn at_reference(pool: &mut Pool, e: ExprId, scalar_parts: &[usize]) -> ExprId {
    let (zero, one) = (pool.zero(), pool.one());
    pool.rebuild(&[e], |pool, node, images| match pool.node(node) {
        Node::Sym(Sym::Coord(i)) if scalar_parts.contains(&(*i as usize)) => one,
        Node::Sym(Sym::Coord(_) | Sym::Time) => zero,
        _ => pool.with_children(node, images),
    })[0]
}
