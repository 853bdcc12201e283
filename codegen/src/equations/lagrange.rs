//! An independent route to the same equations, for cross-checks in the
//! interpreter: `M` as the Hessian of `T` in the speeds, and `f` from
//! Lagrange's equations `d/dt ∂T/∂q̇ − ∂T/∂q + ∂V/∂q + ∂D/∂q̇ = Q`, with
//! gravity through `V` rather than as a force, and the generalized forces
//! `Q` of forces and torques through partial velocities taken another way
//! than d'Alembert's assembly takes them.

use crate::expr::{ExprId, Pool, Sym};
use crate::kinematics::{Kinematics, dot, rate_at_constant_speeds};
use crate::model::{Model, NEWTONIAN, Vector};

/// `(M, f)` by Lagrange's equations from the kinetic energy `t` and the
/// potential energy `v` (gravity included) of `model`.
pub fn lagrange(
    model: &Model,
    pool: &mut Pool,
    t: ExprId,
    v: ExprId,
) -> (Vec<Vec<ExprId>>, Vec<ExprId>) {
    let kinematics = Kinematics::new(model, pool);
    let nq = model.nq() as u32;
    let mut mass = Vec::new();
    let mut forcing = Vec::new();
    for k in 0..nq {
        let momentum = pool.diff(t, Sym::Speed(k));
        mass.push(
            (0..nq)
                .map(|j| pool.diff(momentum, Sym::Speed(j)))
                .collect(),
        );
        let momentum_rate = rate_at_constant_speeds(pool, momentum, nq);
        // Qₖ + ∂T/∂qₖ − (rate of ∂T/∂q̇ₖ) − ∂V/∂qₖ − ∂D/∂q̇ₖ
        let applied = applied_force(model, &kinematics, pool, k);
        let dissipated = pool.diff(model.dissipation, Sym::Speed(k));
        let conservative = pool.diff(v, Sym::Coord(k));
        let dt_dq = pool.diff(t, Sym::Coord(k));
        let gained = pool.add(applied, dt_dq);
        let lost = pool.sum([dissipated, conservative, momentum_rate]);
        forcing.push(pool.sub(gained, lost));
    }
    (mass, forcing)
}

/// `Qₖ = Σ F·∂v/∂q̇ₖ + Σ τ·∂ω/∂q̇ₖ`, by another route than the generator's:
/// `∂v/∂q̇ₖ` differentiates the velocity (not the position), and torques
/// are dotted in `N`'s axes with `ω` rotated into `N`.
fn applied_force(model: &Model, kinematics: &Kinematics, pool: &mut Pool, k: u32) -> ExprId {
    let mut terms = Vec::new();
    for force in &model.forces {
        let f = kinematics.express(pool, model, &force.vector, NEWTONIAN);
        let v = kinematics.velocity(pool, force.at);
        let partial = v.map(|x| pool.diff(x, Sym::Speed(k)));
        terms.push(dot(pool, &f, &partial));
    }
    for torque in &model.torques {
        let tau = kinematics.express(pool, model, &torque.vector, NEWTONIAN);
        let mut frames = vec![(torque.on, false)];
        frames.extend(torque.reacting.map(|r| (r, true)));
        for (frame, reaction) in frames {
            let mut omega_in_frame = Vector::default();
            let omega = kinematics.angular_velocity(frame);
            for (axis, w) in omega.iter().enumerate() {
                let unit = Vector::unit(pool, frame, axis).scale(*w, pool);
                omega_in_frame = omega_in_frame.add(&unit, pool);
            }
            let omega_n = kinematics.express(pool, model, &omega_in_frame, NEWTONIAN);
            let partial = omega_n.map(|x| pool.diff(x, Sym::Speed(k)));
            let p = dot(pool, &tau, &partial);
            terms.push(if reaction { pool.neg(p) } else { p });
        }
    }
    pool.sum(terms)
}
