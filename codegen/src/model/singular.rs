//! Where the kinematic equations `q̇ = N(q) v` of a `speeds` statement are
//! undefined: the divisors of its rates that depend on the coordinates
//! (`cos θ` in `ψ̇ = (sin φ ω_y + cos φ ω_z) / cos θ`, and the cosine of the
//! argument of every `tan`). The emitted `check_coordinate_rates` tests each
//! against zero, so that an integration reaching such a configuration stops
//! with an error naming the coordinate instead of dividing by zero.

use crate::expr::{ExprId, Func, Node, Pool, SymKinds};

/// One divisor of a coordinate's rate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RateDivisor {
    /// The coordinate whose rate divides by it (the first one, when several
    /// do).
    pub coordinate: usize,
    /// The divisor: a factor with a negative power, or `cos x` for `tan x`.
    pub divisor: ExprId,
    /// Its magnitude relative to its scale, compared with the runtime's
    /// tolerance: for a sum, divided by the sum of the magnitudes of its
    /// terms (`|a + b cos θ| / (|a| + |b cos θ|)`), so that a cancellation
    /// is caught at any scale; otherwise the magnitude itself (`|cos θ|`).
    pub relative: ExprId,
}

/// Adds to `found` the divisors of `rate`, the rate of `coordinate`, that
/// depend on the coordinates and are not in `found` yet, in the order the
/// DAG lists them (deterministic).
pub fn collect_rate_divisors(
    pool: &mut Pool,
    coordinate: usize,
    rate: ExprId,
    found: &mut Vec<RateDivisor>,
) {
    for e in pool.topo_order(&[rate]) {
        let divisor = match *pool.node(e) {
            Node::Pow(base, exponent) if exponent < 0 => base,
            Node::Func(Func::Tan, argument) => pool.cos(argument),
            _ => continue,
        };
        let moves = pool.kinds(divisor).intersects(SymKinds::COORD);
        if !moves || found.iter().any(|d| d.divisor == divisor) {
            continue;
        }
        let magnitude = pool.func(Func::Abs, divisor);
        let relative = match pool.node(divisor) {
            Node::Add(terms) => {
                let terms = terms.to_vec();
                let magnitudes: Vec<ExprId> =
                    terms.into_iter().map(|t| pool.func(Func::Abs, t)).collect();
                let scale = pool.sum(magnitudes);
                pool.div(magnitude, scale)
            }
            _ => magnitude,
        };
        found.push(RateDivisor {
            coordinate,
            divisor,
            relative,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Sym;

    #[test]
    fn a_quotient_and_a_tangent_give_their_denominators_once() {
        let mut pool = Pool::default();
        let (theta, phi, w) = (
            pool.sym(Sym::Coord(1)),
            pool.sym(Sym::Coord(2)),
            pool.sym(Sym::Speed(1)),
        );
        let (cos_theta, sin_phi) = (pool.cos(theta), pool.sin(phi));
        let numerator = pool.mul(sin_phi, w);
        let psi_rate = pool.div(numerator, cos_theta);
        let tan_theta = pool.func(Func::Tan, theta);
        let phi_rate = pool.mul(tan_theta, numerator);
        let mut found = Vec::new();
        collect_rate_divisors(&mut pool, 0, psi_rate, &mut found);
        collect_rate_divisors(&mut pool, 2, phi_rate, &mut found);
        let expected = RateDivisor {
            coordinate: 0,
            divisor: cos_theta,
            relative: pool.func(Func::Abs, cos_theta),
        };
        assert_eq!(found, [expected]);
    }

    #[test]
    fn a_sum_is_measured_against_its_terms_and_constants_are_not_divisors() {
        let mut pool = Pool::default();
        let (x, l, w) = (
            pool.sym(Sym::Coord(0)),
            pool.sym(Sym::Param(0)),
            pool.sym(Sym::Speed(0)),
        );
        // w / (l (2 + cos x)): l alone never vanishes with the motion.
        let two = pool.int(2);
        let cos_x = pool.cos(x);
        let sum = pool.add(two, cos_x);
        let denominator = pool.mul(l, sum);
        let rate = pool.div(w, denominator);
        let mut found = Vec::new();
        collect_rate_divisors(&mut pool, 0, rate, &mut found);
        let (abs_sum, abs_cos) = (pool.func(Func::Abs, sum), pool.func(Func::Abs, cos_x));
        let scale = pool.add(two, abs_cos);
        let expected = RateDivisor {
            coordinate: 0,
            divisor: sum,
            relative: pool.div(abs_sum, scale),
        };
        assert_eq!(found, [expected]);
    }
}
