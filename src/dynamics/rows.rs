//! Row operations of a solve with many right-hand sides at once: the
//! generated `accelerations_jacobian` substitutes all its columns through
//! the one `L D Lᵀ` factorisation of `M` together, row by row, so that each
//! step is one loop over the columns, which the compiler vectorises.

/// `row ← factor · row − Σₖ lₖ · otherₖ`, entry by entry (the terms
/// subtracted in their order): one step of a forward substitution
/// (`factor` 1) or of a backward one (`factor` a reciprocal pivot).
#[inline]
pub fn scale_and_subtract<const C: usize, const K: usize>(
    row: &mut [f64; C],
    factor: f64,
    terms: [(f64, &[f64; C]); K],
) {
    for (column, entry) in row.iter_mut().enumerate() {
        let mut value = factor * *entry;
        for (l, other) in &terms {
            value -= l * other[column];
        }
        *entry = value;
    }
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
}
