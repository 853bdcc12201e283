//! The small dense linear algebra of the implicit integrators: an LU
//! factorisation with partial pivoting on the stack.

/// An LU factorisation with partial pivoting, `P A = L U`, on the stack.
pub(crate) struct Lu<const N: usize> {
    /// `L` below the diagonal (unit diagonal implied) and `U` on and above.
    factors: [[f64; N]; N],
    /// Row `i` of `P A` is row `rows[i]` of `A`.
    rows: [usize; N],
    /// Whether a pivot was zero or not finite.
    singular: bool,
}

impl<const N: usize> Lu<N> {
    /// Factors `matrix`.
    pub(crate) fn factor(mut matrix: [[f64; N]; N]) -> Self {
        let mut rows = std::array::from_fn(|i| i);
        let mut singular = false;
        for k in 0..N {
            let pivot = (k..N)
                .max_by(|&a, &b| matrix[a][k].abs().total_cmp(&matrix[b][k].abs()))
                .unwrap_or(k);
            matrix.swap(k, pivot);
            rows.swap(k, pivot);
            let diagonal = matrix[k][k];
            if diagonal == 0.0 || !diagonal.is_finite() {
                singular = true;
                continue;
            }
            let (upper, lower) = matrix.split_at_mut(k + 1);
            let pivot_row = &upper[k];
            for row in lower {
                let factor = row[k] / diagonal;
                row[k] = factor;
                for (entry, pivot) in row[k + 1..].iter_mut().zip(&pivot_row[k + 1..]) {
                    *entry -= factor * pivot;
                }
            }
        }
        Self {
            factors: matrix,
            rows,
            singular,
        }
    }

    /// `x` with `A x = b`, or `None` if `A` is singular.
    pub(crate) fn solve(&self, b: &[f64; N]) -> Option<[f64; N]> {
        if self.singular {
            return None;
        }
        let mut x: [f64; N] = std::array::from_fn(|i| b[self.rows[i]]);
        for i in 0..N {
            for j in 0..i {
                x[i] -= self.factors[i][j] * x[j];
            }
        }
        for i in (0..N).rev() {
            for j in i + 1..N {
                x[i] -= self.factors[i][j] * x[j];
            }
            x[i] /= self.factors[i][i];
        }
        Some(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_solves_a_system_that_needs_pivoting_and_reports_a_singular_one() {
        let lu = Lu::factor([[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]]);
        let x = lu.solve(&[4.5, 3.0, 6.0]).unwrap();
        for (got, want) in x.iter().zip([1.5, 1.5, 1.5]) {
            assert!((got - want).abs() < 1e-14, "{x:?}");
        }
        assert_eq!(
            Lu::factor([[1.0, 2.0], [2.0, 4.0]]).solve(&[1.0, 1.0]),
            None
        );
    }
}
