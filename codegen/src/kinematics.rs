//! Kinematics of a checked model: rotation matrices of frames, positions
//! of points, angular velocities, partial velocities and the velocity-
//! independent part of accelerations — everything d'Alembert's principle
//! dots together.
//!
//! Conventions: a point's position, velocity and partial velocities are
//! measured in `N`'s axes; a frame's angular velocity, its partials and its
//! angular acceleration in the frame's own axes (where its inertia is
//! given). Velocities are linear in the speeds `v` (through the kinematic
//! differential equations `q̇ = N(q) v` of the pool); partial velocities are
//! `∂v_P/∂vₖ = Σᵢ (∂r/∂qᵢ) (∂q̇ᵢ/∂vₖ)` (`∂r/∂qₖ` when `q̇ = v`), and
//! accelerations split as `a = Σₖ (∂v/∂vₖ) v̇ₖ + rate(v)`, where `rate`
//! differentiates in time at constant speeds; so no expression ever holds
//! a `v̇`.

use crate::expr::{ExprId, Pool, Sym, SymKinds};
use crate::model::{
    FrameId, FramePlacement, Model, NEWTONIAN, PointId, Vector, principal_axis, quaternion,
};

/// A column of three components.
pub type Vec3 = [ExprId; 3];
/// A 3×3 matrix, row-major.
pub type Mat3 = [[ExprId; 3]; 3];

/// Rotations, positions and angular velocities of every frame and point.
pub struct Kinematics {
    /// `rotation[f]` maps frame `f`'s components to `N`'s.
    rotation: Vec<Mat3>,
    /// `angular_velocity[f]`: `ω` of frame `f` in `N`, in `f`'s axes.
    angular_velocity: Vec<Vec3>,
    /// `position[p]`: `r` of point `p` from `O`, in `N`'s axes.
    position: Vec<Vec3>,
    /// Number of generalized coordinates.
    nq: u32,
    /// `∂q̇ᵢ/∂vₖ`, for each speed `k`, over the coordinates `i` it moves;
    /// `None` when every `q̇ᵢ = vᵢ`.
    rate_partials: Option<Vec<Vec<(u32, ExprId)>>>,
}

impl Kinematics {
    /// Computes the rotation and angular velocity of every frame and the
    /// position of every point of `model`.
    pub fn new(model: &Model, pool: &mut Pool) -> Kinematics {
        let mut kinematics = Kinematics {
            rotation: Vec::with_capacity(model.frames.len()),
            angular_velocity: Vec::with_capacity(model.frames.len()),
            position: Vec::with_capacity(model.points.len()),
            nq: model.nq() as u32,
            rate_partials: (!pool.rates_are_speeds()).then(|| rate_partials(model, pool)),
        };
        for frame in &model.frames {
            let (rotation, omega) = match &frame.placement {
                None => (identity(pool), [pool.zero(); 3]),
                Some(p) => {
                    let relative = placement_rotation(pool, model, p);
                    let rotation = mat_mul(pool, &kinematics.rotation[p.parent.0], &relative);
                    // ω_F = ω_parent (in F's axes) + the relative rate:
                    // (dθ/dt) ê, where the axis ê has the same components in
                    // F as in its parent, or a quaternion joint's speeds.
                    let carried =
                        transpose_mul(pool, &relative, &kinematics.angular_velocity[p.parent.0]);
                    let own = match p.ball {
                        Some(b) => model.balls[b]
                            .angular
                            .map(|k| pool.sym(Sym::Speed(k as u32))),
                        None => {
                            let spin = pool.time_derivative(p.angle);
                            p.axis.map(|e| pool.mul(spin, e))
                        }
                    };
                    let omega = [0, 1, 2].map(|i| pool.add(carried[i], own[i]));
                    (rotation, omega)
                }
            };
            kinematics.rotation.push(rotation);
            kinematics.angular_velocity.push(omega);
        }
        for point in &model.points {
            let r = match &point.placement {
                None => [pool.zero(); 3],
                Some((base, offset)) => {
                    let offset = kinematics.express(pool, model, offset, NEWTONIAN);
                    add3(pool, &kinematics.position[base.0], &offset)
                }
            };
            kinematics.position.push(r);
        }
        kinematics
    }

    /// Position of point `p` from `O`, in `N`'s axes.
    pub fn position(&self, p: PointId) -> Vec3 {
        self.position[p.0]
    }

    /// Angular velocity of frame `f`, in `f`'s axes.
    pub fn angular_velocity(&self, f: FrameId) -> Vec3 {
        self.angular_velocity[f.0]
    }

    /// Velocity of point `p` in `N`, in `N`'s axes.
    pub fn velocity(&self, pool: &mut Pool, p: PointId) -> Vec3 {
        self.position[p.0].map(|x| pool.time_derivative(x))
    }

    /// `∂v_p/∂vₖ = Σᵢ (∂r_p/∂qᵢ) (∂q̇ᵢ/∂vₖ)`, in `N`'s axes.
    pub fn partial_velocity(&self, pool: &mut Pool, p: PointId, k: usize) -> Vec3 {
        let position = self.position[p.0];
        self.through_rates(pool, k, |pool, i| {
            position.map(|x| pool.diff(x, Sym::Coord(i)))
        })
    }

    /// `Σᵢ (∂q̇ᵢ/∂vₖ) gradient(i)`, where `gradient(i)` is a derivative by
    /// `qᵢ`: the chain rule from a coordinate to the speed `k`.
    pub fn through_rates<const N: usize>(
        &self,
        pool: &mut Pool,
        k: usize,
        mut gradient: impl FnMut(&mut Pool, u32) -> [ExprId; N],
    ) -> [ExprId; N] {
        let Some(rate_partials) = &self.rate_partials else {
            return gradient(pool, k as u32);
        };
        let mut terms = [(); N].map(|_| Vec::new());
        for &(i, coefficient) in &rate_partials[k] {
            let g = gradient(pool, i);
            for (terms, g) in terms.iter_mut().zip(g) {
                terms.push(pool.mul(g, coefficient));
            }
        }
        terms.map(|t| pool.sum(t))
    }

    /// `∂ω_f/∂vₖ`, in `f`'s axes.
    pub fn partial_angular_velocity(&self, pool: &mut Pool, f: FrameId, k: usize) -> Vec3 {
        self.angular_velocity[f.0].map(|x| pool.diff(x, Sym::Speed(k as u32)))
    }

    /// The part of a point's acceleration that remains when every `q̈ = 0`.
    pub fn acceleration_bias(&self, pool: &mut Pool, p: PointId) -> Vec3 {
        let v = self.velocity(pool, p);
        v.map(|x| rate_at_constant_speeds(pool, x, self.nq))
    }

    /// The part of a frame's angular acceleration (in its own axes) that
    /// remains when every `q̈ = 0`.
    pub fn angular_acceleration_bias(&self, pool: &mut Pool, f: FrameId) -> Vec3 {
        self.angular_velocity[f.0].map(|x| rate_at_constant_speeds(pool, x, self.nq))
    }

    /// The components of `v` in `frame`'s axes. Each part is rotated from
    /// its own frame through their lowest common ancestor, so a planar chain
    /// meets only the rotations between the frames involved.
    pub fn express(&self, pool: &mut Pool, model: &Model, v: &Vector, frame: FrameId) -> Vec3 {
        let mut total = [pool.zero(); 3];
        for (from, components) in &v.parts {
            let part = self.rotate_between(pool, model, *from, frame, components);
            total = add3(pool, &total, &part);
        }
        total
    }

    /// Components `c` given in `from`'s axes, re-expressed in `to`'s axes.
    pub fn rotate_between(
        &self,
        pool: &mut Pool,
        model: &Model,
        from: FrameId,
        to: FrameId,
        c: &Vec3,
    ) -> Vec3 {
        let ancestor = common_ancestor(model, from, to);
        let up = self.relative_rotation(pool, model, ancestor, from);
        let in_ancestor = mat_vec(pool, &up, c);
        let down = self.relative_rotation(pool, model, ancestor, to);
        transpose_mul(pool, &down, &in_ancestor)
    }

    /// The rotation mapping the components of `frame` to those of its
    /// ancestor `ancestor` (`N` included), through the frames between.
    pub fn relative_rotation(
        &self,
        pool: &mut Pool,
        model: &Model,
        ancestor: FrameId,
        frame: FrameId,
    ) -> Mat3 {
        if ancestor == NEWTONIAN {
            return self.rotation[frame.0];
        }
        placement_chain(pool, model, ancestor, frame)
            .iter()
            .rev()
            .fold(identity(pool), |acc, r| mat_mul(pool, &acc, r))
    }

    /// [`Kinematics::relative_rotation`] as a product of factors, the
    /// outermost first: the rotations of the frame placements between
    /// `ancestor` and `frame`, each run of constant ones (no coordinate in
    /// them: a mount's fixed turn) multiplied into one, identities left out.
    /// Applied one after the other, a joint's turn about one of its axes
    /// and a fixed turn about another cost two sparse products, where their
    /// product is a dense matrix whose constants spread over every sum it
    /// enters.
    pub fn rotation_factors(
        &self,
        pool: &mut Pool,
        model: &Model,
        ancestor: FrameId,
        frame: FrameId,
    ) -> Vec<Mat3> {
        if ancestor == NEWTONIAN {
            return vec![self.rotation[frame.0]];
        }
        let mut factors: Vec<Mat3> = Vec::new();
        for r in placement_chain(pool, model, ancestor, frame).iter().rev() {
            match factors.last_mut() {
                Some(last) if is_fixed(pool, last) && is_fixed(pool, r) => {
                    *last = mat_mul(pool, last, r)
                }
                _ => factors.push(*r),
            }
        }
        factors.retain(|f| *f != identity(pool));
        factors
    }
}

/// `∂e/∂t + Σⱼ (∂e/∂qⱼ) q̇ⱼ` over the `nq` coordinates, with `q̇ⱼ` in the
/// speeds: the time derivative of `e` with the speeds held constant (the
/// acceleration terms that do not multiply a `v̇`).
pub fn rate_at_constant_speeds(pool: &mut Pool, e: ExprId, nq: u32) -> ExprId {
    let mut terms = vec![pool.diff(e, Sym::Time)];
    for j in 0..nq {
        let d = pool.diff(e, Sym::Coord(j));
        if !pool.is_zero(d) {
            let rate = pool.rate(j);
            terms.push(pool.mul(d, rate));
        }
    }
    pool.sum(terms)
}

/// `∂q̇ᵢ/∂vₖ` for each speed `k`, over the coordinates `i` it moves.
fn rate_partials(model: &Model, pool: &mut Pool) -> Vec<Vec<(u32, ExprId)>> {
    (0..model.nv() as u32)
        .map(|k| {
            (0..model.nq() as u32)
                .filter_map(|i| {
                    let rate = pool.rate(i);
                    let d = pool.diff(rate, Sym::Speed(k));
                    (!pool.is_zero(d)).then_some((i, d))
                })
                .collect()
        })
        .collect()
}

/// The rotation of a frame from its parent: about a constant axis, or by a
/// joint's quaternion.
fn placement_rotation(pool: &mut Pool, model: &Model, p: &FramePlacement) -> Mat3 {
    match p.ball {
        Some(b) => {
            let q = model.balls[b]
                .quaternion
                .map(|i| pool.sym(Sym::Coord(i as u32)));
            quaternion::rotation(pool, q)
        }
        None => axis_rotation(pool, &p.axis, p.angle),
    }
}

/// The rotations of the frame placements from `frame` up to `ancestor`,
/// `frame`'s first.
fn placement_chain(pool: &mut Pool, model: &Model, ancestor: FrameId, frame: FrameId) -> Vec<Mat3> {
    let mut chain = Vec::new();
    let mut f = frame;
    while f != ancestor {
        let Some(p) = &model.frames[f.0].placement else {
            break;
        };
        chain.push(placement_rotation(pool, model, p));
        f = p.parent;
    }
    chain
}

/// The frames from `f` up to `N`, `f` first.
fn ancestors(model: &Model, mut f: FrameId) -> Vec<FrameId> {
    let mut path = vec![f];
    while let Some(p) = &model.frames[f.0].placement {
        f = p.parent;
        path.push(f);
    }
    path
}

fn common_ancestor(model: &Model, a: FrameId, b: FrameId) -> FrameId {
    let above_b = ancestors(model, b);
    ancestors(model, a)
        .into_iter()
        .find(|f| above_b.contains(f))
        .unwrap_or(NEWTONIAN)
}

/// The rotation by `angle` (right-handed) about the unit vector `axis`,
/// mapping the rotated frame's components to the parent's: Rodrigues'
/// `R = cos θ 1 + sin θ [k]× + (1 − cos θ) k kᵀ`, written directly for a
/// coordinate axis.
pub fn axis_rotation(pool: &mut Pool, axis: &[ExprId; 3], angle: ExprId) -> Mat3 {
    if let Some(i) = principal_axis(pool, axis) {
        return principal_rotation(pool, i, angle);
    }
    let c = pool.cos(angle);
    let s = pool.sin(angle);
    let one = pool.one();
    let versine = pool.sub(one, c);
    let mut r = [[pool.zero(); 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            let outer = pool.mul(axis[i], axis[j]);
            let mut terms = vec![pool.mul(versine, outer)];
            if i == j {
                terms.push(c);
            } else {
                // [k]× has k_m at (j + 1, j) and −k_m at (j, j + 1) for the
                // remaining index m.
                let m = 3 - i - j;
                let sign = if (i + 1) % 3 == j { -1 } else { 1 };
                let k = pool.mul(s, axis[m]);
                let signed = pool.int(sign);
                terms.push(pool.mul(signed, k));
            }
            *entry = pool.sum(terms);
        }
    }
    r
}

/// The rotation by `angle` about the `axis`-th coordinate axis.
fn principal_rotation(pool: &mut Pool, axis: usize, angle: ExprId) -> Mat3 {
    let (zero, one) = (pool.zero(), pool.one());
    let c = pool.cos(angle);
    let s = pool.sin(angle);
    let minus_s = pool.neg(s);
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut r = [[zero; 3]; 3];
    r[axis][axis] = one;
    r[i][i] = c;
    r[j][j] = c;
    r[i][j] = minus_s;
    r[j][i] = s;
    r
}

/// The identity matrix.
pub fn identity(pool: &Pool) -> Mat3 {
    let mut r = [[pool.zero(); 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        row[i] = pool.one();
    }
    r
}

/// Whether the rotation `m` is fixed: no coordinate or time in it.
pub fn is_fixed(pool: &Pool, m: &Mat3) -> bool {
    let moving = SymKinds::COORD | SymKinds::TIME;
    m.iter()
        .flatten()
        .all(|&x| !pool.kinds(x).intersects(moving))
}

/// `aᵀ`.
pub fn transpose(a: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [a[0][i], a[1][i], a[2][i]])
}

/// `a · b`.
pub fn mat_mul(pool: &mut Pool, a: &Mat3, b: &Mat3) -> Mat3 {
    let mut r = [[pool.zero(); 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            let terms: Vec<ExprId> = (0..3).map(|k| pool.mul(a[i][k], b[k][j])).collect();
            *entry = pool.sum(terms);
        }
    }
    r
}

/// `a · v`.
pub fn mat_vec(pool: &mut Pool, a: &Mat3, v: &Vec3) -> Vec3 {
    [0, 1, 2].map(|i| dot(pool, &a[i], v))
}

/// `aᵀ · v`.
pub fn transpose_mul(pool: &mut Pool, a: &Mat3, v: &Vec3) -> Vec3 {
    [0, 1, 2].map(|i| {
        let column = [a[0][i], a[1][i], a[2][i]];
        dot(pool, &column, v)
    })
}

/// `a · b`.
pub fn dot(pool: &mut Pool, a: &Vec3, b: &Vec3) -> ExprId {
    let terms: Vec<ExprId> = (0..3).map(|i| pool.mul(a[i], b[i])).collect();
    pool.sum(terms)
}

/// `a × b`.
pub fn cross(pool: &mut Pool, a: &Vec3, b: &Vec3) -> Vec3 {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let first = pool.mul(a[j], b[k]);
        let second = pool.mul(a[k], b[j]);
        pool.sub(first, second)
    })
}

/// `a + b`.
pub fn add3(pool: &mut Pool, a: &Vec3, b: &Vec3) -> Vec3 {
    [0, 1, 2].map(|i| pool.add(a[i], b[i]))
}

#[cfg(test)]
mod tests;
