//! The saddle-point system of a large mechanism with few couplings per row
//! (the N-four-bar mechanism, chains closed into loops): the augmented mass
//! matrix `M̄ = M + ρ AᵀA` factorised by a sparse `L D Lᵀ` in a minimum-degree
//! order, and the multipliers found by the method of multipliers, so that no
//! dense `A M̄⁻¹ Aᵀ` is ever formed. Unlike the dense solvers it keeps its
//! work arrays on the heap (a few allocations per call), which keeps the
//! stack small for mechanisms of a hundred coordinates.

use super::multipliers::CONSISTENCY_TOLERANCE;
use crate::DynamicsError;
use crate::dynamics::RELATIVE_PIVOT_TOLERANCE;

/// The weight of `AᵀA` against `M` in [`ConstraintSolver::Sparse`]
/// (`ρ ‖A‖² ≈ STIFFNESS ‖M‖`): each multiplier iteration shrinks the
/// violation of a row by about `1 / (1 + STIFFNESS σ)`, `σ` the row's
/// weight in `A M⁻¹ Aᵀ` relative to the largest, at the price of about
/// `log10(STIFFNESS)` digits in the factorisation.
///
/// [`ConstraintSolver::Sparse`]: super::ConstraintSolver::Sparse
pub const STIFFNESS: f64 = 1e6;

/// The multiplier iteration stops once every row holds to this fraction of
/// the largest `Σⱼ |Aᵢⱼ xⱼ| + |cᵢ|` of any row.
const CONVERGED: f64 = 1e-13;

/// The multiplier iteration has stalled (at the rounding of the stiff
/// factorisation) when an iteration leaves more than this fraction of the
/// violation before it; a violation then left beyond
/// [`CONSISTENCY_TOLERANCE`] means contradictory rows.
const STALLED: f64 = 0.99;

/// At most this many multiplier iterations (rows close to dependent
/// converge slowly).
const MAX_ITERATIONS: usize = 100;

/// `M̄ = L D Lᵀ` in an elimination order that keeps `L` sparse: at every
/// step the coordinate with the fewest remaining couplings (the structural
/// nonzeros of `M̄` at this `q`, with the fill-in of earlier steps).
struct SparseFactor<const N: usize> {
    /// In the column of each eliminated coordinate `p`, the entries `Lᵢₚ`
    /// for `i` in `couplings[p]` (the rest is the matrix as eliminated).
    l: Vec<[f64; N]>,
    d: [f64; N],
    order: [usize; N],
    couplings: Vec<[u16; N]>,
    count: [u16; N],
}

impl<const N: usize> SparseFactor<N> {
    /// Factorises the symmetric `matrix`, or names the first coordinate
    /// whose pivot is not safely positive.
    fn new(matrix: Vec<[f64; N]>, names: &[&'static str; N]) -> Result<Self, DynamicsError> {
        let largest = (0..N).fold(0.0f64, |m, i| m.max(matrix[i][i]));
        let tolerance = RELATIVE_PIVOT_TOLERANCE * largest;
        let mut coupled = vec![[false; N]; N];
        let mut degree = [0usize; N];
        for i in 0..N {
            for j in 0..N {
                if i != j && matrix[i][j] != 0.0 {
                    coupled[i][j] = true;
                    degree[i] += 1;
                }
            }
        }
        let mut factor = SparseFactor {
            l: matrix,
            d: [0.0; N],
            order: [0; N],
            couplings: vec![[0; N]; N],
            count: [0; N],
        };
        let w = &mut factor.l;
        let mut done = [false; N];
        for step in 0..N {
            let p = (0..N)
                .filter(|&i| !done[i])
                .min_by_key(|&i| degree[i])
                .unwrap_or(0);
            let pivot = w[p][p];
            if pivot.is_nan() || pivot <= tolerance {
                return Err(DynamicsError::SingularMassMatrix {
                    index: p,
                    coordinate: names[p],
                    pivot,
                });
            }
            done[p] = true;
            factor.order[step] = p;
            factor.d[p] = pivot;
            let mut n = 0;
            for i in 0..N {
                if !done[i] && coupled[p][i] {
                    factor.couplings[p][n] = i as u16;
                    degree[i] -= 1;
                    n += 1;
                }
            }
            factor.count[p] = n as u16;
            // Row `p` keeps `M̄ₚⱼ = Lⱼₚ dₚ` for the update; column `p` takes `L`.
            let neighbours = &factor.couplings[p][..n];
            for &i in neighbours {
                let i = usize::from(i);
                let li = w[i][p] / pivot;
                for &j in neighbours {
                    let j = usize::from(j);
                    w[i][j] -= li * w[p][j];
                    if i != j && !coupled[i][j] {
                        coupled[i][j] = true;
                        degree[i] += 1;
                    }
                }
            }
            for &i in neighbours {
                let i = usize::from(i);
                w[i][p] /= pivot;
            }
        }
        Ok(factor)
    }

    /// `M̄⁻¹ b`.
    fn solve(&self, mut b: [f64; N]) -> [f64; N] {
        for &p in &self.order {
            let y = b[p];
            for &i in self.neighbours(p) {
                b[usize::from(i)] -= self.l[usize::from(i)][p] * y;
            }
        }
        for (x, d) in b.iter_mut().zip(&self.d) {
            *x /= d;
        }
        for &p in self.order.iter().rev() {
            let correction: f64 = self
                .neighbours(p)
                .iter()
                .map(|&i| self.l[usize::from(i)][p] * b[usize::from(i)])
                .sum();
            b[p] -= correction;
        }
        b
    }

    fn neighbours(&self, p: usize) -> &[u16] {
        &self.couplings[p][..usize::from(self.count[p])]
    }
}

/// The rows of `A` by their nonzero entries, for products with `A` and `Aᵀ`
/// at the cost of the nonzeros.
struct SparseRows<const NV: usize, const NC: usize> {
    /// `(j, Aᵢⱼ)` of every nonzero, row after row.
    entries: Vec<(usize, f64)>,
    /// Row `i` is `entries[ends[i - 1]..ends[i]]` (from 0 for row 0).
    ends: [usize; NC],
}

impl<const NV: usize, const NC: usize> SparseRows<NV, NC> {
    fn new(jacobian: &[[f64; NV]; NC]) -> Self {
        let mut entries = Vec::new();
        let mut ends = [0; NC];
        for (row, end) in jacobian.iter().zip(&mut ends) {
            entries.extend(
                row.iter()
                    .enumerate()
                    .filter(|(_, a)| **a != 0.0)
                    .map(|(j, &a)| (j, a)),
            );
            *end = entries.len();
        }
        SparseRows { entries, ends }
    }

    /// The nonzero `(j, Aᵢⱼ)` of row `i`.
    fn row(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let start = if i == 0 { 0 } else { self.ends[i - 1] };
        self.entries[start..self.ends[i]].iter().copied()
    }

    /// `A x`.
    fn times(&self, x: &[f64; NV]) -> [f64; NC] {
        std::array::from_fn(|i| self.row(i).map(|(j, a)| a * x[j]).sum())
    }

    /// `f + Aᵀ μ`.
    fn plus_transpose_times(&self, f: &[f64; NV], mu: &[f64; NC]) -> [f64; NV] {
        let mut sum = *f;
        for (i, m) in mu.iter().enumerate() {
            for (j, a) in self.row(i) {
                sum[j] += a * m;
            }
        }
        sum
    }
}

/// The sparse counterpart of the dense metric: `M̄ = M + ρ AᵀA` factorised
/// once, for the accelerations and the projections.
pub(crate) struct SparseMetric<const NV: usize, const NC: usize> {
    factor: SparseFactor<NV>,
    rows: SparseRows<NV, NC>,
    penalty: f64,
}

impl<const NV: usize, const NC: usize> SparseMetric<NV, NC> {
    /// Factorises `M + ρ AᵀA` with `ρ ‖A‖² = STIFFNESS ‖M‖` (largest
    /// diagonal entries); fails as the dense metric does when it is not
    /// positive definite.
    pub(crate) fn new(
        mass: &[[f64; NV]; NV],
        names: &[&'static str; NV],
        jacobian: &[[f64; NV]; NC],
    ) -> Result<Self, DynamicsError> {
        let rows = SparseRows::new(jacobian);
        let mut column_norms = [0.0f64; NV];
        for i in 0..NC {
            for (j, a) in rows.row(i) {
                column_norms[j] += a * a;
            }
        }
        let largest_mass = (0..NV).fold(0.0f64, |m, i| m.max(mass[i][i]));
        let largest_row = column_norms.iter().fold(0.0f64, |m, &c| m.max(c));
        let penalty = match (largest_mass > 0.0, largest_row > 0.0) {
            (_, false) => 0.0,
            (true, true) => STIFFNESS * largest_mass / largest_row,
            (false, true) => STIFFNESS / largest_row,
        };
        let mut augmented = mass.to_vec();
        for i in 0..NC {
            for (j, a) in rows.row(i) {
                for (k, b) in rows.row(i) {
                    augmented[j][k] += penalty * a * b;
                }
            }
        }
        Ok(SparseMetric {
            factor: SparseFactor::new(augmented, names)?,
            rows,
            penalty,
        })
    }

    /// The `x` and the least-norm `λ` of `M x = f + Aᵀ λ`, `A x = c`, by
    /// the method of multipliers (see [`iterate`](Self::iterate)); fails if
    /// rows are left violated beyond [`CONSISTENCY_TOLERANCE`]
    /// (contradictory rows).
    pub(crate) fn solve(
        &self,
        f: &[f64; NV],
        c: &[f64; NC],
    ) -> Result<([f64; NV], [f64; NC]), DynamicsError> {
        let solution = self.iterate(f, c);
        if solution.mismatch > CONSISTENCY_TOLERANCE * solution.scale {
            return Err(DynamicsError::InconsistentConstraints {
                row: solution.worst,
                with: solution.second,
                mismatch: solution.mismatch,
            });
        }
        let lambda = std::array::from_fn(|i| solution.mu[i] - self.penalty * c[i]);
        Ok((solution.x, lambda))
    }

    /// The smallest correction in the metric of `M` with `A x = c` (as
    /// nearly as the rows allow: a projection iterates anyway).
    pub(crate) fn least_norm(&self, c: &[f64; NC]) -> [f64; NV] {
        self.iterate(&[0.0; NV], c).x
    }

    /// The method of multipliers: `M̄ xₖ = f + Aᵀ μₖ`,
    /// `μₖ₊₁ = μₖ + ρ (c − A xₖ)` from `μ₀ = ρ c`, so that `λ = μ − ρ c`
    /// stays in the range of `A` (the least-norm member of its family).
    /// Stops when the rows hold, or when the violation no longer shrinks
    /// (the rounding of the stiff factorisation, or rows that contradict),
    /// with the best iterate.
    fn iterate(&self, f: &[f64; NV], c: &[f64; NC]) -> Multipliers<NV, NC> {
        let mut mu: [f64; NC] = std::array::from_fn(|i| self.penalty * c[i]);
        let mut best: Option<Multipliers<NV, NC>> = None;
        for _ in 0..MAX_ITERATIONS {
            let x = self.factor.solve(self.rows.plus_transpose_times(f, &mu));
            let achieved = self.rows.times(&x);
            let current = self.violation(x, mu, &achieved, c);
            let converged = current.mismatch <= CONVERGED * current.scale;
            match &best {
                Some(previous)
                    if current.mismatch.is_nan()
                        || current.mismatch >= STALLED * previous.mismatch =>
                {
                    return best.unwrap_or(current);
                }
                _ if converged => return current,
                _ => {}
            }
            for i in 0..NC {
                mu[i] += self.penalty * (c[i] - achieved[i]);
            }
            best = Some(current);
        }
        best.unwrap_or_else(|| self.violation([0.0; NV], mu, &[0.0; NC], c))
    }

    /// `x` and `μ` with the rows most and second most violated, the
    /// largest violation `|cᵢ − Aᵢ x|` and the scale it is measured against,
    /// the largest `Σⱼ |Aᵢⱼ xⱼ| + |cᵢ|`.
    fn violation(
        &self,
        x: [f64; NV],
        mu: [f64; NC],
        achieved: &[f64; NC],
        c: &[f64; NC],
    ) -> Multipliers<NV, NC> {
        let (mut worst, mut second) = (0, 0);
        let mut violations = [0.0f64; NC];
        let mut scale = 0.0f64;
        for i in 0..NC {
            violations[i] = (c[i] - achieved[i]).abs();
            let terms: f64 = self.rows.row(i).map(|(j, a)| (a * x[j]).abs()).sum();
            scale = scale.max(terms + c[i].abs());
            if violations[i] > violations[worst] {
                (worst, second) = (i, worst);
            } else if i != worst && (second == worst || violations[i] > violations[second]) {
                second = i;
            }
        }
        Multipliers {
            x,
            mu,
            worst,
            second,
            mismatch: violations.iter().fold(0.0, |m: f64, &v| m.max(v)),
            scale,
        }
    }
}

/// An iterate of the method of multipliers and how far it is off.
struct Multipliers<const NV: usize, const NC: usize> {
    x: [f64; NV],
    mu: [f64; NC],
    worst: usize,
    second: usize,
    mismatch: f64,
    scale: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constrained::ConstraintSolver;
    use crate::constrained::test_systems::{PointOnCircle, TiedMassless};

    /// An arrow matrix (first row and column full, diagonal elsewhere) in
    /// natural order fills in completely; the minimum-degree order leaves
    /// the full coordinate for the end and has no fill.
    #[test]
    fn an_arrow_matrix_is_solved_without_fill() {
        const N: usize = 6;
        let m: [[f64; N]; N] = std::array::from_fn(|i| {
            std::array::from_fn(|j| match (i, j) {
                _ if i == j => 4.0 + i as f64,
                (0, _) | (_, 0) => 1.0,
                _ => 0.0,
            })
        });
        let factor = SparseFactor::new(m.to_vec(), &["q"; N]).unwrap();
        let total_couplings: usize = factor.count.iter().map(|&c| usize::from(c)).sum();
        assert_eq!(total_couplings, N - 1, "no fill-in");
        let b = [1.0, -2.0, 3.0, 0.5, -1.5, 2.5];
        let x = factor.solve(b);
        for i in 0..N {
            let mx: f64 = (0..N).map(|j| m[i][j] * x[j]).sum();
            assert!((mx - b[i]).abs() < 1e-14, "row {i}: {mx} vs {}", b[i]);
        }
    }

    #[test]
    fn a_pendulum_and_a_redundant_row_agree_with_the_rank_revealing_solver() {
        let twice = PointOnCircle::<2> {
            m: 2.0,
            l: 0.5,
            g: 9.81,
        };
        for (q, v) in [([0.3, -0.4], [0.8, 0.6]), ([-0.5, 0.0], [0.0, 2.0])] {
            let dense = ConstraintSolver::RankRevealing
                .accelerations(&twice, 0.0, &q, &v, &[])
                .unwrap();
            let sparse = ConstraintSolver::Sparse
                .accelerations(&twice, 0.0, &q, &v, &[])
                .unwrap();
            for (a, b) in dense.0.iter().zip(&sparse.0) {
                assert!(
                    (a - b).abs() < 1e-10 * (1.0 + a.abs()),
                    "{dense:?} {sparse:?}"
                );
            }
            // The least-norm multipliers: the rod tension shared equally.
            for (a, b) in dense.1.iter().zip(&sparse.1) {
                assert!(
                    (a - b).abs() < 1e-9 * (1.0 + a.abs()),
                    "{dense:?} {sparse:?}"
                );
            }
        }
    }

    #[test]
    fn a_coordinate_without_inertia_tied_by_a_row_has_its_acceleration() {
        let system = TiedMassless {
            m: 2.0,
            g: 9.81,
            push: 5.0,
        };
        let (vdot, [lambda]) = ConstraintSolver::Sparse
            .accelerations(&system, 0.0, &[0.3, 0.3], &[1.0, 1.0], &[])
            .unwrap();
        let expected = system.push / system.m - system.g;
        assert!((vdot[0] - expected).abs() < 1e-9 && (vdot[1] - expected).abs() < 1e-9);
        assert!((lambda + system.push).abs() < 1e-8, "{lambda}");
    }

    #[test]
    fn contradictory_rows_are_named() {
        // x = 0 and 2x = 0 demanding different accelerations.
        let metric = SparseMetric::new(
            &[[1.0, 0.0], [0.0, 1.0]],
            &["x", "y"],
            &[[1.0, 0.0], [2.0, 0.0]],
        )
        .unwrap();
        let error = metric.solve(&[0.0, -9.81], &[0.0, 1.0]).unwrap_err();
        assert!(
            matches!(error, DynamicsError::InconsistentConstraints { .. }),
            "{error:?}"
        );
    }
}
