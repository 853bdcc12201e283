//! The Schur complement `S = A M̄⁻¹ Aᵀ` of the constraints factorised as
//! `P S Pᵀ = L Lᵀ` on the stack, with or without symmetric pivoting: its
//! rank, a basic solution of `S μ = r`, the null space of `Aᵀ` and the
//! minimum-norm member of a family of multipliers.
//!
//! With pivoting (the largest remaining diagonal first) the factorisation
//! reveals the rank of `A`: it stops when every remaining pivot is at most
//! `tolerance` times the largest diagonal entry of `S`, the rows left over
//! being combinations of the rows taken. Without pivoting the rows are taken
//! in declaration order and the first pivot that fails names a dependent row.

/// A Cholesky pivot that is not safely positive: the constraint row where a
/// factorisation without pivoting stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DependentRow {
    /// The constraint row (declaration order).
    pub(crate) row: usize,
    /// Its pivot: zero, negative or tiny.
    pub(crate) pivot: f64,
}

/// `P S Pᵀ = L Lᵀ` for the first `rank` pivots.
#[derive(Clone, Copy)]
pub(crate) struct SchurFactor<const NC: usize> {
    /// Row `k` is constraint row `order[k]`. Columns `0..rank` hold `L`
    /// (`L₁₁` over `L₂₁`) on and below the diagonal.
    factors: [[f64; NC]; NC],
    /// The constraint row taken at each pivot position.
    order: [usize; NC],
    /// The number of independent rows found.
    rank: usize,
}

impl<const NC: usize> SchurFactor<NC> {
    /// Factorises the symmetric positive semi-definite `schur` taking the
    /// largest remaining pivot first, until every remaining pivot is at
    /// most `tolerance` times the largest diagonal entry: the rank. The
    /// rows `absent` (rows known to vanish identically) are left out, as
    /// dependent rows.
    pub(crate) fn pivoted(schur: [[f64; NC]; NC], tolerance: f64, absent: &[bool; NC]) -> Self {
        Self::factorise(schur, true, tolerance, absent).0
    }

    /// Factorises `schur` in declaration order, the rows `absent` left
    /// out (as dependent rows), or names the first other row whose pivot
    /// is at most `tolerance` times the largest diagonal entry.
    pub(crate) fn in_order(
        schur: [[f64; NC]; NC],
        tolerance: f64,
        absent: &[bool; NC],
    ) -> Result<Self, DependentRow> {
        match Self::factorise(schur, false, tolerance, absent) {
            (_, Some(dependent)) => Err(dependent),
            (factor, None) => Ok(factor),
        }
    }

    /// The factorisation of the rows not `absent` (moved first, in
    /// declaration order), stopped at the first pivot not above the
    /// threshold; without pivoting that pivot's row is returned too.
    fn factorise(
        schur: [[f64; NC]; NC],
        pivoting: bool,
        tolerance: f64,
        absent: &[bool; NC],
    ) -> (Self, Option<DependentRow>) {
        let largest = (0..NC).fold(0.0f64, |m, i| m.max(schur[i][i]));
        let threshold = tolerance * largest;
        let mut order = [0; NC];
        let rows = (0..NC).filter(|&i| !absent[i]);
        let present = rows.clone().count();
        for (slot, i) in order
            .iter_mut()
            .zip(rows.chain((0..NC).filter(|&i| absent[i])))
        {
            *slot = i;
        }
        let mut schur: [[f64; NC]; NC] =
            std::array::from_fn(|i| std::array::from_fn(|j| schur[order[i]][order[j]]));
        let mut rank = present;
        let mut dependent = None;
        for k in 0..present {
            if pivoting {
                let best = (k..present)
                    .max_by(|&a, &b| schur[a][a].total_cmp(&schur[b][b]))
                    .unwrap_or(k);
                swap_symmetric(&mut schur, k, best);
                order.swap(k, best);
            }
            let pivot = schur[k][k];
            if pivot.is_nan() || pivot <= threshold {
                if !pivoting {
                    dependent = Some(DependentRow {
                        row: order[k],
                        pivot,
                    });
                }
                rank = k;
                break;
            }
            eliminate(&mut schur, k);
        }
        let factor = Self {
            factors: schur,
            order,
            rank,
        };
        (factor, dependent)
    }

    /// The number of independent constraint rows.
    pub(crate) fn rank(&self) -> usize {
        self.rank
    }

    /// The basic solution of `S μ = r`: the independent rows solved, the
    /// multipliers of the dependent rows zero.
    pub(crate) fn solve(&self, r: &[f64; NC]) -> [f64; NC] {
        let mut y: [f64; NC] = std::array::from_fn(|k| r[self.order[k]]);
        self.forward(&mut y);
        self.backward(&mut y);
        let mut mu = [0.0; NC];
        for k in 0..self.rank {
            mu[self.order[k]] = y[k];
        }
        mu
    }

    /// The vector `z` of the null space of `Aᵀ` that expresses dependent
    /// pivot position `k ≥ rank` through the independent rows: `zᵀ A = 0`
    /// with `z` one at row `order[k]`, in declaration order.
    pub(crate) fn dependency(&self, k: usize) -> [f64; NC] {
        let mut w: [f64; NC] = std::array::from_fn(|j| {
            if j < self.rank {
                self.factors[k][j]
            } else {
                0.0
            }
        });
        self.backward(&mut w);
        let mut z = [0.0; NC];
        for j in 0..self.rank {
            z[self.order[j]] = -w[j];
        }
        z[self.order[k]] = 1.0;
        z
    }

    /// The last independent row, how independent it is and of what: its
    /// row (declaration order), its pivot's relative size `Lᵣᵣ / L₁₁` (an
    /// estimate of the ratio of the smallest to the largest singular value
    /// of the independent rows, within a small factor: `√2` for two rows
    /// at a small angle), and its
    /// dependency on the rows before it (as [`dependency`](Self::dependency),
    /// were it taken as dependent). `None` with no independent row.
    pub(crate) fn weakest(&self) -> Option<(usize, f64, [f64; NC])> {
        let last = self.rank.checked_sub(1)?;
        let l = &self.factors;
        let ratio = l[last][last] / l[0][0];
        let without = Self {
            rank: last,
            ..*self
        };
        Some((self.order[last], ratio, without.dependency(last)))
    }

    /// The constraint row at dependent pivot position `k`.
    pub(crate) fn row_at(&self, k: usize) -> usize {
        self.order[k]
    }

    /// The member of `λ + null(Aᵀ)` of least Euclidean norm: `λ` minus its
    /// orthogonal projection `Z (ZᵀZ)⁻¹ Zᵀ λ` onto the null space `Z` of
    /// `Aᵀ`, whose columns are the [`dependency`](Self::dependency) vectors.
    pub(crate) fn least_norm(&self, lambda: &[f64; NC]) -> [f64; NC] {
        let nullity = NC - self.rank;
        if nullity == 0 {
            return *lambda;
        }
        let mut basis = [[0.0; NC]; NC];
        for (c, column) in basis.iter_mut().take(nullity).enumerate() {
            *column = self.dependency(self.rank + c);
        }
        let dot = |a: &[f64; NC], b: &[f64; NC]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        // The Gram matrix G = ZᵀZ (positive definite on its leading
        // `nullity` block: each z has its own unit entry, zero elsewhere),
        // factorised like S, and w = G⁻¹ Zᵀλ.
        let gram: [[f64; NC]; NC] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                if i < nullity && j < nullity {
                    dot(&basis[i], &basis[j])
                } else {
                    0.0
                }
            })
        });
        let projection: [f64; NC] = std::array::from_fn(|i| {
            if i < nullity {
                dot(&basis[i], lambda)
            } else {
                0.0
            }
        });
        let w = Self::pivoted(gram, 0.0, &[false; NC]).solve(&projection);
        std::array::from_fn(|r| lambda[r] - (0..nullity).map(|c| basis[c][r] * w[c]).sum::<f64>())
    }

    /// `y ← L₁₁⁻¹ y` on the first `rank` entries.
    fn forward(&self, y: &mut [f64; NC]) {
        let l = &self.factors;
        for k in 0..self.rank {
            y[k] = (y[k] - (0..k).map(|j| l[k][j] * y[j]).sum::<f64>()) / l[k][k];
        }
    }

    /// `y ← L₁₁⁻ᵀ y` on the first `rank` entries.
    fn backward(&self, y: &mut [f64; NC]) {
        let l = &self.factors;
        for k in (0..self.rank).rev() {
            y[k] = (y[k] - (k + 1..self.rank).map(|i| l[i][k] * y[i]).sum::<f64>()) / l[k][k];
        }
    }
}

/// Swaps rows and columns `a` and `b` of a square matrix.
fn swap_symmetric<const N: usize>(matrix: &mut [[f64; N]; N], a: usize, b: usize) {
    if a != b {
        matrix.swap(a, b);
        for row in matrix.iter_mut() {
            row.swap(a, b);
        }
    }
}

/// One step of the outer-product Cholesky factorisation at a positive pivot
/// `k`: column `k` of `L`, and the trailing block updated in full (both
/// triangles, so that later symmetric swaps see a symmetric matrix).
fn eliminate<const N: usize>(matrix: &mut [[f64; N]; N], k: usize) {
    let d = matrix[k][k].sqrt();
    matrix[k][k] = d;
    for row in matrix.iter_mut().skip(k + 1) {
        row[k] /= d;
    }
    let column: [f64; N] = std::array::from_fn(|i| matrix[i][k]);
    for (i, row) in matrix.iter_mut().enumerate().skip(k + 1) {
        for (j, entry) in row.iter_mut().enumerate().skip(k + 1) {
            *entry -= column[i] * column[j];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Aᵀ`'s rows for `A = [[1, 0], [0, 1], [1, 1]]`: the third row is the
    /// sum of the first two.
    fn redundant_schur() -> [[f64; 3]; 3] {
        let a = [[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
        std::array::from_fn(|i| std::array::from_fn(|j| a[i][0] * a[j][0] + a[i][1] * a[j][1]))
    }

    #[test]
    fn pivoting_finds_the_rank_and_the_dependency() {
        let factor = SchurFactor::pivoted(redundant_schur(), 1e-12, &[false; 3]);
        assert_eq!(factor.rank(), 2);
        // Row 2 (largest diagonal) is taken first; the one left over is a
        // combination: z = ±(1, 1, −1) up to the unit entry.
        let z = factor.dependency(2);
        let left = factor.row_at(2);
        assert_eq!(z[left], 1.0);
        let a = [[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
        let za = [0, 1].map(|col| z.iter().zip(&a).map(|(z, row)| z * row[col]).sum::<f64>());
        assert!(za[0].abs() < 1e-15 && za[1].abs() < 1e-15, "zᵀA = {za:?}");
    }

    #[test]
    fn least_norm_removes_the_null_space_component() {
        let factor = SchurFactor::pivoted(redundant_schur(), 1e-12, &[false; 3]);
        // λ = (3, 5, 0) and (3 − s, 5 − s, s) give the same Aᵀλ; the least
        // norm has s = (3 + 5)/3.
        let s = 8.0 / 3.0;
        let least = factor.least_norm(&[3.0, 5.0, 0.0]);
        for (got, want) in least.iter().zip([3.0 - s, 5.0 - s, s]) {
            assert!((got - want).abs() < 1e-14, "{least:?}");
        }
    }

    #[test]
    fn absent_rows_are_left_out_in_order() {
        // A = [[0, 0], [1, 0], [0, 2]]: the first row vanishes.
        let schur = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 4.0]];
        let absent = [true, false, false];
        let error = SchurFactor::in_order(schur, 1e-14, &[false; 3])
            .err()
            .unwrap();
        assert_eq!(error.row, 0);
        let factor = SchurFactor::in_order(schur, 1e-14, &absent).unwrap();
        assert_eq!(factor.rank(), 2);
        assert_eq!(factor.solve(&[7.0, 3.0, 8.0]), [0.0, 3.0, 2.0]);
        assert_eq!(factor.least_norm(&[5.0, 3.0, 2.0]), [0.0, 3.0, 2.0]);
    }

    #[test]
    fn without_pivoting_the_first_dependent_row_is_an_error() {
        let error = SchurFactor::in_order(redundant_schur(), 1e-14, &[false; 3])
            .err()
            .unwrap();
        assert_eq!(error.row, 2);
        assert!(error.pivot.abs() < 1e-15);
    }

    #[test]
    fn basic_solution_solves_the_independent_rows() {
        let schur = [[4.0, 2.0], [2.0, 3.0]];
        let factor = SchurFactor::pivoted(schur, 1e-12, &[false; 2]);
        let mu = factor.solve(&[1.0, 2.0]);
        // det = 8: μ = (3·1 − 2·2, −2·1 + 4·2)/8.
        assert!((mu[0] + 1.0 / 8.0).abs() < 1e-15 && (mu[1] - 6.0 / 8.0).abs() < 1e-15);
    }
}
