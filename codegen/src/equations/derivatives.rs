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
//! The residual can come from any derivation of the same equations: built
//! from `M` and `f` or from a Newton–Euler sweep, which for a
//! tree is linear in the number of links where `M v̇` is quadratic.

use crate::expr::{ExprId, Pool, Sym};

/// The partial derivatives of a residual `r` of the equations of motion:
/// entry `[i][j]` is `∂rᵢ/∂xⱼ`.
#[derive(Clone, Debug, PartialEq)]
pub struct ResidualJacobian {
    /// `∂r/∂q`, `nv × nq`.
    pub coordinates: Vec<Vec<ExprId>>,
    /// `∂r/∂v`, `nv × nv`.
    pub speeds: Vec<Vec<ExprId>>,
    /// `∂r/∂u`, `nv × nu`.
    pub inputs: Vec<Vec<ExprId>>,
}

/// `∂r/∂q`, `∂r/∂v` and `∂r/∂u` of `residual`, for `nq` coordinates (the
/// speeds are their rates) and `nu` inputs.
pub fn residual_jacobian(
    pool: &mut Pool,
    residual: &[ExprId],
    nq: usize,
    nu: usize,
) -> ResidualJacobian {
    let mut by = |symbol: fn(u32) -> Sym, n: usize| -> Vec<Vec<ExprId>> {
        residual
            .iter()
            .map(|&r| (0..n).map(|j| pool.diff(r, symbol(j as u32))).collect())
            .collect()
    };
    ResidualJacobian {
        coordinates: by(Sym::Coord, nq),
        speeds: by(Sym::Speed, nq),
        inputs: by(Sym::Input, nu),
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
    /// Newton–Euler sweep for a tree) against central differences of
    /// `M q̈ − f` evaluated numerically, at random points.
    fn check_against_differences(source: &str) {
        let system =
            crate::language::parse_system(source.parse().expect("tokens")).expect("parses");
        let (model, mut pool) = crate::model::resolve(&system).expect("a valid model");
        let equations = super::super::derive(&model, &mut pool);
        let (tau, _) = super::super::inverse_dynamics(&model, &equations, &mut pool);
        let (nq, nu, np) = (model.nq(), model.inputs.len(), model.parameters.len());
        let jacobian = residual_jacobian(&mut pool, &tau, nq, nu);
        let residual = |pool: &Pool, point: &Point, i: usize| -> f64 {
            let inertial: f64 = (0..nq)
                .map(|j| pool.eval(equations.mass_matrix[i][j], point) * point.a[j])
                .sum();
            inertial - pool.eval(equations.forcing[i], point)
        };
        let mut random = Random::new(17);
        let mut draw =
            |n: usize| -> Vec<f64> { (0..n).map(|_| random.uniform(-2.0, 2.0)).collect() };
        for _ in 0..3 {
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
    }

    #[test]
    fn partials_of_the_seed_examples_match_differences() {
        for source in [crate::seeds::DOUBLE_PENDULUM, crate::seeds::ROTATING_BAR] {
            check_against_differences(source);
        }
    }

    #[test]
    fn partials_of_chains_on_the_recursive_route_match_differences() {
        use crate::chain::{Family, chain};
        for family in [Family::Planar, Family::Spatial] {
            check_against_differences(&chain(family, 3));
        }
        // A slide, then a hinge, with an applied force.
        check_against_differences(include_str!("../../../generated/models/cart_pole.dal"));
    }
}
