//! d'Alembert's principle assembled into the equations of motion:
//!
//! ```text
//! Σᵢ mᵢ a_Gᵢ · ∂v_Gᵢ/∂vₖ + Σᵢ (I_Gᵢ·αᵢ + ωᵢ × I_Gᵢ·ωᵢ) · ∂ωᵢ/∂vₖ = Fₖ (+ Σⱼ λⱼ aⱼₖ)
//! ```
//!
//! for every speed `vₖ` (the rate `q̇ₖ` of a coordinate unless a joint or
//! statement defines it otherwise: Kane's form). With
//! `a = Σⱼ (∂v/∂vⱼ) v̇ⱼ + a_bias` (and likewise `α`), the `v̇` terms give
//! the mass matrix `M` — symmetric by construction — and everything else
//! moves to the forcing `f`, so that `M v̇ = f (+ Aᵀλ)`. Constraints give
//! `A` and `b` with `A v̇ = b`, and the energies come from the same
//! kinematics.
//!
//! A kinematic tree (see [`crate::model::Tree`]) takes a shortcut to the
//! same `M`, inertia and load terms: the recursions of `recursive`, linear
//! in the number of links per entry where the dot products are quadratic.

use crate::expr::{ExprId, Pool, Sym};
use crate::kinematics::{Kinematics, Vec3, cross, dot, mat_vec, rate_at_constant_speeds};
use crate::model::{FrameId, Model, NEWTONIAN, PointId};
pub use articulated::Articulated;
use std::rc::Rc;
pub use tree_mass::{SpeedVectors, depth_first, subtree_ends};
pub use tree_partials::{LinkState, LinkVectors};

/// The derived equations of one system, as expressions of the pool the model was resolved into.
#[derive(Clone)]
pub struct Equations {
    /// `M(q)`, `nq × nq`.
    pub mass_matrix: Vec<Vec<ExprId>>,
    /// `f(t, q, q̇, u)`, length `nq`.
    pub forcing: Vec<ExprId>,
    /// `T(q, q̇)`.
    pub kinetic_energy: ExprId,
    /// `V(q)`: gravity relative to `O` plus the `potential` statements.
    pub potential_energy: ExprId,
    /// `A(q)`, one row per constraint.
    pub constraint_jacobian: Vec<Vec<ExprId>>,
    /// `b(t, q, q̇)` with `A q̈ = b`.
    pub constraint_bias: Vec<ExprId>,
    /// `lhs − rhs` of holonomic rows, 0 for nonholonomic rows.
    pub constraint_residual: Vec<ExprId>,
    /// The velocity form `ψ = A q̇ + ψ₀` of each row: `dφ/dt` of a
    /// holonomic row, the row itself for a nonholonomic one.
    pub constraint_velocity: Vec<ExprId>,
    /// `q̈ = M⁻¹ f` by the articulated-body recursion, for kinematic trees
    /// (not among [`Equations::expressions_mut`]: it is code, not a formula
    /// for the docs).
    pub articulated: Option<Articulated>,
    /// What they were derived from, shared by every output.
    pub mechanics: Rc<Mechanics>,
}

/// The kinematics of a model and, for a kinematic tree, its joint tree
/// with its masses and loads: derived once per model, with the equations,
/// and shared by every output that derives more from them (the inverse
/// dynamics, the tree's partials and `M`'s vectors, kinematic outputs).
pub struct Mechanics {
    /// Rotations, positions and velocities of every frame and point.
    pub kinematics: Kinematics,
    /// The joint tree; `None` for a model that is no tree.
    tree: Option<recursive::JointTree>,
}

impl Mechanics {
    /// The kinematics and joint tree of `model`.
    fn new(model: &Model, pool: &mut Pool) -> Mechanics {
        let kinematics = Kinematics::new(model, pool);
        let tree = joint_tree(model, &kinematics, pool);
        Mechanics { kinematics, tree }
    }
}

impl Equations {
    /// Every expression grouped by the generated function that computes
    /// it, in a fixed order (`M` row by row, `f`, `T`, `V`, `A`, `b`,
    /// residuals, velocity forms), for passes that rewrite them.
    pub fn functions_mut(&mut self) -> [Vec<&mut ExprId>; 8] {
        let Equations {
            mass_matrix,
            forcing,
            kinetic_energy,
            potential_energy,
            constraint_jacobian,
            constraint_bias,
            constraint_residual,
            constraint_velocity,
            ..
        } = self;
        [
            mass_matrix.iter_mut().flatten().collect(),
            forcing.iter_mut().collect(),
            vec![kinetic_energy],
            vec![potential_energy],
            constraint_jacobian.iter_mut().flatten().collect(),
            constraint_bias.iter_mut().collect(),
            constraint_residual.iter_mut().collect(),
            constraint_velocity.iter_mut().collect(),
        ]
    }

    /// Every expression, in the order of [`Equations::functions_mut`].
    pub fn expressions_mut(&mut self) -> impl Iterator<Item = &mut ExprId> {
        self.functions_mut().into_iter().flatten()
    }

    /// Whether time `t` stays in `M`, `T`, `V` or `A` (prescribed motion
    /// of a mass, a constraint whose Jacobian turns with time): then the
    /// generated functions of these take `t` first and end in `_at`
    /// (`mass_matrix_at(t, q)`), and the struct is `TIME_DEPENDENT`.
    pub fn time_dependent(&self, pool: &Pool) -> bool {
        self.mass_matrix
            .iter()
            .chain(&self.constraint_jacobian)
            .flatten()
            .chain([&self.kinetic_energy, &self.potential_energy])
            .any(|&e| pool.kinds(e).intersects(crate::expr::SymKinds::TIME))
    }

    /// The same equations without groups
    /// ([`Node::Group`](crate::expr::Node::Group)), as plain canonical
    /// expressions (for rendering).
    pub fn ungrouped(&self, pool: &mut Pool) -> Equations {
        let mut plain = self.clone();
        let roots: Vec<ExprId> = plain.expressions_mut().map(|e| *e).collect();
        let images = pool.ungroup(&roots);
        plain
            .expressions_mut()
            .zip(images)
            .for_each(|(e, image)| *e = image);
        plain
    }
}

/// The rows of `A`, `b`, residual and velocity form, as in [`Equations`].
struct ConstraintRows {
    jacobian: Vec<Vec<ExprId>>,
    bias: Vec<ExprId>,
    residual: Vec<ExprId>,
    velocity: Vec<ExprId>,
}

/// A mass moving with a point and, for bodies, turning with a frame.
struct Inertia<'a> {
    mass: ExprId,
    center: PointId,
    rotation: Option<(FrameId, &'a [[ExprId; 3]; 3])>,
}

/// Derives every equation of `model`.
pub fn derive(model: &Model, pool: &mut Pool) -> Equations {
    let mechanics = Mechanics::new(model, pool);
    let Mechanics { kinematics, tree } = &mechanics;
    let nv = model.nv();
    let inertias = inertias(model);
    // The recursion carries the applied forces and torques; the general
    // route takes them through their partial velocities.
    let (mass_matrix, bias, loads_done) = match tree {
        Some(tree) => {
            let (mass_matrix, bias) = recursive::inertia_terms(tree, pool);
            (mass_matrix, bias, true)
        }
        None => {
            let (mass_matrix, bias) = inertia_terms(kinematics, pool, &inertias, nv);
            let bias = (0..nv)
                .map(|k| {
                    let gravity = gravity_force(model, kinematics, pool, &inertias, k);
                    pool.sub(bias[k], gravity)
                })
                .collect::<Vec<_>>();
            (mass_matrix, bias, false)
        }
    };
    let armature = armature(model, pool);
    let mass_matrix = with_armature(mass_matrix, &armature, pool);
    let forcing: Vec<ExprId> = (0..nv)
        .map(|k| {
            let mut active = potential_and_dissipation_force(model, kinematics, pool, k);
            if !loads_done {
                let loads = load_force(model, kinematics, pool, k);
                active = pool.add(loads, active);
            }
            pool.sub(active, bias[k])
        })
        .collect();
    let rows = constraints(model, pool);
    let articulated = match (tree, model.constraints.is_empty()) {
        (Some(tree), true) => articulated::articulated(tree, &forcing, &armature, pool),
        _ => None,
    };
    Equations {
        mass_matrix,
        forcing,
        kinetic_energy: kinetic_energy(kinematics, pool, &inertias, &armature),
        potential_energy: potential_energy(model, kinematics, pool, &inertias),
        constraint_jacobian: rows.jacobian,
        constraint_bias: rows.bias,
        constraint_residual: rows.residual,
        constraint_velocity: rows.velocity,
        articulated,
        mechanics: Rc::new(mechanics),
    }
}

/// `M q̈ − f` for the symbols `q̈`, and whether it was found by the
/// Newton–Euler sweeps with the accelerations carried outwards (where the
/// model is a tree) rather than through the derived `M` and `f`.
pub fn inverse_dynamics(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
) -> (Vec<ExprId>, bool) {
    let nv = model.nv();
    let Mechanics { kinematics, tree } = &*equations.mechanics;
    match tree {
        Some(tree) => {
            let inertial = recursive::inverse_dynamics(tree, pool);
            let armature = armature(model, pool);
            let forces = (0..nv)
                .map(|k| {
                    let active = potential_and_dissipation_force(model, kinematics, pool, k);
                    let inertial = match pool.is_zero(armature[k]) {
                        true => inertial[k],
                        false => {
                            let qdd = pool.sym(Sym::Accel(k as u32));
                            let rotor = pool.mul(armature[k], qdd);
                            pool.add(inertial[k], rotor)
                        }
                    };
                    pool.sub(inertial, active)
                })
                .collect();
            (forces, true)
        }
        None => {
            let forces = (0..nv)
                .map(|k| {
                    let mut terms: Vec<ExprId> = (0..nv)
                        .map(|j| {
                            let qdd = pool.sym(Sym::Accel(j as u32));
                            pool.mul(equations.mass_matrix[k][j], qdd)
                        })
                        .collect();
                    terms.push(pool.neg(equations.forcing[k]));
                    pool.sum(terms)
                })
                .collect();
            (forces, false)
        }
    }
}

/// The partials of the inverse dynamics `τ = M v̇ − f` of a tree of
/// revolute, prismatic, spherical and free joints in two parts: the applied loads,
/// potentials and dissipation (everything in `τ` but its inertia and
/// gravity terms) differentiated symbolically, and the vectors of each
/// link whose pairs give the rest (see `tree_partials`).
pub struct TreeJacobian {
    /// The loads', potentials' and dissipation's share of `τ`, which is
    /// minus their share of `f`.
    pub residual: Vec<ExprId>,
    /// `∂/∂δ`, `∂/∂v`, `∂/∂u` of the loads, potentials and dissipation.
    pub rest: derivatives::ResidualJacobian,
    /// The links' vectors, parents before children.
    pub links: Vec<LinkVectors>,
    /// What the runtime computes the links' vectors from, in the same
    /// order, and gravity, in the axes of its recursion (`N`'s, or a free
    /// or spherical root's: see `tree_partials::link_states`).
    pub states: Vec<LinkState>,
    pub gravity: Vec3,
}

impl TreeJacobian {
    /// `∂τ/∂δ`, `∂τ/∂v` and `∂τ/∂u` in full: the pairs' dot products added
    /// to the rest.
    pub fn combined(&self, pool: &mut Pool) -> derivatives::ResidualJacobian {
        let n = self.rest.speeds.len();
        let (by_q, by_v) = tree_partials::paired(&self.links, n, pool);
        let mut jacobian = self.rest.clone();
        for (block, inertial) in [
            (&mut jacobian.coordinates, by_q),
            (&mut jacobian.speeds, by_v),
        ] {
            for (row, inertial) in block.iter_mut().zip(inertial) {
                for (entry, x) in row.iter_mut().zip(inertial) {
                    *entry = pool.add(*entry, x);
                }
            }
        }
        jacobian
    }
}

/// The [`TreeJacobian`] of a tree of revolute, prismatic, spherical and
/// free joints whose one-speed joints move along their speeds' tangent
/// directions (each coordinate's rate its speed); `None` for any other
/// model.
pub fn tree_jacobian(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
) -> Option<TreeJacobian> {
    let Mechanics { kinematics, tree } = &*equations.mechanics;
    let (tree, joints) = (tree.as_ref()?, model.tree.as_ref()?);
    let plain = derivatives::plain_speeds(model);
    let along_its_speed = joints.links.iter().zip(&tree.links).all(|(joint, link)| {
        let speed = link.columns.first().map(|c| c.speed);
        joint.ball.is_some() || speed.is_some_and(|k| plain.contains(&(k, joint.coordinate)))
    });
    if !along_its_speed {
        return None;
    }
    let links = tree_partials::link_vectors(tree, pool)?;
    let states = tree_partials::link_states(tree, pool);
    let gravity = tree_partials::recursion_gravity(tree, pool);
    let loads = tree.applied_loads(pool);
    let residual: Vec<ExprId> = (0..model.nv())
        .map(|k| {
            let active = potential_and_dissipation_force(model, kinematics, pool, k);
            pool.sub(loads[k], active)
        })
        .collect();
    let directions = derivatives::tangent_directions(model, pool);
    let rest = derivatives::residual_jacobian(pool, &residual, &directions, model.inputs.len());
    Some(TreeJacobian {
        residual,
        rest,
        links,
        states,
        gravity,
    })
}

/// The two vectors of each speed whose dot products are the entries of a
/// tree's `M` (see `tree_mass`); `None` for a model that is no tree.
pub fn tree_mass(equations: &Equations, pool: &mut Pool) -> Option<Vec<SpeedVectors>> {
    let tree = equations.mechanics.tree.as_ref()?;
    Some(tree_mass::speed_vectors(tree, pool))
}

/// The tree of joints of `model` with its masses and loads, for the
/// recursive routes; `None` for a model that is no tree.
fn joint_tree(
    model: &Model,
    kinematics: &Kinematics,
    pool: &mut Pool,
) -> Option<recursive::JointTree> {
    let inertias = inertias(model);
    recursive::JointTree::new(model, model.tree.as_ref()?, kinematics, &inertias, pool)
}

fn inertias(model: &Model) -> Vec<Inertia<'_>> {
    let bodies = model.bodies.iter().map(|b| Inertia {
        mass: b.mass,
        center: b.center,
        rotation: Some((b.frame, &b.inertia)),
    });
    let particles = model.particles.iter().map(|p| Inertia {
        mass: p.mass,
        center: p.at,
        rotation: None,
    });
    bodies.chain(particles).collect()
}

/// Partial velocities of one mass: of its centre (in `N`) and, for a body,
/// of its frame (in the frame's axes), for every `k`.
struct Partials {
    linear: Vec<Vec3>,
    angular: Vec<Vec3>,
}

fn partials(
    kinematics: &Kinematics,
    pool: &mut Pool,
    inertia: &Inertia<'_>,
    nv: usize,
) -> Partials {
    Partials {
        linear: (0..nv)
            .map(|k| kinematics.partial_velocity(pool, inertia.center, k))
            .collect(),
        angular: match inertia.rotation {
            Some((frame, _)) => (0..nv)
                .map(|k| kinematics.partial_angular_velocity(pool, frame, k))
                .collect(),
            None => Vec::new(),
        },
    }
}

/// The mass matrix `Mₖⱼ = Σ m vₖ·vⱼ + ωₖ·(I ωⱼ)` and, for each `k`, the
/// inertia terms that multiply no `q̈`:
/// `Σ m a_bias·vₖ + (I α_bias + ω × Iω)·ωₖ`.
fn inertia_terms(
    kinematics: &Kinematics,
    pool: &mut Pool,
    inertias: &[Inertia<'_>],
    nv: usize,
) -> (Vec<Vec<ExprId>>, Vec<ExprId>) {
    let mut mass_terms = vec![vec![Vec::new(); nv]; nv];
    let mut bias_terms = vec![Vec::new(); nv];
    for inertia in inertias {
        let p = partials(kinematics, pool, inertia, nv);
        let a_bias = kinematics.acceleration_bias(pool, inertia.center);
        let m_a_bias = a_bias.map(|x| pool.mul(inertia.mass, x));
        let rotational = inertia.rotation.map(|(frame, tensor)| {
            let omega = kinematics.angular_velocity(frame);
            let alpha = kinematics.angular_acceleration_bias(pool, frame);
            let i_alpha = mat_vec(pool, tensor, &alpha);
            let h = mat_vec(pool, tensor, &omega);
            let gyroscopic = cross(pool, &omega, &h);
            let moment = [0, 1, 2].map(|i| pool.add(i_alpha[i], gyroscopic[i]));
            let i_partials: Vec<Vec3> =
                p.angular.iter().map(|w| mat_vec(pool, tensor, w)).collect();
            (moment, i_partials)
        });
        for k in 0..nv {
            bias_terms[k].push(dot(pool, &m_a_bias, &p.linear[k]));
            if let Some((moment, _)) = &rotational {
                bias_terms[k].push(dot(pool, moment, &p.angular[k]));
            }
            for j in k..nv {
                let linear = dot(pool, &p.linear[k], &p.linear[j]);
                mass_terms[k][j].push(pool.mul(inertia.mass, linear));
                if let Some((_, i_partials)) = &rotational {
                    mass_terms[k][j].push(dot(pool, &p.angular[k], &i_partials[j]));
                }
            }
        }
    }
    let mut mass_matrix = vec![vec![pool.zero(); nv]; nv];
    for k in 0..nv {
        for j in k..nv {
            let entry = pool.sum(std::mem::take(&mut mass_terms[k][j]));
            mass_matrix[k][j] = entry;
            mass_matrix[j][k] = entry;
        }
    }
    let bias = bias_terms
        .into_iter()
        .map(|terms| pool.sum(terms))
        .collect();
    (mass_matrix, bias)
}

/// The generalized gravity force `Σ m g · ∂v_G/∂q̇ₖ`.
fn gravity_force(
    model: &Model,
    kinematics: &Kinematics,
    pool: &mut Pool,
    inertias: &[Inertia<'_>],
    k: usize,
) -> ExprId {
    let mut terms = Vec::new();
    if let Some(gravity) = &model.gravity {
        let g = kinematics.express(pool, model, gravity, NEWTONIAN);
        for inertia in inertias {
            let v = kinematics.partial_velocity(pool, inertia.center, k);
            let g_dot_v = dot(pool, &g, &v);
            terms.push(pool.mul(inertia.mass, g_dot_v));
        }
    }
    pool.sum(terms)
}

/// The generalized force `F_qₖ` of the applied forces and torques, through
/// their partial velocities.
fn load_force(model: &Model, kinematics: &Kinematics, pool: &mut Pool, k: usize) -> ExprId {
    let mut terms = Vec::new();
    for force in &model.forces {
        let f = kinematics.express(pool, model, &force.vector, NEWTONIAN);
        let v = kinematics.partial_velocity(pool, force.at, k);
        terms.push(dot(pool, &f, &v));
    }
    for torque in &model.torques {
        terms.push(torque_power(
            model,
            kinematics,
            pool,
            &torque.vector,
            torque.on,
            k,
        ));
        if let Some(reacting) = torque.reacting {
            let reaction = torque_power(model, kinematics, pool, &torque.vector, reacting, k);
            terms.push(pool.neg(reaction));
        }
    }
    pool.sum(terms)
}

/// `−∂V/∂vₖ − ∂D/∂vₖ`, where `∂V/∂vₖ = Σᵢ (∂V/∂qᵢ) (∂q̇ᵢ/∂vₖ)` (`∂V/∂qₖ`
/// when `q̇ = v`).
fn potential_and_dissipation_force(
    model: &Model,
    kinematics: &Kinematics,
    pool: &mut Pool,
    k: usize,
) -> ExprId {
    let [potential] = kinematics.through_rates(pool, k, |pool, i| {
        [pool.diff(model.potential, Sym::Coord(i))]
    });
    let dissipation = pool.diff(model.dissipation, Sym::Speed(k as u32));
    let terms = [pool.neg(potential), pool.neg(dissipation)];
    pool.sum(terms)
}

/// `τ · ∂ω_F/∂q̇ₖ`, in `F`'s axes.
fn torque_power(
    model: &Model,
    kinematics: &Kinematics,
    pool: &mut Pool,
    torque: &crate::model::Vector,
    frame: FrameId,
    k: usize,
) -> ExprId {
    let tau = kinematics.express(pool, model, torque, frame);
    let w = kinematics.partial_angular_velocity(pool, frame, k);
    dot(pool, &tau, &w)
}

/// Per speed, the sum of its `armature` statements (zero if none).
fn armature(model: &Model, pool: &mut Pool) -> Vec<ExprId> {
    let mut added = vec![pool.zero(); model.nv()];
    for &(k, a) in &model.armature {
        added[k] = pool.add(added[k], a);
    }
    added
}

/// `M` with each speed's armature added to its diagonal entry.
fn with_armature(
    mut mass_matrix: Vec<Vec<ExprId>>,
    armature: &[ExprId],
    pool: &mut Pool,
) -> Vec<Vec<ExprId>> {
    for (k, &a) in armature.iter().enumerate() {
        if !pool.is_zero(a) {
            mass_matrix[k][k] = pool.add(mass_matrix[k][k], a);
        }
    }
    mass_matrix
}

/// `T = Σ ½ m v·v + ½ ω·(I ω) + Σ ½ a v²` (the last over the armatures).
fn kinetic_energy(
    kinematics: &Kinematics,
    pool: &mut Pool,
    inertias: &[Inertia<'_>],
    armature: &[ExprId],
) -> ExprId {
    let half = pool.rational(1, 2);
    let mut terms = Vec::new();
    for (k, &a) in armature.iter().enumerate() {
        if pool.is_zero(a) {
            continue;
        }
        let v = pool.sym(Sym::Speed(k as u32));
        let vv = pool.mul(v, v);
        terms.push(pool.product([half, a, vv]));
    }
    for inertia in inertias {
        let v = kinematics.velocity(pool, inertia.center);
        let vv = dot(pool, &v, &v);
        terms.push(pool.product([half, inertia.mass, vv]));
        if let Some((frame, tensor)) = inertia.rotation {
            let omega = kinematics.angular_velocity(frame);
            let h = mat_vec(pool, tensor, &omega);
            let wh = dot(pool, &omega, &h);
            terms.push(pool.mul(half, wh));
        }
    }
    pool.sum(terms)
}

/// `V = −Σ m g·r + Σ potentials`, gravity measured from `O`.
fn potential_energy(
    model: &Model,
    kinematics: &Kinematics,
    pool: &mut Pool,
    inertias: &[Inertia<'_>],
) -> ExprId {
    let mut terms = vec![model.potential];
    if let Some(gravity) = &model.gravity {
        let g = kinematics.express(pool, model, gravity, NEWTONIAN);
        for inertia in inertias {
            let r = kinematics.position(inertia.center);
            let g_dot_r = dot(pool, &g, &r);
            let minus_m = pool.neg(inertia.mass);
            terms.push(pool.mul(minus_m, g_dot_r));
        }
    }
    pool.sum(terms)
}

/// `A`, `b`, the residuals and velocity forms. A row's velocity form is
/// `ψ = A q̇ + ψ₀` (`ψ = dφ/dt` for a holonomic `φ`), so `A = ∂ψ/∂q̇` and
/// `b = −rate(ψ)`, the time derivative of `ψ` at constant speeds.
fn constraints(model: &Model, pool: &mut Pool) -> ConstraintRows {
    let (nq, nv) = (model.nq(), model.nv());
    let mut rows = ConstraintRows {
        jacobian: Vec::new(),
        bias: Vec::new(),
        residual: Vec::new(),
        velocity: Vec::new(),
    };
    for constraint in &model.constraints {
        let psi = if constraint.nonholonomic {
            rows.residual.push(pool.zero());
            constraint.residual
        } else {
            rows.residual.push(constraint.residual);
            pool.time_derivative(constraint.residual)
        };
        rows.jacobian.push(
            (0..nv)
                .map(|k| pool.diff(psi, Sym::Speed(k as u32)))
                .collect(),
        );
        let rate = rate_at_constant_speeds(pool, psi, nq as u32);
        rows.bias.push(pool.neg(rate));
        rows.velocity.push(psi);
    }
    rows
}

mod articulated;
pub mod derivatives;
#[cfg(any(test, feature = "testing"))]
pub mod lagrange;
#[cfg(test)]
mod lagrange_check;
#[cfg(test)]
mod quaternion_check;
mod recursive;
pub mod regressor;
mod tree_mass;
mod tree_partials;
