//! Four rows of `∂v̇/∂x` a pass: the generated `accelerations_jacobian` of
//! a fixed-base tree takes row `i` as the vector–jacobian product
//! `μᵀ ∂τ/∂x` of the inverse dynamics at the weights `μ = −M⁻¹ eᵢ` (one
//! reverse sweep over `τ`), four rows at once with their weights in the
//! lanes of a `wide::f64x4`: the sweep's coefficients, which do not depend
//! on the weights, are computed once; each lane operation then serves
//! four rows.

use crate::__private::lanes::{LANES, Lanes};

/// The weights of pass `pass` from `inverse` (`−M⁻¹`, symmetric, by
/// speed): for each speed `s`, the lanes `inverse[s][4 pass..4 pass + 4]`,
/// zero past the last row.
#[inline]
pub fn weight_lanes<const N: usize>(inverse: &[[f64; N]; N], pass: usize) -> [Lanes; N] {
    let start = LANES * pass;
    let mut weights = [Lanes::ZERO; N];
    for (weight, row) in weights.iter_mut().zip(inverse) {
        let lanes: [f64; LANES] =
            core::array::from_fn(|k| row.get(start + k).copied().unwrap_or(0.0));
        *weight = Lanes::new(lanes);
    }
    weights
}

/// Writes lane `k` of each of `values` (a row's entries, a column each)
/// into row `4 pass + k` of `rows`; the lanes past the last row are
/// dropped.
#[inline]
pub fn put_rows<const C: usize, const N: usize>(
    rows: &mut [[f64; C]; N],
    pass: usize,
    values: &[Lanes; C],
) {
    let columns: [[f64; LANES]; C] = values.map(|v| v.to_array());
    for (k, row) in rows.iter_mut().skip(LANES * pass).take(LANES).enumerate() {
        for (entry, lanes) in row.iter_mut().zip(&columns) {
            if let Some(value) = lanes.get(k) {
                *entry = *value;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Lanes, put_rows, weight_lanes};

    #[test]
    fn weights_are_columns_four_at_a_time_and_rows_come_back_in_place() {
        let inverse: [[f64; 5]; 5] =
            core::array::from_fn(|i| core::array::from_fn(|j| (10 * i + j) as f64));
        let second = weight_lanes(&inverse, 1);
        // Columns 4.. of each row: column 4, then zeros.
        for (s, lanes) in second.iter().enumerate() {
            assert_eq!(lanes.to_array(), [(10 * s + 4) as f64, 0.0, 0.0, 0.0]);
        }
        let mut rows = [[0.0; 2]; 5];
        let values = [
            Lanes::new([1.0, 2.0, 3.0, 4.0]),
            Lanes::new([5.0, 6.0, 7.0, 8.0]),
        ];
        put_rows(&mut rows, 0, &values);
        put_rows(&mut rows, 1, &values);
        assert_eq!(
            rows,
            [[1.0, 5.0], [2.0, 6.0], [3.0, 7.0], [4.0, 8.0], [1.0, 5.0]]
        );
    }
}
