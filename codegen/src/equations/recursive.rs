//! The inertia and load terms of a kinematic tree ([`Tree`]), by recursion
//! over the tree instead of by dot products of partial velocities: the
//! composite-rigid-body recursion for `M` and the Newton–Euler recursion
//! for everything else that multiplies no `q̈`, on the same DAG.
//!
//! Both are d'Alembert's principle regrouped. For a revolute joint `k` with
//! unit axis `eₖ` through its origin `Jₖ`, the partial velocity of any point
//! `P` beyond it is `eₖ × (r_P − r_Jₖ)` and that of any frame beyond it is
//! `eₖ`; for a prismatic joint they are `eₖ` and `0`. So
//! `Σᵢ (mᵢ a_Gᵢ · ∂v_Gᵢ/∂q̇ₖ + Mᵢ · ∂ωᵢ/∂q̇ₖ)` minus the applied loads' share
//! is `eₖ` dotted with the moment about `Jₖ` (revolute) or the resultant
//! (prismatic) of the inertia forces minus the loads beyond joint `k`,
//! which a sweep from the leaves to the root accumulates in `O(n)`. A
//! spherical joint is three such turning speeds about its link's axes
//! (its angular velocity), a free joint three sliding speeds along them
//! first: each speed is a column of its link's motion subspace, and the
//! sweeps project on every column. Every
//! vector lives in the axes of its own link, so a planar chain meets only
//! 2×2 rotations and its zeros fold away at construction; a revolute joint
//! about a constant axis along none of its frame's axes (MuJoCo's slanted
//! shoulders) keeps its link's vectors in axes whose `z` is that axis
//! instead. A link's rotation from its parent is applied as its factors,
//! one after the other (a mount's fixed turn, then the joint's turn about
//! one axis): two sparse products where their product is a dense matrix
//! whose constants would spread over every sum it enters (for dm_control's
//! humanoid, `M` and `f` in 12 % fewer flops).
//!
//! Canonical sums would flatten each step's running totals into the next
//! and spread every coefficient over their terms, making a step cost as
//! much as all before it; so each step's results are [`Pool::group`]ed.

use super::Inertia;
use crate::expr::{ExprId, Number, Pool, Sym};
use crate::kinematics::{
    Kinematics, Mat3, Vec3, add3, axis_rotation, cross, dot, identity, is_fixed, mat_mul, mat_vec,
    transpose, transpose_mul,
};
use crate::model::{JointKind, Model, NEWTONIAN, Tree, Vector};

/// The tree with every vector in components: the rotations and offsets of
/// the links, the masses and the loads.
pub struct JointTree {
    /// The links, parents before children (as in [`Tree::links`]).
    pub(super) links: Vec<Link>,
    /// The bodies and particles, each fixed in one link.
    masses: Vec<Mass>,
    /// Applied forces and torques: per link, the resultant and its moment
    /// about the link's origin, in the link's axes.
    loads: Vec<(Vec3, Vec3)>,
    /// Gravity in `N`'s axes.
    pub(super) gravity: Vec3,
}

/// A link: the subtree beyond one joint.
pub(super) struct Link {
    /// The parent link, `None` for a joint on `N`.
    pub(super) parent: Option<usize>,
    pub(super) kind: JointKind,
    /// The joint's motion subspace: one column per speed.
    pub(super) columns: Vec<Column>,
    /// From the parent's origin to this link's, in the parent's axes (with
    /// the slide of a prismatic joint).
    pub(super) offset: Vec3,
    /// Maps the link's components to its parent's.
    pub(super) rotation: Mat3,
    /// `rotation` as a product of factors, the outermost first (see
    /// [`Kinematics::rotation_factors`]), which the sweeps apply one after
    /// the other where there are several (see [`Link::keep_sparse_factors`]);
    /// at most one where `rotation` is applied whole.
    factors: Vec<Mat3>,
}

/// One speed of a joint: a turn about, or a slide along, a unit axis.
pub(super) struct Column {
    /// Whether the speed turns the link about `axis` through its origin
    /// (else it slides it along `axis`).
    pub(super) turns: bool,
    /// The axis, in the link's axes.
    pub(super) axis: Vec3,
    /// The speed's index.
    pub(super) speed: usize,
}

/// A mass fixed in a link.
struct Mass {
    link: usize,
    mass: ExprId,
    /// From the link's origin to the centre, in the link's axes.
    center: Vec3,
    /// Central inertia in the link's axes (zero for a particle).
    inertia: Mat3,
}

/// The velocity-independent recursion state of one link, in its axes.
struct Motion {
    omega: Vec3,
    /// Angular acceleration at `q̈ = 0`.
    alpha: Vec3,
    /// Acceleration of the link's origin at `q̈ = 0`, gravity subtracted.
    accel: Vec3,
}

/// A subtree's mass, first moment and inertia about its link's origin.
#[derive(Clone, Copy)]
pub(super) struct Composite {
    pub(super) mass: ExprId,
    pub(super) moment: Vec3,
    pub(super) inertia: Mat3,
}

impl JointTree {
    /// The components of `tree`'s links, masses, loads and gravity; `None`
    /// if gravity turns with a moving frame.
    pub fn new(
        model: &Model,
        tree: &Tree,
        kinematics: &Kinematics,
        inertias: &[Inertia<'_>],
        pool: &mut Pool,
    ) -> Option<JointTree> {
        let frame_of = |link: Option<usize>| link.map_or(NEWTONIAN, |l| tree.links[l].frame);
        // Per link, the turn from the axes its vectors are kept in to its
        // frame's (`None`: the frame's own; see `axis_turn`).
        let mut turns: Vec<Option<Mat3>> = Vec::with_capacity(tree.links.len());
        let mut links: Vec<Link> = Vec::with_capacity(tree.links.len());
        for link in &tree.links {
            let parent_turn = link.parent.and_then(|p| turns[p]);
            let parent_frame = frame_of(link.parent);
            let mut offset = kinematics.express(pool, model, &link.offset, parent_frame);
            let mut own_turn = None;
            let (rotation, factors, columns) = match (link.kind, link.ball) {
                (JointKind::Revolute | JointKind::Prismatic, _) => {
                    let mut axis = kinematics.express(pool, model, &link.axis, link.frame);
                    let turns_link = link.kind == JointKind::Revolute;
                    let placement = model.frames[link.frame.0].placement.as_ref();
                    let about_axis = placement.filter(|p| {
                        turns_link
                            && p.ball.is_none()
                            && p.angle == pool.sym(Sym::Coord(link.coordinate as u32))
                    });
                    let turned = about_axis.and_then(|p| {
                        turned_about_axis(pool, model, kinematics, parent_frame, p, &axis)
                    });
                    let (rotation, factors) = if let Some((rotation, factors, q)) = turned {
                        own_turn = Some(q);
                        axis = crate::model::unit_axis(pool, 2);
                        (rotation, factors)
                    } else if turns_link {
                        let r = kinematics.relative_rotation(pool, model, parent_frame, link.frame);
                        let factors =
                            kinematics.rotation_factors(pool, model, parent_frame, link.frame);
                        (r, factors)
                    } else {
                        let q = pool.sym(Sym::Coord(link.coordinate as u32));
                        let slide = axis.map(|e| pool.mul(q, e));
                        offset = add3(pool, &offset, &slide);
                        (identity(pool), Vec::new())
                    };
                    let column = Column {
                        turns: turns_link,
                        axis,
                        speed: speed_of(pool, link.coordinate)?,
                    };
                    (rotation, factors, vec![column])
                }
                (_, ball) => {
                    let ball = &model.balls[ball?];
                    let rotation =
                        kinematics.relative_rotation(pool, model, parent_frame, link.frame);
                    let factors =
                        kinematics.rotation_factors(pool, model, parent_frame, link.frame);
                    let slides = ball.translation.iter().flat_map(|(_, v)| *v);
                    let columns = slides
                        .map(|k| (false, k))
                        .chain(ball.angular.map(|k| (true, k)))
                        .enumerate()
                        .map(|(i, (turns, speed))| Column {
                            turns,
                            axis: crate::model::unit_axis(pool, i % 3),
                            speed,
                        })
                        .collect();
                    (rotation, factors, columns)
                }
            };
            let mut link = Link {
                parent: link.parent,
                kind: link.kind,
                columns,
                offset,
                rotation,
                factors,
            };
            // A slide keeps its parent's axes.
            if link.kind == JointKind::Prismatic {
                own_turn = parent_turn;
            }
            if let Some(q) = &parent_turn {
                link.with_parent_axes(pool, q);
            }
            link.keep_sparse_factors(pool, own_turn.is_some() || parent_turn.is_some());
            if let (JointKind::Prismatic, Some(q)) = (link.kind, &own_turn) {
                for column in &mut link.columns {
                    column.axis = transpose_mul(pool, q, &column.axis);
                }
            }
            turns.push(own_turn);
            links.push(link);
        }
        let mut masses = Vec::new();
        let attachments = tree
            .bodies
            .iter()
            .chain(model.particles.iter().map(|p| &tree.points[p.at.0]));
        for (inertia, at) in inertias.iter().zip(attachments) {
            let Some(link) = at.link else { continue };
            let frame = tree.links[link].frame;
            let center = kinematics.express(pool, model, &at.offset, frame);
            let tensor = match inertia.rotation {
                Some((body_frame, tensor)) => {
                    let r = kinematics.relative_rotation(pool, model, frame, body_frame);
                    rotate_tensor(pool, &r, tensor)
                }
                None => [[pool.zero(); 3]; 3],
            };
            let (center, tensor) = match &turns[link] {
                Some(q) => {
                    let back = transpose(q);
                    (
                        transpose_mul(pool, q, &center),
                        rotate_tensor(pool, &back, &tensor),
                    )
                }
                None => (center, tensor),
            };
            masses.push(Mass {
                link,
                mass: inertia.mass,
                center,
                inertia: tensor,
            });
        }
        let zero = pool.zero();
        let mut loads = vec![([zero; 3], [zero; 3]); links.len()];
        for force in &model.forces {
            let at = &tree.points[force.at.0];
            let Some(link) = at.link else { continue };
            let frame = tree.links[link].frame;
            let f = kinematics.express(pool, model, &force.vector, frame);
            let c = kinematics.express(pool, model, &at.offset, frame);
            let moment = cross(pool, &c, &f);
            let (total, about) = loads[link];
            loads[link] = (add3(pool, &total, &f), add3(pool, &about, &moment));
        }
        for torque in &model.torques {
            let reaction = torque.reacting.map(|g| (g, torque.vector.neg(pool)));
            for (frame, vector) in
                std::iter::once((torque.on, torque.vector.clone())).chain(reaction)
            {
                let Some(link) = tree.frames[frame.0] else {
                    continue;
                };
                let tau = kinematics.express(pool, model, &vector, tree.links[link].frame);
                loads[link].1 = add3(pool, &loads[link].1, &tau);
            }
        }
        for (load, turn) in loads.iter_mut().zip(&turns) {
            if let Some(q) = turn {
                *load = (
                    transpose_mul(pool, q, &load.0),
                    transpose_mul(pool, q, &load.1),
                );
            }
        }
        let gravity = match &model.gravity {
            None => [zero; 3],
            Some(g) => constant_in_newtonian(model, kinematics, pool, g)?,
        };
        Some(JointTree {
            links,
            masses,
            loads,
            gravity,
        })
    }
}

/// The axes a revolute link's vectors are kept in when its axis `e` is a
/// constant along none of its frame's axes: the turn `Q` (its columns the
/// new axes, in the frame's) with `Q z = e`, its `x` a coordinate axis
/// square to `e` where there is one (then `Q` turns about that axis), so
/// that the joint's turn `Rot(e, q) = Q R_z(q) Qᵀ` is one about `z` there
/// and a fixed one; `None` for any other axis.
fn axis_turn(pool: &mut Pool, axis: &Vec3) -> Option<Mat3> {
    if crate::model::principal_axis(pool, axis).is_some() {
        return None;
    }
    let values: Vec<f64> = axis
        .iter()
        .map(|&c| pool.as_number(c).map(|n| n.to_f64()))
        .collect::<Option<_>>()?;
    let x = match axis.iter().position(|&c| pool.is_zero(c)) {
        Some(k) => crate::model::unit_axis(pool, k),
        None => {
            // Along e × y, normalised.
            let norm = values[0].hypot(values[2]);
            let [x, z] =
                [-values[2] / norm, values[0] / norm].map(|v| pool.number(Number::Float(v)));
            [x, pool.zero(), z]
        }
    };
    let y = cross(pool, axis, &x);
    Some([0, 1, 2].map(|i| [x[i], y[i], axis[i]]))
}

/// A revolute link turning by its coordinate (`placement`) about an axis
/// that [`axis_turn`] gives new axes `Q`: its rotation from `parent_frame`
/// and that rotation's factors in them, `R₀ Rot(e, q) Q = (R₀ Q) R_z(q)`
/// (a fixed turn and one about `z`), and `Q`.
fn turned_about_axis(
    pool: &mut Pool,
    model: &Model,
    kinematics: &Kinematics,
    parent_frame: crate::model::FrameId,
    placement: &crate::model::FramePlacement,
    axis: &Vec3,
) -> Option<(Mat3, Vec<Mat3>, Mat3)> {
    let q = axis_turn(pool, axis)?;
    let fixed = kinematics.relative_rotation(pool, model, parent_frame, placement.parent);
    let fixed = mat_mul(pool, &fixed, &q);
    let z = crate::model::unit_axis(pool, 2);
    let own = axis_rotation(pool, &z, placement.angle);
    let rotation = mat_mul(pool, &fixed, &own);
    let factors = match fixed == identity(pool) {
        true => vec![own],
        false => vec![fixed, own],
    };
    Some((rotation, factors, q))
}

/// The speed whose rate a one-speed joint's coordinate is, if it is one.
fn speed_of(pool: &mut Pool, coordinate: usize) -> Option<usize> {
    if pool.rates_are_speeds() {
        return Some(coordinate);
    }
    let rate = pool.rate(coordinate as u32);
    match *pool.node(rate) {
        crate::expr::Node::Sym(Sym::Speed(k)) => Some(k as usize),
        _ => None,
    }
}

/// The components of `v` in `N`'s axes, if they are constant.
fn constant_in_newtonian(
    model: &Model,
    kinematics: &Kinematics,
    pool: &mut Pool,
    v: &Vector,
) -> Option<Vec3> {
    let g = kinematics.express(pool, model, v, NEWTONIAN);
    g.iter()
        .all(|&x| crate::expr::SymKinds::PARAM.contains(pool.kinds(x)))
        .then_some(g)
}

/// `M` and, per coordinate, the terms that multiply no `q̈`:
/// `Σᵢ (mᵢ (a_bias − g) · vₖ + (I α_bias + ω × Iω) · ωₖ)` minus the
/// generalized forces of the applied forces and torques.
pub fn inertia_terms(tree: &JointTree, pool: &mut Pool) -> (Vec<Vec<ExprId>>, Vec<ExprId>) {
    let mass_matrix = tree.mass_matrix(pool);
    let motions = tree.motions(pool, false);
    let bias = tree.projected_wrenches(pool, &motions);
    (mass_matrix, bias)
}

/// `M q̈` plus the terms of [`inertia_terms`]' bias: the same Newton–Euler
/// sweeps with the joints' accelerations `q̈` carried outwards.
pub fn inverse_dynamics(tree: &JointTree, pool: &mut Pool) -> Vec<ExprId> {
    let motions = tree.motions(pool, true);
    tree.projected_wrenches(pool, &motions)
}

impl JointTree {
    /// `M` by composite rigid bodies: the subtree beyond joint `j` moving
    /// at unit rate has momentum `(eⱼ × hⱼ, Kⱼ eⱼ)` about its origin
    /// (revolute) or `(mⱼ eⱼ, hⱼ × eⱼ)` (prismatic); `Mₖⱼ` is its angular
    /// momentum about the origin of every ancestor `k` along `eₖ`
    /// (revolute), or its momentum along `eₖ` (prismatic).
    fn mass_matrix(&self, pool: &mut Pool) -> Vec<Vec<ExprId>> {
        let nv = self.links.iter().map(|l| l.columns.len()).sum();
        let composites = self.composites(pool);
        let mut m = vec![vec![pool.zero(); nv]; nv];
        for (j, link) in self.links.iter().enumerate() {
            let c = &composites[j];
            for (i, own) in link.columns.iter().enumerate() {
                let (mut linear, mut angular) = c.momentum(pool, own);
                let column = own.speed;
                for other in &link.columns[..=i] {
                    m[other.speed][column] = other.project(pool, &linear, &angular);
                    m[column][other.speed] = m[other.speed][column];
                }
                let mut l = j;
                while let Some(p) = self.links[l].parent {
                    linear = self.links[l].to_parent(pool, &linear);
                    let rotated = self.links[l].to_parent(pool, &angular);
                    let shift = cross(pool, &self.links[l].offset, &linear);
                    linear = group3(pool, &linear);
                    let sum = add3(pool, &rotated, &shift);
                    angular = group3(pool, &sum);
                    for other in &self.links[p].columns {
                        m[other.speed][column] = other.project(pool, &linear, &angular);
                        m[column][other.speed] = m[other.speed][column];
                    }
                    l = p;
                }
            }
        }
        m
    }

    /// Mass, first moment and inertia about its link's origin, in its
    /// link's axes, of the masses fixed in each link.
    pub(super) fn link_inertias(&self, pool: &mut Pool) -> Vec<Composite> {
        let zero = pool.zero();
        let mut inertias = vec![
            Composite {
                mass: zero,
                moment: [zero; 3],
                inertia: [[zero; 3]; 3],
            };
            self.links.len()
        ];
        for mass in &self.masses {
            let own = Composite {
                mass: mass.mass,
                moment: mass.center.map(|c| pool.mul(mass.mass, c)),
                inertia: mass.inertia,
            };
            let own = shifted(pool, &own, &mass.center, &own.moment);
            inertias[mass.link] = combined(pool, &inertias[mass.link], &own);
        }
        inertias
    }

    /// Mass, first moment and inertia of every subtree about its link's
    /// origin, in its link's axes, leaves first.
    pub(super) fn composites(&self, pool: &mut Pool) -> Vec<Composite> {
        let mut composites = self.link_inertias(pool);
        for l in (0..self.links.len()).rev() {
            let Some(p) = self.links[l].parent else {
                continue;
            };
            let link = &self.links[l];
            let c = grouped(pool, &composites[l]);
            let rotated = Composite {
                mass: c.mass,
                moment: link.to_parent(pool, &c.moment),
                inertia: link.tensor_to_parent(pool, &c.inertia),
            };
            let moved_moment = [0, 1, 2].map(|i| {
                let shift = pool.mul(c.mass, link.offset[i]);
                pool.add(rotated.moment[i], shift)
            });
            let moved = shifted(pool, &rotated, &link.offset, &moved_moment);
            composites[p] = combined(pool, &composites[p], &moved);
        }
        composites
    }

    /// The Newton–Euler sweep inwards: given the `motions` of the links,
    /// the resultant and moment about each link's origin of the inertia
    /// forces minus the applied loads beyond it (gravity as an upward
    /// acceleration of the base), projected on the joint.
    fn projected_wrenches(&self, pool: &mut Pool, motions: &[Motion]) -> Vec<ExprId> {
        let (mut force, mut moment) = self.reversed_loads(pool);
        for mass in &self.masses {
            let (f, n) = inertia_wrench(pool, mass, &motions[mass.link]);
            force[mass.link] = add3(pool, &force[mass.link], &f);
            moment[mass.link] = add3(pool, &moment[mass.link], &n);
        }
        self.projected(pool, force, moment)
    }

    /// The applied loads' share of the inverse dynamics: minus their
    /// generalized forces, by the inward sweep without the masses.
    pub(super) fn applied_loads(&self, pool: &mut Pool) -> Vec<ExprId> {
        let (force, moment) = self.reversed_loads(pool);
        self.projected(pool, force, moment)
    }

    /// Per link, minus the resultant of its applied loads and minus their
    /// moment about its origin.
    fn reversed_loads(&self, pool: &mut Pool) -> (Vec<Vec3>, Vec<Vec3>) {
        self.loads
            .iter()
            .map(|(f, n)| (f.map(|x| pool.neg(x)), n.map(|x| pool.neg(x))))
            .unzip()
    }

    /// The sweep inwards of the wrenches `force`, `moment` (per link, about
    /// its origin, in its axes), each subtree's total projected on its
    /// joint.
    fn projected(
        &self,
        pool: &mut Pool,
        mut force: Vec<Vec3>,
        mut moment: Vec<Vec3>,
    ) -> Vec<ExprId> {
        let nv = self.links.iter().map(|l| l.columns.len()).sum();
        let mut bias = vec![pool.zero(); nv];
        for l in (0..self.links.len()).rev() {
            let link = &self.links[l];
            let f = group3(pool, &force[l]);
            let n = group3(pool, &moment[l]);
            for column in &link.columns {
                bias[column.speed] = column.project(pool, &f, &n);
            }
            let Some(p) = link.parent else {
                continue;
            };
            let f = link.to_parent(pool, &f);
            let n = link.to_parent(pool, &n);
            let lever = cross(pool, &link.offset, &f);
            force[p] = add3(pool, &force[p], &f);
            let n = add3(pool, &n, &lever);
            moment[p] = add3(pool, &moment[p], &n);
        }
        bias
    }

    /// `ω`, `α` and the origin's acceleration of every link, each in its
    /// link's axes, at `q̈ = 0` or (`accelerations`) at the symbols `q̈`;
    /// the base accelerates at `−g`.
    fn motions(&self, pool: &mut Pool, accelerations: bool) -> Vec<Motion> {
        let zero = pool.zero();
        let base = Motion {
            omega: [zero; 3],
            alpha: [zero; 3],
            accel: self.gravity.map(|g| pool.neg(g)),
        };
        let mut motions: Vec<Motion> = Vec::with_capacity(self.links.len());
        for link in &self.links {
            let parent = link.parent.map_or(&base, |p| &motions[p]);
            let d = &link.offset;
            // The joint's own rates Σ vₖ eₖ over its turning and its sliding
            // speeds, in the link's axes, and (`accelerations`) the same sums
            // of the symbols v̇ₖ.
            let [spin, slide] = [true, false].map(|turns| link.rates(pool, turns, Sym::Speed));
            let [spin_rate, slide_rate] = match accelerations {
                true => [true, false].map(|turns| link.rates(pool, turns, Sym::Accel)),
                false => [[zero; 3]; 2],
            };
            // a_J = a_p + α_p × d + ω_p × (ω_p × d) (+ 2 ω_p × ḋ for a slide),
            // then into the link's axes.
            let mut accel = parent.point_acceleration(pool, d);
            let carried = link.to_link(pool, &parent.omega);
            let alpha = link.to_link(pool, &parent.alpha);
            let (omega, alpha) = match link.kind {
                JointKind::Revolute | JointKind::Spherical => {
                    // ω = Rᵀ ω_p + Σ vₖ eₖ;  α = Rᵀ α_p + Σ v̇ₖ eₖ + (Rᵀ ω_p) × Σ vₖ eₖ.
                    let coriolis = cross(pool, &carried, &spin);
                    let alpha = add3(pool, &alpha, &spin_rate);
                    (add3(pool, &carried, &spin), add3(pool, &alpha, &coriolis))
                }
                JointKind::Prismatic => {
                    let coriolis = cross(pool, &parent.omega, &slide);
                    let twice = coriolis.map(|x| pool.add(x, x));
                    accel = add3(pool, &accel, &twice);
                    accel = add3(pool, &accel, &slide_rate);
                    (carried, alpha)
                }
                JointKind::Free => {
                    // On the ground: ω = Σ wₖ eₖ and α = Σ ẇₖ eₖ; the
                    // origin's velocity v (in the link's axes) turns with
                    // it, adding ω × v to its rate v̇.
                    let turning = link.to_link(pool, &accel);
                    let transport = cross(pool, &spin, &slide);
                    let accel = add3(pool, &turning, &transport);
                    let accel = add3(pool, &accel, &slide_rate);
                    let alpha = add3(pool, &alpha, &spin_rate);
                    motions.push(Motion {
                        omega: group3(pool, &spin),
                        alpha: group3(pool, &alpha),
                        accel: group3(pool, &accel),
                    });
                    continue;
                }
            };
            let accel = link.to_link(pool, &accel);
            motions.push(Motion {
                omega: group3(pool, &omega),
                alpha: group3(pool, &alpha),
                accel: group3(pool, &accel),
            });
        }
        motions
    }
}

impl Motion {
    /// The acceleration `a + α × d + ω × (ω × d)` of the point `d` from the
    /// link's origin (in its axes), written `a + A d` with the link's matrix
    /// `A = [α]× + ω ωᵀ − |ω|² 1`, each entry one operand: the points of a
    /// link (its masses' centres and its children's joints) share `A`'s
    /// columns, and a point on an axis of the link (a chain's next joint,
    /// a rod's centre) costs a product per component.
    fn point_acceleration(&self, pool: &mut Pool, d: &Vec3) -> Vec3 {
        let relative = self.transport(pool, d);
        add3(pool, &self.accel, &relative)
    }

    /// `A d`, with `A = [α]× + ω ωᵀ − |ω|² 1` the matrix that takes a
    /// point's offset from the link's origin to its acceleration relative
    /// to the origin's: the sum of `A`'s columns weighted by `d`'s nonzero
    /// components.
    fn transport(&self, pool: &mut Pool, d: &Vec3) -> Vec3 {
        let mut sum = [pool.zero(); 3];
        for (k, &dk) in d.iter().enumerate() {
            if pool.is_zero(dk) {
                continue;
            }
            let column = self.transport_column(pool, k);
            let part = column.map(|x| pool.mul(dk, x));
            sum = add3(pool, &sum, &part);
        }
        sum
    }

    /// Column `k` of `A = [α]× + ω ωᵀ − |ω|² 1`: the acceleration relative
    /// to the origin of the point at unit distance along axis `k`, each
    /// entry grouped.
    fn transport_column(&self, pool: &mut Pool, k: usize) -> Vec3 {
        let w = &self.omega;
        let axis = crate::model::unit_axis(pool, k);
        let tangential = cross(pool, &self.alpha, &axis);
        let column = [0, 1, 2].map(|i| {
            let centripetal = match i == k {
                true => {
                    let squares: Vec<ExprId> = (0..3)
                        .filter(|&j| j != k)
                        .map(|j| pool.mul(w[j], w[j]))
                        .collect();
                    let sum = pool.sum(squares);
                    pool.neg(sum)
                }
                false => pool.mul(w[i], w[k]),
            };
            pool.add(tangential[i], centripetal)
        });
        group3(pool, &column)
    }
}

impl Link {
    /// Keeps the rotation's factors where applying them one after the
    /// other costs less than their product. Between axes chosen for
    /// slanted joints (`turned`: the link's or its parent's, see
    /// [`axis_turn`]) always: the fixed factor holds the turn between
    /// those axes (dm_control's humanoid: 6 465 flops for `M` and `f`
    /// against 6 698 with the product). Elsewhere where each factor turns
    /// about one axis and their product does not (a mount's fixed turn
    /// about one axis, the joint's about another: 6 operations a vector
    /// each, where the product's single-term entries cost 17); a product
    /// that turns about one axis (a fixed turn about the joint's own axis,
    /// as the UR5's) or a dense fixed factor (the G1's: 9 826 flops
    /// against 9 949 factored) is applied whole.
    fn keep_sparse_factors(&mut self, pool: &Pool, turned: bool) {
        let one_axis = |f: &Mat3| turning_axis(pool, f).is_some();
        let sparse = self.factors.len() > 1
            && (turned || (!one_axis(&self.rotation) && self.factors.iter().all(one_axis)));
        if !sparse {
            self.factors.clear();
        }
    }

    /// The link with its parent's vectors kept in the axes `q` (its
    /// columns, in the parent frame's): offset `qᵀ d`, rotation `qᵀ R`
    /// (`qᵀ` joins the rotation's fixed first factor, or comes first). A
    /// slide keeps its parent's axes, and its rotation the identity.
    fn with_parent_axes(&mut self, pool: &mut Pool, q: &Mat3) {
        self.offset = transpose_mul(pool, q, &self.offset);
        if self.kind == JointKind::Prismatic {
            return;
        }
        let back = transpose(q);
        self.rotation = mat_mul(pool, &back, &self.rotation);
        match self.factors.first_mut() {
            Some(first) if is_fixed(pool, first) => *first = mat_mul(pool, &back, first),
            _ => self.factors.insert(0, back),
        }
    }

    /// `R v`: components in the link's axes, in its parent's. Where the
    /// rotation has several factors, they are applied innermost first,
    /// each intermediate result grouped.
    pub(super) fn to_parent(&self, pool: &mut Pool, v: &Vec3) -> Vec3 {
        match self.factors.as_slice() {
            [_, inner @ ..] if !inner.is_empty() => {
                let turned = inner.iter().rev().fold(*v, |v, f| {
                    let w = mat_vec(pool, f, &v);
                    group3(pool, &w)
                });
                mat_vec(pool, &self.factors[0], &turned)
            }
            _ => mat_vec(pool, &self.rotation, v),
        }
    }

    /// `Rᵀ v`: components in the parent's axes, in the link's, factor by
    /// factor as [`Link::to_parent`].
    pub(super) fn to_link(&self, pool: &mut Pool, v: &Vec3) -> Vec3 {
        match self.factors.as_slice() {
            [outer @ .., last] if !outer.is_empty() => {
                let turned = outer.iter().fold(*v, |v, f| {
                    let w = transpose_mul(pool, f, &v);
                    group3(pool, &w)
                });
                transpose_mul(pool, last, &turned)
            }
            _ => transpose_mul(pool, &self.rotation, v),
        }
    }

    /// `R K Rᵀ` for a symmetric `K` in the link's axes, factor by factor as
    /// [`Link::to_parent`].
    pub(super) fn tensor_to_parent(&self, pool: &mut Pool, k: &Mat3) -> Mat3 {
        self.turned_by_factors(pool, k, rotate_symmetric)
    }

    /// `R K Rᵀ` for any `K` (not symmetric), factor by factor as
    /// [`Link::to_parent`].
    pub(super) fn general_tensor_to_parent(&self, pool: &mut Pool, k: &Mat3) -> Mat3 {
        self.turned_by_factors(pool, k, rotate_tensor)
    }

    /// `R K Rᵀ` by `rotate` (`(R, K) ↦ R K Rᵀ`), applied factor by factor,
    /// innermost first, each intermediate result grouped.
    fn turned_by_factors(
        &self,
        pool: &mut Pool,
        k: &Mat3,
        rotate: fn(&mut Pool, &Mat3, &Mat3) -> Mat3,
    ) -> Mat3 {
        match self.factors.as_slice() {
            [_, inner @ ..] if !inner.is_empty() => {
                let turned = inner.iter().rev().fold(*k, |k, f| {
                    let t = rotate(pool, f, &k);
                    t.map(|row| group3(pool, &row))
                });
                rotate(pool, &self.factors[0], &turned)
            }
            _ => rotate(pool, &self.rotation, k),
        }
    }

    /// `Σ symbol(k) eₖ` over the columns that turn (`turns`) or slide, in
    /// the link's axes.
    fn rates(&self, pool: &mut Pool, turns: bool, symbol: fn(u32) -> Sym) -> Vec3 {
        let parts: Vec<Vec3> = self
            .columns
            .iter()
            .filter(|c| c.turns == turns)
            .map(|c| {
                let v = pool.sym(symbol(c.speed as u32));
                c.axis.map(|e| pool.mul(v, e))
            })
            .collect();
        match parts.as_slice() {
            [one] => *one,
            _ => parts
                .iter()
                .fold([pool.zero(); 3], |a, b| add3(pool, &a, b)),
        }
    }
}

impl Composite {
    /// The momentum (resultant, moment about the link's origin, each entry
    /// grouped) of the subtree moving at unit rate of `column`, a speed of
    /// its link: `(e × h, K e)` for a turn about `e`, `(m e, h × e)` for a
    /// slide along it.
    pub(super) fn momentum(&self, pool: &mut Pool, column: &Column) -> (Vec3, Vec3) {
        let e = &column.axis;
        let (linear, angular) = match column.turns {
            true => (
                cross(pool, e, &self.moment),
                mat_vec(pool, &self.inertia, e),
            ),
            false => (
                e.map(|x| pool.mul(self.mass, x)),
                cross(pool, &self.moment, e),
            ),
        };
        (group3(pool, &linear), group3(pool, &angular))
    }
}

impl Column {
    /// The speed's share of a wrench (resultant, moment about the link's
    /// origin): the moment along the axis (a turn) or the resultant along
    /// it (a slide).
    fn project(&self, pool: &mut Pool, resultant: &Vec3, moment: &Vec3) -> ExprId {
        match self.turns {
            true => dot(pool, &self.axis, moment),
            false => dot(pool, &self.axis, resultant),
        }
    }
}

/// The inertia force of a mass and its moment about the link's origin,
/// `∫ a dm` and `∫ r × a dm` with `a = a_O + A r` (see
/// [`Motion::transport`]): through its second moment `J = ∫ r rᵀ dm`
/// about the origin when that is one entry (a rod along an axis of its
/// link, a particle on one), else through its central inertia, which
/// folds its symmetries (the second moment measured slower on the UR5,
/// BENCHMARKS.md).
fn inertia_wrench(pool: &mut Pool, mass: &Mass, motion: &Motion) -> (Vec3, Vec3) {
    let h = mass.center.map(|x| pool.mul(mass.mass, x));
    let j = second_moment(pool, mass, &h);
    match j.iter().flatten().filter(|&&x| !pool.is_zero(x)).count() <= 1 {
        true => rod_wrench(pool, mass, motion, &h, &j),
        false => body_wrench(pool, mass, motion),
    }
}

/// `m a_O + A h` and `h × a_O + N` with `h = m c` and
/// `N_i = ε_ijk (A J)_kj`: for a one-entry `J`, two products of a column
/// of `A` that the link's points use already.
fn rod_wrench(pool: &mut Pool, mass: &Mass, motion: &Motion, h: &Vec3, j: &Mat3) -> (Vec3, Vec3) {
    let carried = motion.accel.map(|a| pool.mul(mass.mass, a));
    let transported = motion.transport(pool, h);
    let force = add3(pool, &carried, &transported);
    let a_j = [0, 1, 2].map(|column| motion.transport(pool, &j[column]));
    let spin = [0, 1, 2].map(|i| {
        let (k, l) = ((i + 1) % 3, (i + 2) % 3);
        pool.sub(a_j[k][l], a_j[l][k])
    });
    let lever = cross(pool, h, &motion.accel);
    (force, add3(pool, &lever, &spin))
}

/// `m a_G` and `I α + ω × I ω + c × m a_G`, from the central inertia `I`.
fn body_wrench(pool: &mut Pool, mass: &Mass, motion: &Motion) -> (Vec3, Vec3) {
    let c = &mass.center;
    let a = motion.point_acceleration(pool, c);
    let a = group3(pool, &a);
    let force = a.map(|x| pool.mul(mass.mass, x));
    let i_alpha = mat_vec(pool, &mass.inertia, &motion.alpha);
    let momentum = mat_vec(pool, &mass.inertia, &motion.omega);
    let gyroscopic = cross(pool, &motion.omega, &momentum);
    let lever = cross(pool, c, &force);
    let moment = add3(pool, &i_alpha, &gyroscopic);
    (force, add3(pool, &moment, &lever))
}

/// The second moment `J = ∫ r rᵀ dm` of a mass about its link's origin,
/// from its central inertia `I`: `J = ½ tr(I) 1 − I + c hᵀ` (symmetric,
/// so its rows are its columns).
fn second_moment(pool: &mut Pool, mass: &Mass, h: &Vec3) -> Mat3 {
    let k = &mass.inertia;
    let trace = pool.sum([k[0][0], k[1][1], k[2][2]]);
    let half = pool.rational(1, 2);
    let half_trace = pool.mul(half, trace);
    [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let minus = pool.neg(k[i][j]);
            let outer = pool.mul(mass.center[i], h[j]);
            let central = match i == j {
                true => pool.add(half_trace, minus),
                false => minus,
            };
            pool.add(central, outer)
        })
    })
}

/// Each component as one operand ([`Pool::group`]).
pub(super) fn group3(pool: &mut Pool, v: &Vec3) -> Vec3 {
    v.map(|x| pool.group(x))
}

/// A composite with every entry grouped.
pub(super) fn grouped(pool: &mut Pool, c: &Composite) -> Composite {
    Composite {
        mass: c.mass,
        moment: group3(pool, &c.moment),
        inertia: c.inertia.map(|row| group3(pool, &row)),
    }
}

/// `a + b`, entry by entry.
fn combined(pool: &mut Pool, a: &Composite, b: &Composite) -> Composite {
    Composite {
        mass: pool.add(a.mass, b.mass),
        moment: add3(pool, &a.moment, &b.moment),
        inertia: [0, 1, 2].map(|i| [0, 1, 2].map(|j| pool.add(a.inertia[i][j], b.inertia[i][j]))),
    }
}

/// `c` (inertia about a point `A`, first moment `h` about `A`) moved to the
/// point `B = A − d`, where its first moment is `moved = h + m d`:
/// `K_B = K_A + m(|d|² 1 − d dᵀ) + 2(h·d) 1 − h dᵀ − d hᵀ`, with `h` the
/// moment about `A`. For a single mass about its centre, `h = 0` and `moved
/// = m d`: pass the centre as `d` and `m c` as `moved` (the parallel-axis
/// theorem).
pub(super) fn shifted(pool: &mut Pool, c: &Composite, d: &Vec3, moved: &Vec3) -> Composite {
    // With h = moved − m d: K_B = K_A + (2 moved·d − m|d|²) 1 − moved dᵀ − d movedᵀ + m d dᵀ.
    let two = pool.int(2);
    let md = d.map(|x| pool.mul(c.mass, x));
    let moved_dot_d = dot(pool, moved, d);
    let twice = pool.mul(two, moved_dot_d);
    let m_dd = dot(pool, &md, d);
    let diagonal = pool.sub(twice, m_dd);
    let inertia = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let outer = [
                pool.mul(moved[i], d[j]),
                pool.mul(d[i], moved[j]),
                pool.mul(md[i], d[j]),
            ];
            let minus = [pool.neg(outer[0]), pool.neg(outer[1]), outer[2]];
            let mut terms = vec![c.inertia[i][j]];
            terms.extend(minus);
            if i == j {
                terms.push(diagonal);
            }
            pool.sum(terms)
        })
    });
    Composite {
        mass: c.mass,
        moment: *moved,
        inertia,
    }
}

/// `R K Rᵀ` for a symmetric `K` (an inertia tensor). When `R` turns about
/// one of the axes `a`, as a revolute joint about `x`, `y` or `z` does, the
/// entry `K_aa` is unchanged, `(K_ia, K_ja)` turns as a vector by the 2×2
/// block `P` of `R` in the other two axes `i`, `j`, and the block of `K` in
/// that plane becomes `P K Pᵀ`, of which only the entries `ii` and `ij`
/// are multiplied out and `jj` follows from the trace, which a turn keeps:
/// 20 operations where the general `R K Rᵀ` takes 36 (6 if the block is a
/// multiple of the identity, as a body's symmetric about the axis is).
pub(super) fn rotate_symmetric(pool: &mut Pool, r: &Mat3, k: &Mat3) -> Mat3 {
    let Some(a) = turning_axis(pool, r) else {
        return rotate_tensor(pool, r, k);
    };
    let (i, j) = ((a + 1) % 3, (a + 2) % 3);
    // Row `row` of `P` times `(x, y)`, as one operand.
    let turned = |pool: &mut Pool, row: usize, x: ExprId, y: ExprId| {
        let xs = pool.mul(r[row][i], x);
        let ys = pool.mul(r[row][j], y);
        let sum = pool.add(xs, ys);
        pool.group(sum)
    };
    let mut out = [[k[a][a]; 3]; 3];
    for row in [i, j] {
        out[row][a] = turned(pool, row, k[i][a], k[j][a]);
        out[a][row] = out[row][a];
    }
    if k[i][i] == k[j][j] && pool.is_zero(k[i][j]) {
        // A multiple of the identity in the plane: turned, the same.
        for (row, column) in [(i, i), (i, j), (j, i), (j, j)] {
            out[row][column] = k[row][column];
        }
        return out;
    }
    // Row `i` of `P K` times the rows `i` and `j` of `P`.
    let u = turned(pool, i, k[i][i], k[j][i]);
    let v = turned(pool, i, k[i][j], k[j][j]);
    for column in [i, j] {
        out[i][column] = turned(pool, column, u, v);
        out[column][i] = out[i][column];
    }
    // A turn keeps the trace.
    let trace = pool.add(k[i][i], k[j][j]);
    out[j][j] = pool.sub(trace, out[i][i]);
    out
}

/// The axis `a` about which `R` turns, if its row and column `a` are those
/// of the identity.
fn turning_axis(pool: &Pool, r: &Mat3) -> Option<usize> {
    (0..3).find(|&a| {
        r[a][a] == pool.one()
            && (0..3)
                .filter(|&b| b != a)
                .all(|b| pool.is_zero(r[a][b]) && pool.is_zero(r[b][a]))
    })
}

/// `R K Rᵀ`: a tensor given in a child's axes, in the parent's.
pub(super) fn rotate_tensor(pool: &mut Pool, r: &Mat3, k: &Mat3) -> Mat3 {
    // Columns of R K, then the rows of (R K) Rᵀ as R times the rows of R K.
    let columns: [Vec3; 3] = [0, 1, 2].map(|j| mat_vec(pool, r, &[k[0][j], k[1][j], k[2][j]]));
    [0, 1, 2].map(|i| mat_vec(pool, r, &[columns[0][i], columns[1][i], columns[2][i]]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Env;

    /// The angle `q0`.
    struct Angle(f64);
    impl Env for Angle {
        fn value(&self, _: Sym) -> f64 {
            self.0
        }
    }

    /// A turn about each coordinate axis of an inertia tensor with every
    /// entry nonzero, and of one symmetric about `z` (its block in `x, y`
    /// a multiple of the identity), against `R K Rᵀ` multiplied out in
    /// `f64`.
    #[test]
    fn symmetric_rotation_about_an_axis_is_r_k_rt() {
        let tensors: [[[i128; 3]; 3]; 2] = [
            [[30, 2, -4], [2, 20, 3], [-4, 3, 15]],
            [[20, 0, -4], [0, 20, 3], [-4, 3, 15]],
        ];
        let angle = 0.7_f64;
        let (s, c) = angle.sin_cos();
        for (tenths, axis) in tensors.iter().flat_map(|t| (0..3).map(move |a| (t, a))) {
            let k = tenths.map(|row| row.map(|x| x as f64 / 10.0));
            let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
            let mut numeric = [[0.0; 3]; 3];
            numeric[axis][axis] = 1.0;
            (numeric[i][i], numeric[i][j], numeric[j][i], numeric[j][j]) = (c, -s, s, c);
            let expected: [[f64; 3]; 3] = std::array::from_fn(|a| {
                std::array::from_fn(|b| {
                    (0..3)
                        .flat_map(|x| (0..3).map(move |y| (x, y)))
                        .map(|(x, y)| numeric[a][x] * k[x][y] * numeric[b][y])
                        .sum()
                })
            });

            let mut pool = Pool::new();
            let q = pool.sym(Sym::Coord(0));
            let (sin, cos) = (pool.sin(q), pool.cos(q));
            let minus_sin = pool.neg(sin);
            let mut r = identity(&pool);
            (r[i][i], r[i][j], r[j][i], r[j][j]) = (cos, minus_sin, sin, cos);
            let tensor = tenths.map(|row| row.map(|x| pool.rational(x, 10)));
            let rotated = rotate_symmetric(&mut pool, &r, &tensor);
            for (a, b) in (0..3).flat_map(|a| (0..3).map(move |b| (a, b))) {
                let value = pool.eval(rotated[a][b], &Angle(angle));
                assert!(
                    (value - expected[a][b]).abs() < 1e-14,
                    "axis {axis}, entry ({a}, {b}): {value} against {}",
                    expected[a][b]
                );
            }
        }
    }
}
