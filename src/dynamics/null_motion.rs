//! Why a mass matrix is singular: the motion that moves no mass.
//!
//! Where `M` loses rank, some combination `x` of the speeds has `M x = 0`:
//! at that configuration those speeds' columns are dependent. One speed
//! alone means it moves no mass of its own; several mean a coordinate
//! singularity — Euler angles whose first and third axes line up (a top
//! released upright, a gimbal lock) turn about the same axis there. The
//! [`NullMotion`] found by a Cholesky factorisation with diagonal pivoting
//! (rank-revealing, on the stack: the one the constraint solvers use for
//! their Schur complement) names them for
//! [`DynamicsError::SingularMassMatrix`].

use super::{DynamicsError, RELATIVE_PIVOT_TOLERANCE};
use crate::constrained::SchurFactor;

/// The most speeds a [`NullMotion`] names: two, the Euler angles that line
/// up (a dependency among more names its first two), so that the error
/// stays small enough to return by value cheaply.
pub const NULL_MOTION_NAMES: usize = 2;

/// A combination of the speeds that moves no mass at a configuration where
/// `M` is singular: the null vector of `M`, scaled so that its largest
/// weight is `1` and the first positive, by the coordinates (or speeds)
/// that take part in it (a weight of at least `1e-6`), in index order, at
/// most [`NULL_MOTION_NAMES`] of them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NullMotion {
    names: [&'static str; NULL_MOTION_NAMES],
    weights: [f32; NULL_MOTION_NAMES],
    len: u8,
}

/// A weight smaller than this (relative to the largest) takes no part.
const NEGLIGIBLE_WEIGHT: f64 = 1e-6;

/// The pivots of the rank-revealing factorisation that count as zero,
/// relative to the largest diagonal entry: looser than the solvers' test
/// ([`RELATIVE_PIVOT_TOLERANCE`]), which has already failed, so that the
/// factorisation meets the dependency however the rounding fell.
const RANK_TOLERANCE: f64 = 1e4 * RELATIVE_PIVOT_TOLERANCE;

impl NullMotion {
    /// The names taking part, in index order.
    pub fn names(&self) -> &[&'static str] {
        &self.names[..usize::from(self.len)]
    }

    /// Their weights, in the order of [`names`](NullMotion::names).
    pub fn weights(&self) -> &[f32] {
        &self.weights[..usize::from(self.len)]
    }

    /// The motion that moves no mass for `mass`, whose rows and columns are
    /// named by `names`; empty if `mass` has a non-finite entry.
    pub fn of<const N: usize>(mass: &[[f64; N]; N], names: &[&'static str; N]) -> NullMotion {
        if N == 0 || !mass.iter().flatten().all(|x| x.is_finite()) {
            return NullMotion::default();
        }
        let factor = SchurFactor::pivoted(*mass, RANK_TOLERANCE, &[false; N]);
        // The first dependent column expressed through the columns before
        // it; with none found (the solvers' stricter test failed, this one
        // did not), the last pivot's column through the others.
        let x = match factor.rank() {
            rank if rank < N => factor.dependency(rank),
            _ => factor
                .weakest()
                .map_or([0.0; N], |(.., dependency)| dependency),
        };
        let largest = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let weights = x.map(|w| w / largest);
        let mut motion = NullMotion::default();
        let taking_part = (0..N).filter(|&i| weights[i].abs() >= NEGLIGIBLE_WEIGHT);
        for index in taking_part.take(NULL_MOTION_NAMES) {
            let slot = usize::from(motion.len);
            motion.names[slot] = names[index];
            motion.weights[slot] = weights[index] as f32;
            motion.len += 1;
        }
        // The first named speed turns forwards.
        if motion.weights[0] < 0.0 {
            motion.weights.iter_mut().for_each(|w| *w = -*w);
        }
        motion
    }
}

/// `error` with the [`NullMotion`] of `mass` (rows named by `names`) when
/// it is a [`DynamicsError::SingularMassMatrix`] that has none yet; any
/// other error as it is. The emitted solvers call it on their way out of a
/// failed pivot, with the mass matrix they factored.
pub fn with_null_motion<const N: usize>(
    error: DynamicsError,
    mass: &[[f64; N]; N],
    names: &[&'static str; N],
) -> DynamicsError {
    match error {
        DynamicsError::SingularMassMatrix {
            index,
            coordinate,
            pivot,
            null_motion,
        } if null_motion.names().is_empty() => DynamicsError::SingularMassMatrix {
            index,
            coordinate,
            pivot,
            null_motion: NullMotion::of(mass, names),
        },
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_speed_that_moves_nothing_stands_alone() {
        let mass = [[2.0, 0.0, 0.5], [0.0, 0.0, 0.0], [0.5, 0.0, 1.0]];
        let motion = NullMotion::of(&mass, &["a", "b", "c"]);
        assert_eq!(motion.names(), ["b"]);
        assert_eq!(motion.weights(), [1.0]);
    }

    #[test]
    fn two_columns_that_coincide_are_named_together() {
        // The top upright: ψ and φ turn about the same axis, so their
        // columns are equal, and ψ̇ = −φ̇ moves nothing.
        let (i3, i1) = (0.8, 1.5);
        let mass = [[i3, 0.0, i3], [0.0, i1, 0.0], [i3, 0.0, i3]];
        let motion = NullMotion::of(&mass, &["psi", "theta", "phi"]);
        assert_eq!(motion.names().len(), 2, "{motion:?}");
        assert!(motion.names().contains(&"psi") && motion.names().contains(&"phi"));
        assert!((motion.weights()[0] + motion.weights()[1]).abs() < 1e-6);
        let x = [
            f64::from(motion.weights()[0]),
            0.0,
            f64::from(motion.weights()[1]),
        ];
        let residual: f64 = mass
            .iter()
            .map(|row| (0..3).map(|j| row[j] * x[j]).sum::<f64>().abs())
            .sum();
        assert!(residual < 1e-6);
    }

    #[test]
    fn a_non_finite_matrix_has_no_motion_to_name() {
        let motion = NullMotion::of(&[[f64::NAN]], &["a"]);
        assert!(motion.names().is_empty());
    }
}
