//! The numbers compared between routes, and the comparisons.

use dalembert_codegen::testing::{Interpreter, Values};

/// The relative tolerance of every comparison.
const TOLERANCE: f64 = 1e-10;

/// `M`, `f` and the energies of one system at one state.
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluation {
    /// `M(q)`, row by row.
    pub mass_matrix: Vec<Vec<f64>>,
    /// `f(t, q, q̇, u)`.
    pub forcing: Vec<f64>,
    /// `T(q, q̇)`.
    pub kinetic_energy: f64,
    /// `V(q)`.
    pub potential_energy: f64,
}

impl Evaluation {
    /// What `interpreter` computes at `at`.
    pub fn interpreted(interpreter: &Interpreter, at: &Values<'_>) -> Evaluation {
        Evaluation {
            mass_matrix: interpreter.mass_matrix(at),
            forcing: interpreter.forcing(at),
            kinetic_energy: interpreter.kinetic_energy(at),
            potential_energy: interpreter.potential_energy(at),
        }
    }

    /// Panics with `context` unless every number of `self` agrees with
    /// `other` to `TOLERANCE` (1e-10) relative to the largest magnitude of its
    /// kind (at least one).
    pub fn assert_agrees(&self, other: &Evaluation, context: &str) {
        let pairs: [(&str, Vec<f64>, Vec<f64>); 4] = [
            ("M", self.mass_matrix.concat(), other.mass_matrix.concat()),
            ("f", self.forcing.clone(), other.forcing.clone()),
            ("T", vec![self.kinetic_energy], vec![other.kinetic_energy]),
            (
                "V",
                vec![self.potential_energy],
                vec![other.potential_energy],
            ),
        ];
        for (what, ours, theirs) in pairs {
            assert_eq!(ours.len(), theirs.len(), "{context}: sizes of {what}");
            let scale = ours.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
            for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
                assert!(
                    (a - b).abs() <= TOLERANCE * scale,
                    "{context}: {what}[{i}] {a:e} vs {b:e} (scale {scale:e})"
                );
            }
        }
    }
}

/// Panics with `context` unless `m` is symmetric (to `TOLERANCE`, 1e-10) and
/// positive definite: its Cholesky factorisation succeeds.
pub fn assert_positive_definite(m: &[Vec<f64>], context: &str) {
    let n = m.len();
    let scale = m.concat().iter().fold(1.0_f64, |s, x| s.max(x.abs()));
    let mut l = vec![vec![0.0; n]; n];
    for i in 0..n {
        for j in 0..=i {
            assert!(
                (m[i][j] - m[j][i]).abs() <= TOLERANCE * scale,
                "{context}: M is not symmetric at ({i}, {j}): {m:?}"
            );
            let s = m[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>();
            if i == j {
                assert!(
                    s > 0.0,
                    "{context}: M is not positive definite (pivot {i} is {s:e}): {m:?}"
                );
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
}
