//! Row operations of a solve with many right-hand sides at once: the
//! generated `accelerations_jacobian` substitutes all its columns through
//! the one `L D Lᵀ` factorisation of `M` together, row by row, so that each
//! step is one pass over the columns, four columns an operation in the
//! lanes of a `wide::f64x4` (the rest, fewer than four, one by one).

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
    let lanes = C - C % 4;
    let (head, tail) = row.split_at_mut(lanes);
    for (start, chunk) in (0..lanes).step_by(4).zip(head.chunks_exact_mut(4)) {
        let mut value = Lanes::new(four(chunk)) * factor;
        for (l, other) in &terms {
            value -= Lanes::new(four(&other[start..start + 4])) * *l;
        }
        chunk.copy_from_slice(value.as_array());
    }
    for (column, entry) in (lanes..C).zip(tail) {
        let mut value = factor * *entry;
        for (l, other) in &terms {
            value -= l * other[column];
        }
        *entry = value;
    }
}

/// Four entries as an array.
#[inline(always)]
fn four(entries: &[f64]) -> [f64; 4] {
    [entries[0], entries[1], entries[2], entries[3]]
}

#[cfg(test)]
mod tests {
    use super::scale_and_subtract;

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
}
