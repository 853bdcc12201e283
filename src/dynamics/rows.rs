//! Row operations of a solve with many right-hand sides at once: the
//! generated `accelerations_jacobian` substitutes all its columns through
//! the one `L D Lᵀ` factorisation of `M` together, row by row, so that each
//! step is one pass over the columns, four columns an operation in the
//! lanes of a `wide::f64x4` (the rest, fewer than four, one by one). A
//! step of the forward substitution whose terms are zero outside some runs
//! of columns (on a tree, a row's right-hand sides are nonzero only in the
//! columns of its ancestors, itself and its subtree) passes over those
//! runs only, [`subtract_on_runs`].

use crate::__private::lanes::Lanes;

/// `row ← factor · row − Σₖ lₖ · otherₖ`, entry by entry (the terms
/// subtracted in their order): one step of a forward substitution
/// (`factor` 1) or of a backward one (`factor` a reciprocal pivot). Four
/// columns at a time in lanes, each rounded as the scalar
/// `factor * x − l₁ * y₁ − …` (no fused operation): the same values.
#[inline]
pub fn scale_and_subtract<const C: usize, const K: usize>(
    row: &mut [f64; C],
    factor: f64,
    terms: [(f64, &[f64; C]); K],
) {
    combine(row, Some(factor), &terms, (0, C));
}

/// `row ← row − Σₖ lₖ · otherₖ` on the columns of `runs` (each
/// `(start, end)`, `end` excluded) and nothing elsewhere: a step of a
/// forward substitution whose `otherₖ` are all zero outside the runs,
/// which there leaves every entry as [`scale_and_subtract`] with `factor`
/// 1 would (`x − l · 0 = x`), in fewer operations.
#[inline]
pub fn subtract_on_runs<const C: usize, const K: usize>(
    row: &mut [f64; C],
    terms: [(f64, &[f64; C]); K],
    runs: &[(usize, usize)],
) {
    for &run in runs {
        combine(row, None, &terms, run);
    }
}

/// `row ← factor · row − Σₖ lₖ · otherₖ` (`row − …` without a factor) on
/// the columns from `start` to before `end`, four at a time in lanes.
#[inline(always)]
fn combine<const C: usize, const K: usize>(
    row: &mut [f64; C],
    factor: Option<f64>,
    terms: &[(f64, &[f64; C]); K],
    (start, end): (usize, usize),
) {
    let end = end.min(C);
    let lanes = start + end.saturating_sub(start) / 4 * 4;
    for first in (start..lanes).step_by(4) {
        let mut value = Lanes::new(four(row, first));
        if let Some(factor) = factor {
            value *= Lanes::splat(factor);
        }
        for (l, other) in terms {
            value -= Lanes::new(four(other, first)) * *l;
        }
        if let Some(chunk) = row.get_mut(first..first + 4) {
            chunk.copy_from_slice(value.as_array());
        }
    }
    for column in lanes..end {
        let mut value = row[column];
        if let Some(factor) = factor {
            value *= factor;
        }
        for (l, other) in terms {
            value -= l * other[column];
        }
        row[column] = value;
    }
}

/// The four entries from `first`.
#[inline(always)]
fn four<const C: usize>(entries: &[f64; C], first: usize) -> [f64; 4] {
    [
        entries[first],
        entries[first + 1],
        entries[first + 2],
        entries[first + 3],
    ]
}

#[cfg(test)]
mod tests {
    use super::{scale_and_subtract, subtract_on_runs};

    #[test]
    fn scales_then_subtracts_each_term() {
        let mut row = [1.0, 2.0, -3.0];
        let (a, b) = ([1.0, 0.0, 2.0], [0.5, 4.0, 1.0]);
        scale_and_subtract(&mut row, -2.0, [(3.0, &a), (2.0, &b)]);
        // -2·1 − 3·1 − 2·0.5, -2·2 − 0 − 2·4, -2·-3 − 3·2 − 2·1
        assert_eq!(row, [-6.0, -12.0, -2.0]);
    }

    /// Nine columns: two passes of four lanes and one column alone, each
    /// entry as the scalar expression rounds it.
    #[test]
    fn lanes_and_the_rest_round_as_the_scalar_step() {
        let start: [f64; 9] = std::array::from_fn(|i| 0.1 + i as f64 / 7.0);
        let (a, b): ([f64; 9], [f64; 9]) = (
            std::array::from_fn(|i| (i as f64).sin()),
            std::array::from_fn(|i| 1.0 / (1.0 + i as f64)),
        );
        let (la, lb, factor) = (0.3, -1.7, 1.0 / 3.0);
        let mut row = start;
        scale_and_subtract(&mut row, factor, [(la, &a), (lb, &b)]);
        for i in 0..9 {
            assert_eq!(
                row[i],
                factor * start[i] - la * a[i] - lb * b[i],
                "column {i}"
            );
        }
    }

    /// Runs of columns: the entries outside them untouched, those inside
    /// as the full step with factor 1 leaves them.
    #[test]
    fn runs_change_only_their_columns_as_the_full_step_would() {
        let start: [f64; 11] = std::array::from_fn(|i| 0.2 - i as f64 / 5.0);
        let (a, b): ([f64; 11], [f64; 11]) = (
            std::array::from_fn(|i| (i as f64).cos()),
            std::array::from_fn(|i| 2.0 / (3.0 + i as f64)),
        );
        let (la, lb) = (0.7, -1.3);
        let mut full = start;
        scale_and_subtract(&mut full, 1.0, [(la, &a), (lb, &b)]);
        let runs = [(0, 2), (3, 9), (10, 11)];
        let mut partial = start;
        subtract_on_runs(&mut partial, [(la, &a), (lb, &b)], &runs);
        for i in 0..11 {
            let inside = runs.iter().any(|&(s, e)| (s..e).contains(&i));
            let expected = if inside { full[i] } else { start[i] };
            assert_eq!(partial[i], expected, "column {i}");
        }
    }
}
