//! Exact first derivatives of the equations of motion, for control.
//!
//! The equations `M(q) v̇ = f(t, q, v, u)` are the zeros of the residual
//! `r(t, q, v, v̇, u) = M v̇ − f` (the inverse dynamics, with the
//! accelerations as the symbols [`Sym::Accel`]). Differentiating the
//! identity `r(t, q, v, v̇(t, q, v, u), u) = 0` gives
//! `M ∂v̇/∂x = −∂r/∂x` for `x` any of `q`, `v`, `u`: the derivatives of the
//! accelerations are the partials of `r`, evaluated at the solved `v̇`, sent
//! through the factorisation of `M` that solved for `v̇`. So the generator
//! needs only `∂r/∂q`, `∂r/∂v` and `∂r/∂u` — expressions of the same DAG,
//! differentiated with the pool's memoised [`Pool::diff`], so that what the
//! columns share is computed once. `∂r/∂v̇ = M`.
//!
//! The derivatives by `q` are taken in the tangent space, one direction per
//! speed, along `q ⊕ δ` (the update of `integrate_configuration`, and
//! Pinocchio's convention): a quaternion `p` of a free or spherical joint
//! moves as `p ⊗ exp(δ_ω / 2)` (the rotation `δ_ω` in the child's axes), a
//! free joint's position as `r + R(p) δ_v` (the SE(3) exponential to first
//! order), every other coordinate as `q + δ`. By the chain rule,
//! `∂r/∂δₖ = Σ_c ∂r/∂q_c · ∂q_c/∂δₖ` ([`tangent_directions`]); where every
//! coordinate is plain this is `∂r/∂q` itself.
//!
//! The residual can come from any derivation of the same equations: built
//! from `M` and `f` or from a Newton–Euler sweep, which for a
//! tree is linear in the number of links where `M v̇` is quadratic. For a
//! tree of revolute, prismatic, spherical and free joints the partials of its inertia and
//! gravity terms also have a recursion of their own in the axes of `N`
//! (`tree_partials`, through [`super::tree_jacobian`]), which
//! differentiates only the rest of the residual (the applied loads, springs
//! and dampers) symbolically; the outputs keep whichever route costs fewer
//! operations.

use crate::expr::{ExprId, Pool, Sym};
use crate::model::{Model, quaternion};

/// The partial derivatives of a residual `r` of the equations of motion:
/// entry `[i][j]` is `∂rᵢ/∂xⱼ`.
#[derive(Clone, Debug, PartialEq)]
pub struct ResidualJacobian {
    /// `∂r/∂δ`, `nv × nv`: by the coordinates in the tangent space.
    pub coordinates: Vec<Vec<ExprId>>,
    /// `∂r/∂v`, `nv × nv`.
    pub speeds: Vec<Vec<ExprId>>,
    /// `∂r/∂u`, `nv × nu`.
    pub inputs: Vec<Vec<ExprId>>,
}

/// How `q ⊕ δ` moves the coordinates: entry `k` lists the coordinates `c`
/// that the tangent direction `δₖ` (one per speed) moves, with
/// `∂q_c/∂δₖ` at `δ = 0`.
pub type TangentDirections = Vec<Vec<(usize, ExprId)>>;

/// `∂(q ⊕ δ)/∂δ` at `δ = 0`, by direction: `½ p ⊗ (eₖ, 0)` for a
/// joint's quaternion `p` and its angular speed `k`, column `k` of the
/// rotation `R(p)` for a free joint's position and its linear speed `k`;
/// a plain coordinate moves along the direction of its own speed
/// ([`plain_speeds`]).
pub fn tangent_directions(model: &Model, pool: &mut Pool) -> TangentDirections {
    let mut directions: TangentDirections = vec![Vec::new(); model.nv()];
    for ball in &model.balls {
        let p = ball.quaternion.map(|c| pool.sym(Sym::Coord(c as u32)));
        for (axis, &k) in ball.angular.iter().enumerate() {
            let unit = [0, 1, 2].map(|i| pool.int(i64::from(i == axis)));
            let moved = quaternion::rates(pool, p, unit);
            directions[k].extend(ball.quaternion.into_iter().zip(moved));
        }
        if let Some((position, velocity)) = ball.translation {
            let rotation = quaternion::rotation(pool, p);
            for (column, &k) in velocity.iter().enumerate() {
                let moved = rotation.map(|row| row[column]);
                directions[k].extend(position.into_iter().zip(moved));
            }
        }
    }
    for (k, c) in plain_speeds(model) {
        directions[k].push((c, pool.one()));
    }
    directions
}

/// The pairs `(k, c)` of a speed and a coordinate outside every
/// quaternion joint that belong together: the `m`-th such coordinate with
/// the `m`-th such speed, in the order both are declared (a `coordinates`
/// statement adds one speed per coordinate; a `speeds` statement renames
/// them in place).
pub fn plain_speeds(model: &Model) -> Vec<(usize, usize)> {
    let (mut in_ball, mut ball_speed) = (vec![false; model.nq()], vec![false; model.nv()]);
    for ball in &model.balls {
        let (position, velocity) = ball.translation.unzip();
        for c in ball
            .quaternion
            .into_iter()
            .chain(position.into_iter().flatten())
        {
            in_ball[c] = true;
        }
        for k in ball
            .angular
            .into_iter()
            .chain(velocity.into_iter().flatten())
        {
            ball_speed[k] = true;
        }
    }
    let speeds = (0..model.nv()).filter(|&k| !ball_speed[k]);
    speeds
        .zip((0..model.nq()).filter(|&c| !in_ball[c]))
        .collect()
}

/// The names of the tangent directions (one per speed): a plain
/// coordinate's own, or the speed's along which a free or spherical
/// joint's coordinates move.
pub fn direction_names(model: &Model) -> Vec<String> {
    let mut names: Vec<String> = model.speeds.iter().map(|s| s.written()).collect();
    for (k, c) in plain_speeds(model) {
        names[k] = model.coordinates[c].to_string();
    }
    names
}

/// The kinematic rows of a linearisation in the tangent space: with
/// `q = q̄ ⊕ δ` and `v = v̄ + δv`, `δ̇ = K_δ δ + K_v δv` to first order;
/// `(K_δ, K_v)`, rows and columns by speed. For a plain coordinate `c`
/// of rate `q̇_c = N_c(q) v`, its row is `(∂N_c v/∂δ, ∂N_c v/∂v)`
/// (`(0, eₖ)` when the rate is its speed). For a quaternion joint,
/// `q ⊕ δ = q exp(δ)` gives `ν = Ad(exp(−δ)) ν̄ + δ̇` to first order, so
/// `δ̇ = δν − ad(ν̄) δ`: `δ̇_ω = δω − ω̄ × δ_ω` and, for a free joint,
/// `δ̇_v = δv − ω̄ × δ_v − v̄ × δ_ω`.
pub fn tangent_kinematics(
    model: &Model,
    pool: &mut Pool,
    directions: &TangentDirections,
) -> (Vec<Vec<ExprId>>, Vec<Vec<ExprId>>) {
    let nv = model.nv();
    let mut by_coordinates = vec![vec![pool.zero(); nv]; nv];
    let mut by_speeds = vec![vec![pool.zero(); nv]; nv];
    for (k, c) in plain_speeds(model) {
        let rate = pool.rate(c as u32);
        for (j, direction) in directions.iter().enumerate() {
            by_coordinates[k][j] = along(pool, rate, direction);
            by_speeds[k][j] = pool.diff(rate, Sym::Speed(j as u32));
        }
    }
    for ball in &model.balls {
        let omega = ball.angular.map(|k| pool.sym(Sym::Speed(k as u32)));
        let mut blocks = vec![(ball.angular, ball.angular, omega)];
        if let Some((_, velocity)) = ball.translation {
            let linear = velocity.map(|k| pool.sym(Sym::Speed(k as u32)));
            blocks.extend([
                (velocity, velocity, omega),
                (velocity, ball.angular, linear),
            ]);
        }
        // −[x]× of each block `(rows, columns, x)`.
        for (rows, columns, x) in blocks {
            for i in 0..3 {
                let (j, l) = ((i + 1) % 3, (i + 2) % 3);
                // (−[x]×)ᵢⱼ = xₗ, (−[x]×)ᵢₗ = −xⱼ for (i, j, l) cyclic.
                by_coordinates[rows[i]][columns[j]] = x[l];
                by_coordinates[rows[i]][columns[l]] = pool.neg(x[j]);
            }
        }
        let speeds = ball.translation.map(|(_, v)| v);
        for k in ball.angular.into_iter().chain(speeds.into_iter().flatten()) {
            by_speeds[k][k] = pool.one();
        }
    }
    (by_coordinates, by_speeds)
}

/// `Σ_c ∂e/∂q_c · ∂q_c/∂δ` along one tangent `direction`.
pub fn along(pool: &mut Pool, e: ExprId, direction: &[(usize, ExprId)]) -> ExprId {
    let terms: Vec<ExprId> = direction
        .iter()
        .map(|&(c, moved)| {
            let partial = pool.diff(e, Sym::Coord(c as u32));
            pool.mul(partial, moved)
        })
        .collect();
    pool.sum(terms)
}

/// `∂r/∂δ`, `∂r/∂v` and `∂r/∂u` of `residual`, for the tangent
/// `directions` (one per speed) and `nu` inputs.
pub fn residual_jacobian(
    pool: &mut Pool,
    residual: &[ExprId],
    directions: &TangentDirections,
    nu: usize,
) -> ResidualJacobian {
    let nv = directions.len();
    let mut by = |symbol: fn(u32) -> Sym, n: usize| -> Vec<Vec<ExprId>> {
        residual
            .iter()
            .map(|&r| (0..n).map(|j| pool.diff(r, symbol(j as u32))).collect())
            .collect()
    };
    let (speeds, inputs) = (by(Sym::Speed, nv), by(Sym::Input, nu));
    let coordinates = residual
        .iter()
        .map(|&r| directions.iter().map(|d| along(pool, r, d)).collect())
        .collect();
    ResidualJacobian {
        coordinates,
        speeds,
        inputs,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Env;
    use crate::random::Random;

    /// A point of `(t, q, v, v̇, u)` and the parameters.
    #[derive(Clone)]
    struct Point {
        parameters: Vec<f64>,
        q: Vec<f64>,
        v: Vec<f64>,
        a: Vec<f64>,
        u: Vec<f64>,
    }

    /// The variables of a [`Point`] that one block of partials is by.
    type Variables = fn(&mut Point) -> &mut Vec<f64>;

    impl Env for Point {
        fn value(&self, sym: Sym) -> f64 {
            match sym {
                Sym::Time => 0.3,
                Sym::Param(i) => self.parameters[i as usize],
                Sym::Coord(i) => self.q[i as usize],
                Sym::Speed(i) => self.v[i as usize],
                Sym::Accel(i) => self.a[i as usize],
                Sym::Input(i) => self.u[i as usize],
                Sym::Multiplier(_) => f64::NAN,
            }
        }
    }

    /// Every partial of the inverse dynamics of `source` (as derived: by a
    /// Newton–Euler sweep for a tree), and those of the world-frame
    /// recursion where it applies, against central differences of
    /// `M q̈ − f` evaluated numerically, at random points; whether the
    /// world-frame recursion applied.
    fn check_against_differences(source: &str) -> bool {
        let system =
            crate::language::parse_system(source.parse().expect("tokens")).expect("parses");
        let (model, mut pool) = crate::model::resolve(&system).expect("a valid model");
        let equations = super::super::derive(&model, &mut pool);
        let (tau, _) = super::super::inverse_dynamics(&model, &equations, &mut pool);
        let (nq, nu, np) = (model.nq(), model.inputs.len(), model.parameters.len());
        let directions = tangent_directions(&model, &mut pool);
        let general = residual_jacobian(&mut pool, &tau, &directions, nu);
        let tree = super::super::tree_jacobian(&model, &equations, &mut pool)
            .map(|tree| tree.combined(&mut pool));
        let residual = |pool: &Pool, point: &Point, i: usize| -> f64 {
            let inertial: f64 = (0..nq)
                .map(|j| pool.eval(equations.mass_matrix[i][j], point) * point.a[j])
                .sum();
            inertial - pool.eval(equations.forcing[i], point)
        };
        let mut random = Random::new(17);
        let mut draw =
            |n: usize| -> Vec<f64> { (0..n).map(|_| random.uniform(-2.0, 2.0)).collect() };
        let routes = std::iter::once(&general).chain(tree.as_ref());
        for jacobian in routes.flat_map(|jacobian| [jacobian; 3]) {
            let mut point = Point {
                parameters: draw(np).iter().map(|p| 1.0 + p.abs() / 2.0).collect(),
                q: draw(nq),
                v: draw(nq),
                a: draw(nq),
                u: draw(nu),
            };
            let blocks: [(&Vec<Vec<ExprId>>, Variables); 3] = [
                (&jacobian.coordinates, |p| &mut p.q),
                (&jacobian.speeds, |p| &mut p.v),
                (&jacobian.inputs, |p| &mut p.u),
            ];
            for (block, coordinate) in blocks {
                for (i, row) in block.iter().enumerate() {
                    for (j, &entry) in row.iter().enumerate() {
                        let exact = pool.eval(entry, &point);
                        let h = 1e-6;
                        let mut at = |delta: f64| {
                            let saved = coordinate(&mut point)[j];
                            coordinate(&mut point)[j] = saved + delta;
                            let value = residual(&pool, &point, i);
                            coordinate(&mut point)[j] = saved;
                            value
                        };
                        let numeric = (at(h) - at(-h)) / (2.0 * h);
                        let scale = 1.0 + exact.abs().max(numeric.abs());
                        assert!(
                            (exact - numeric).abs() <= 1e-6 * scale,
                            "∂r{i}/∂x{j}: exact {exact}, differences {numeric}"
                        );
                    }
                }
            }
        }
        tree.is_some()
    }

    #[test]
    fn partials_of_the_seed_examples_match_differences() {
        for source in [crate::seeds::DOUBLE_PENDULUM, crate::seeds::ROTATING_BAR] {
            let _ = check_against_differences(source);
        }
    }

    /// Azimuth `ψ` and elevation `θ` with the body's rates about its y and z
    /// axes as speeds (`ψ̇ = w_z / cos θ`, `θ̇ = w_y`): the kinematic rows of
    /// the linearisation are `∂(N v)/∂q` and `N`, by hand.
    #[test]
    fn kinematic_rows_of_own_speeds_are_the_partials_of_their_rates() {
        let source = "pub Pointer {
            parameters I;
            coordinates psi, theta;
            speeds wy, wz { psi: wz / cos(theta), theta: wy };
            frame A = N.rotate_z(psi);
            frame B = A.rotate_y(theta);
            body b { mass: 1, center: O, frame: B, inertia: [I, 2 * I, 3 * I] };
        }";
        let system =
            crate::language::parse_system(source.parse().expect("tokens")).expect("parses");
        let (model, mut pool) = crate::model::resolve(&system).expect("a valid model");
        let directions = tangent_directions(&model, &mut pool);
        let (by_q, by_v) = tangent_kinematics(&model, &mut pool, &directions);
        let point = Point {
            parameters: vec![1.0],
            q: vec![0.4, -0.7],
            v: vec![1.3, -0.6],
            a: Vec::new(),
            u: Vec::new(),
        };
        let (cos, sin, wz) = (0.7_f64.cos(), -(0.7_f64.sin()), -0.6);
        let expected_q = [[0.0, wz * sin / (cos * cos)], [0.0, 0.0]];
        let expected_v = [[0.0, 1.0 / cos], [1.0, 0.0]];
        for i in 0..2 {
            for j in 0..2 {
                let (got_q, got_v) = (pool.eval(by_q[i][j], &point), pool.eval(by_v[i][j], &point));
                assert!(
                    (got_q - expected_q[i][j]).abs() < 1e-14,
                    "K_δ[{i}][{j}] = {got_q}"
                );
                assert!(
                    (got_v - expected_v[i][j]).abs() < 1e-14,
                    "K_v[{i}][{j}] = {got_v}"
                );
            }
        }
    }

    /// The world-frame recursion's partials against the symbolic ones of
    /// the Newton–Euler sweep, along the same tangent directions, for a
    /// free joint at the root and a ball joint inside the tree (whose
    /// coordinates central differences would leave the unit sphere).
    #[test]
    fn the_recursions_partials_of_joints_of_several_speeds_are_the_symbolic_ones() {
        use crate::equations::quaternion_check::{BALL_IN_CHAIN, LOADED};
        for source in [LOADED, BALL_IN_CHAIN] {
            let system =
                crate::language::parse_system(source.parse().expect("tokens")).expect("parses");
            let (model, mut pool) = crate::model::resolve(&system).expect("a valid model");
            let equations = super::super::derive(&model, &mut pool);
            let (tau, _) = super::super::inverse_dynamics(&model, &equations, &mut pool);
            let (nq, nv, nu) = (model.nq(), model.nv(), model.inputs.len());
            let directions = tangent_directions(&model, &mut pool);
            let symbolic = residual_jacobian(&mut pool, &tau, &directions, nu);
            let tree = super::super::tree_jacobian(&model, &equations, &mut pool)
                .expect("the recursion takes joints of several speeds");
            let recursion = tree.combined(&mut pool);
            let mut random = Random::new(5);
            let mut draw =
                |n: usize| -> Vec<f64> { (0..n).map(|_| random.uniform(-1.0, 1.0)).collect() };
            for _ in 0..3 {
                let mut q = draw(nq);
                for ball in &model.balls {
                    let norm = ball.quaternion.map(|i| q[i] * q[i]).iter().sum::<f64>();
                    for i in ball.quaternion {
                        q[i] /= norm.sqrt();
                    }
                }
                let parameters = draw(model.parameters.len());
                let point = Point {
                    parameters: parameters.iter().map(|p| 1.0 + p.abs() / 2.0).collect(),
                    q,
                    v: draw(nv),
                    a: draw(nv),
                    u: draw(nu),
                };
                let pairs = [
                    (&recursion.coordinates, &symbolic.coordinates),
                    (&recursion.speeds, &symbolic.speeds),
                    (&recursion.inputs, &symbolic.inputs),
                ];
                for (block, (got, want)) in pairs.into_iter().enumerate() {
                    for (i, (got, want)) in got.iter().zip(want).enumerate() {
                        for (j, (&got, &want)) in got.iter().zip(want).enumerate() {
                            let (got, want) = (pool.eval(got, &point), pool.eval(want, &point));
                            assert!(
                                (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                                "{}: block {block} [{i}][{j}]: {got} against {want}",
                                model.name
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn partials_of_chains_on_the_recursive_route_match_differences() {
        use crate::chain::{Family, chain};
        for family in [Family::Planar, Family::Spatial] {
            assert!(check_against_differences(&chain(family, 3)));
        }
        // A slide, then a hinge, with an applied force.
        let cart_pole = include_str!("../../../generated/models/cart_pole.dal");
        assert!(check_against_differences(cart_pole));
    }
}
