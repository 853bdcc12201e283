//! Rows of `∂v̇/∂x` a few at a time: the generated `accelerations_jacobian`
//! of a fixed-base tree takes row `i` as the vector–jacobian product
//! `μᵀ ∂τ/∂x` of the inverse dynamics at the weights `μ = −M⁻¹ eᵢ` (one
//! reverse sweep over `τ`), [`WEIGHT_LANES`] rows at once with their
//! weights in the lanes of a [`WeightLanes`]: the sweep's coefficients,
//! which do not depend on the weights, are computed once; each lane
//! operation then serves that many rows.

/// The lanes of the weights: the target's vector register of `f64`s, a
/// `wide::f64x4` with AVX, else a `wide::f64x2` (SSE2, the x86-64
/// baseline). A wider type than the registers costs the sweep a register
/// copy or a spill for about every operation (two-operand SSE2 overwrites
/// a source, and a four-lane value takes two of its sixteen registers):
/// the spatial chain of 12's jacobian took 0.84–0.87 of its time and the
/// panda's 0.69 with two lanes instead of four on the baseline. With AVX
/// (built for x86-64-v3) a four-lane value is one register and the chain
/// of 12's jacobian took 1.21 times its time with two lanes.
#[cfg(target_feature = "avx")]
pub type WeightLanes = wide::f64x4;

/// The lanes of the weights (see the AVX definition).
#[cfg(not(target_feature = "avx"))]
pub type WeightLanes = wide::f64x2;

/// The rows of `∂v̇/∂x` a pass: the lanes of a [`WeightLanes`].
pub const WEIGHT_LANES: usize = size_of::<WeightLanes>() / size_of::<f64>();

/// The passes over `n` rows, [`WEIGHT_LANES`] a pass.
#[inline]
pub const fn weight_passes(n: usize) -> usize {
    n.div_ceil(WEIGHT_LANES)
}

/// The weights of pass `pass` from `inverse` (`−M⁻¹`, symmetric, by
/// speed): for each speed `s`, the lanes
/// `inverse[s][WEIGHT_LANES pass..WEIGHT_LANES (pass + 1)]`, zero past the
/// last row.
#[inline]
pub fn weight_lanes<const N: usize>(inverse: &[[f64; N]; N], pass: usize) -> [WeightLanes; N] {
    let start = WEIGHT_LANES * pass;
    let mut weights = [WeightLanes::ZERO; N];
    for (weight, row) in weights.iter_mut().zip(inverse) {
        let lanes: [f64; WEIGHT_LANES] =
            core::array::from_fn(|k| row.get(start + k).copied().unwrap_or(0.0));
        *weight = WeightLanes::new(lanes);
    }
    weights
}

/// Writes lane `k` of each of `values` (a row's entries, a column each)
/// into row `WEIGHT_LANES pass + k` of `rows`; the lanes past the last row
/// are dropped.
#[inline]
pub fn put_rows<const C: usize, const N: usize>(
    rows: &mut [[f64; C]; N],
    pass: usize,
    values: &[WeightLanes; C],
) {
    let columns: [[f64; WEIGHT_LANES]; C] = values.map(|v| v.to_array());
    for (k, row) in rows
        .iter_mut()
        .skip(WEIGHT_LANES * pass)
        .take(WEIGHT_LANES)
        .enumerate()
    {
        for (entry, lanes) in row.iter_mut().zip(&columns) {
            if let Some(value) = lanes.get(k) {
                *entry = *value;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{WEIGHT_LANES, WeightLanes, put_rows, weight_lanes, weight_passes};

    #[test]
    fn weights_are_columns_a_pass_at_a_time_and_rows_come_back_in_place() {
        const N: usize = 5;
        let inverse: [[f64; N]; N] =
            core::array::from_fn(|i| core::array::from_fn(|j| (10 * i + j) as f64));
        let last = weight_passes(N) - 1;
        assert_eq!(last * WEIGHT_LANES < N, N <= (last + 1) * WEIGHT_LANES);
        // The last pass: its columns of each row, then zeros past the last.
        for (s, lanes) in weight_lanes(&inverse, last).iter().enumerate() {
            for (k, lane) in lanes.to_array().into_iter().enumerate() {
                let column = last * WEIGHT_LANES + k;
                let expected = if column < N {
                    (10 * s + column) as f64
                } else {
                    0.0
                };
                assert_eq!(lane, expected, "speed {s}, lane {k}");
            }
        }
        // Lane `k` of column `j`'s value: `10 k + j`; each pass writes its rows.
        let values: [WeightLanes; 2] = core::array::from_fn(|j| {
            WeightLanes::new(core::array::from_fn(|k| (10 * k + j) as f64))
        });
        let mut rows = [[-1.0; 2]; N];
        for pass in 0..=last {
            put_rows(&mut rows, pass, &values);
        }
        let expected: [[f64; 2]; N] = core::array::from_fn(|i| {
            let k = i % WEIGHT_LANES;
            [(10 * k) as f64, (10 * k + 1) as f64]
        });
        assert_eq!(rows, expected);
    }
}
