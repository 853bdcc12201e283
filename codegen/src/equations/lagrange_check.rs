//! An independent route to the same equations, run in the interpreter:
//! `M` as the Hessian of `T` in the speeds, and `f` from Lagrange's
//! equations `d/dt ∂T/∂q̇ − ∂T/∂q + ∂V/∂q + ∂D/∂q̇ = Q`, with gravity through
//! `V` rather than as a force, and the generalized forces `Q` of forces and
//! torques through partial velocities taken another way. Checked at random
//! states on every example system.

use super::derive;
use crate::expr::{Env, ExprId, Pool, Sym};
use crate::kinematics::{Kinematics, dot, rate_at_constant_speeds};
use crate::model::{Model, NEWTONIAN, Vector, resolve};
use crate::seeds::{CONSTRAINED_PENDULUM, DOUBLE_PENDULUM, ROTATING_BAR};

/// Seed examples 1–3 as in DESIGN §3, and systems that exercise the rest of
/// the language: 3-D rotations, products of inertia, particles, forces,
/// reacting torques, potentials, dissipation, moving geometry and joints.
const SYSTEMS: [&str; 6] = [
    DOUBLE_PENDULUM,
    ROTATING_BAR,
    CONSTRAINED_PENDULUM,
    "pub Gyro {
        parameters m, a, b, c, g, k, r;
        coordinates psi, th, ph;
        inputs Tq, Fx;
        frame A = N.rotate_z(psi);
        frame B = A.rotate_x(th);
        frame C = B.rotate_y(ph);
        point G = O + a * B.z + r * C.x;
        body rotor { mass: m, center: G, frame: C, inertia: [a*m, b*m, c*m, m*a*b/10, -m*c/7, m/5] };
        particle tip { mass: m/3, at: G + b * C.z - r * B.y };
        gravity -g * N.z;
        force Fx * N.x + k * dt(th) * A.y at G;
        torque Tq * B.y on C reacting A;
        potential k * th^2 / 2 + k * sin(ph)^2;
        dissipation c * dt(psi)^2 / 2 + r * dt(ph) * dt(th);
    }",
    "pub MovingBase {
        parameters m, l, w, g;
        coordinates s, theta;
        frame R = N.rotate_z(w * t);
        point C = O + s * R.x + sin(w * t) * N.y;
        frame B = R.rotate_z(theta);
        body cart { mass: 2 * m, center: C, frame: R, inertia: [0, 0, m] };
        body arm { mass: m, center: C - l * B.y, frame: B, inertia: [m*l^2, 0, m*l^2/3] };
        gravity -g * N.y + g/10 * N.x;
    }",
    "pub Chain {
        parameters m1, m2, L1, L2, g;
        coordinates q1, q2, q3;
        joint revolute J1 { parent: N, child: L1f, axis: z, coordinate: q1, at: O };
        joint revolute J2 { parent: L1f, child: L2f, axis: y, coordinate: q2, at: J1 + L1 * L1f.x };
        joint prismatic J3 { parent: L2f, child: S, axis: x, coordinate: q3, at: J2 };
        body link1 { mass: m1, center: J1 + L1/2 * L1f.x, frame: L1f, inertia: [0, m1*L1^2/12, m1*L1^2/12] };
        body link2 { mass: m2, center: J2 + L2/2 * L2f.x, frame: L2f, inertia: [m2/100, m2*L2^2/12, m2*L2^2/12] };
        particle slider { mass: m2/2, at: J3 };
        gravity -g * N.z;
    }",
];

/// Numeric values of every symbol, from a small deterministic generator.
struct State {
    values: Vec<(Sym, f64)>,
}

impl Env for State {
    fn value(&self, sym: Sym) -> f64 {
        self.values
            .iter()
            .find(|(s, _)| *s == sym)
            .map_or(0.0, |(_, v)| *v)
    }
}

fn random_state(model: &Model, seed: u64) -> State {
    let mut x = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut values = vec![(Sym::Time, 3.0 * next())];
    for i in 0..model.parameters.len() as u32 {
        values.push((Sym::Param(i), 0.5 + next()));
    }
    for i in 0..model.nq() as u32 {
        values.push((Sym::Coord(i), 6.0 * next() - 3.0));
        values.push((Sym::Speed(i), 4.0 * next() - 2.0));
    }
    for i in 0..model.inputs.len() as u32 {
        values.push((Sym::Input(i), 10.0 * next() - 5.0));
    }
    State { values }
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

/// `(M, f)` by Lagrange's equations, as expressions.
fn lagrange(
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

/// The model, pool and d'Alembert equations of a system in the language.
fn derived(source: &str) -> (Model, Pool, super::Equations) {
    let system = crate::language::parse_system(source.parse().expect("tokens"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut model = resolve(&system).unwrap_or_else(|e| panic!("{e}"));
    let mut pool = std::mem::take(&mut model.pool);
    let equations = derive(&model, &mut pool);
    (model, pool, equations)
}

fn assert_close(what: &str, a: f64, b: f64, scale: f64) {
    assert!(
        (a - b).abs() <= 1e-10 * scale.max(1.0),
        "{what}: d'Alembert {a:e} vs Lagrange {b:e}"
    );
}

#[test]
fn dalembert_agrees_with_lagrange_on_every_example_system() {
    for source in SYSTEMS {
        let (model, mut pool, equations) = derived(source);
        let (mass, forcing) = lagrange(
            &model,
            &mut pool,
            equations.kinetic_energy,
            equations.potential_energy,
        );
        let nq = model.nq();
        for seed in 0..5 {
            let state = random_state(&model, seed);
            let name = format!("{} at state {seed}", model.name);
            let scale_m = (0..nq)
                .map(|k| pool.eval(equations.mass_matrix[k][k], &state).abs())
                .fold(0.0, f64::max);
            let scale_f = (0..nq)
                .map(|k| pool.eval(forcing[k], &state).abs())
                .fold(0.0, f64::max);
            for k in 0..nq {
                for (j, (&ours, &theirs)) in
                    equations.mass_matrix[k].iter().zip(&mass[k]).enumerate()
                {
                    let (a, b) = (pool.eval(ours, &state), pool.eval(theirs, &state));
                    assert_close(&format!("{name}: M[{k}][{j}]"), a, b, scale_m);
                }
                let a = pool.eval(equations.forcing[k], &state);
                let b = pool.eval(forcing[k], &state);
                assert_close(&format!("{name}: f[{k}]"), a, b, scale_f);
            }
        }
    }
}

#[test]
fn the_mass_matrix_is_symmetric_and_its_quadratic_form_is_twice_t() {
    for source in SYSTEMS {
        let (model, pool, equations) = derived(source);
        let state = random_state(&model, 42);
        let nq = model.nq();
        let qd: Vec<f64> = (0..nq as u32).map(|i| state.value(Sym::Speed(i))).collect();
        let mut quadratic = 0.0;
        for k in 0..nq {
            for j in 0..nq {
                let m = pool.eval(equations.mass_matrix[k][j], &state);
                assert_eq!(m, pool.eval(equations.mass_matrix[j][k], &state));
                quadratic += qd[k] * m * qd[j];
            }
        }
        let t = pool.eval(equations.kinetic_energy, &state);
        // Only scleronomic systems have T = ½ q̇ᵀ M q̇ exactly.
        if !pool
            .kinds(equations.kinetic_energy)
            .intersects(crate::expr::SymKinds::TIME)
        {
            assert_close(&format!("{}: 2T", model.name), quadratic, 2.0 * t, t.abs());
        }
    }
}
