//! Unit quaternions of free and spherical joints: the rotation they stand
//! for and their kinematic differential equations.
//!
//! A quaternion is `(x, y, z, w)`, vector part first (Pinocchio's order),
//! and turns the child frame from its parent: the matrix [`rotation`] maps
//! the child's components to the parent's. It is written as the
//! homogeneous quadratic form, which is the rotation for a unit quaternion
//! and `|q|²` times it otherwise; with `q̇ = ½ q ⊗ (ω, 0)` ([`rates`]),
//! `Ṙ = R [ω]×` holds for every `q`, so the derived equations are exact
//! identities, not identities modulo `|q| = 1`.

use crate::expr::{ExprId, Pool};

/// `R(q)` for `q = (x, y, z, w)`, row-major:
/// `(w² − |v|²) 1 + 2 v vᵀ + 2 w [v]×`.
pub fn rotation(pool: &mut Pool, q: [ExprId; 4]) -> [[ExprId; 3]; 3] {
    let squares = q.map(|c| pool.powi(c, 2));
    let two = pool.int(2);
    let mut r = [[pool.zero(); 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry = if i == j {
                // w² + xᵢ² − the other two squares.
                let (a, b) = ((i + 1) % 3, (i + 2) % 3);
                let minus = [pool.neg(squares[a]), pool.neg(squares[b])];
                pool.sum([squares[3], squares[i], minus[0], minus[1]])
            } else {
                // 2 (xᵢ xⱼ − w xₘ) when j follows i cyclically, else 2 (xᵢ xⱼ + w xₘ).
                let m = 3 - i - j;
                let outer = pool.mul(q[i], q[j]);
                let cross = pool.mul(q[3], q[m]);
                let signed = if (i + 1) % 3 == j {
                    pool.neg(cross)
                } else {
                    cross
                };
                let sum = pool.add(outer, signed);
                pool.mul(two, sum)
            };
        }
    }
    r
}

/// `q̇ = ½ q ⊗ (ω, 0)` for the angular velocity `ω` in the child's axes:
/// `(½ (w ω + v × ω), −½ v · ω)`.
pub fn rates(pool: &mut Pool, q: [ExprId; 4], omega: [ExprId; 3]) -> [ExprId; 4] {
    let half = pool.rational(1, 2);
    let minus_one = pool.int(-1);
    let v = [q[0], q[1], q[2]];
    let vector = [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let terms = [
            pool.mul(q[3], omega[i]),
            pool.mul(v[j], omega[k]),
            pool.product([minus_one, v[k], omega[j]]),
        ];
        let sum = pool.sum(terms);
        pool.mul(half, sum)
    });
    let dot: Vec<ExprId> = (0..3).map(|i| pool.mul(v[i], omega[i])).collect();
    let dot = pool.sum(dot);
    let minus_half = pool.neg(half);
    let scalar = pool.mul(minus_half, dot);
    [vector[0], vector[1], vector[2], scalar]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::{Env, Sym};

    struct Values([f64; 7]);
    impl Env for Values {
        fn value(&self, sym: Sym) -> f64 {
            match sym {
                Sym::Coord(i) => self.0[i as usize],
                Sym::Speed(i) => self.0[4 + i as usize],
                _ => f64::NAN,
            }
        }
    }

    /// The rotation by `angle` about the unit `axis`, by Rodrigues' formula.
    fn rodrigues(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
        let (s, c) = angle.sin_cos();
        let k = [
            [0.0, -axis[2], axis[1]],
            [axis[2], 0.0, -axis[0]],
            [-axis[1], axis[0], 0.0],
        ];
        let mut r = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                let delta = if i == j { 1.0 } else { 0.0 };
                r[i][j] = c * delta + s * k[i][j] + (1.0 - c) * axis[i] * axis[j];
            }
        }
        r
    }

    #[test]
    fn rotation_is_rodrigues_for_a_unit_quaternion() {
        let mut pool = Pool::new();
        let q = [0, 1, 2, 3].map(|i| pool.sym(Sym::Coord(i)));
        let r = rotation(&mut pool, q);
        let axis = [2.0_f64, -3.0, 6.0].map(|a| a / 7.0);
        let angle = 1.3_f64;
        let (s, c) = (angle / 2.0).sin_cos();
        let values = Values([axis[0] * s, axis[1] * s, axis[2] * s, c, 0.0, 0.0, 0.0]);
        let expected = rodrigues(axis, angle);
        for (i, (row, expected)) in r.iter().zip(expected).enumerate() {
            for (j, (&entry, expected)) in row.iter().zip(expected).enumerate() {
                let got = pool.eval(entry, &values);
                assert!((got - expected).abs() < 1e-15, "R[{i}][{j}]");
            }
        }
    }

    #[test]
    fn rates_turn_the_frame_at_omega_in_its_axes() {
        // Ṙ = R [ω]×, with Ṙ by the chain rule through q̇ = rates(q, ω),
        // for a quaternion that is not unit too.
        let mut pool = Pool::new();
        let q = [0, 1, 2, 3].map(|i| pool.sym(Sym::Coord(i)));
        let omega = [0, 1, 2].map(|i| pool.sym(Sym::Speed(i)));
        let r = rotation(&mut pool, q);
        let qd = rates(&mut pool, q, omega);
        let values = Values([0.3, -0.5, 0.2, 0.7, 1.1, -0.4, 2.0]);
        let w = [1.1, -0.4, 2.0];
        let at = |pool: &Pool, e| pool.eval(e, &values);
        for (i, row) in r.iter().enumerate() {
            for (j, &entry) in row.iter().enumerate() {
                let rate: f64 = (0..4)
                    .map(|c| {
                        let d = pool.diff(entry, Sym::Coord(c as u32));
                        at(&pool, d) * at(&pool, qd[c])
                    })
                    .sum();
                // (R [ω]×)ᵢⱼ = Rᵢₐ ω_b − R_ib ωₐ for (j, a, b) cyclic.
                let (a, b) = ((j + 1) % 3, (j + 2) % 3);
                let expected = at(&pool, row[a]) * w[b] - at(&pool, row[b]) * w[a];
                assert!((rate - expected).abs() < 1e-14, "Ṙ[{i}][{j}]");
            }
        }
    }
}
