//! What only generated code calls, out of the user's API (serde's
//! `__private` pattern): the elementary functions and Taylor recurrences the
//! emitted functions call, the tables and loops of the looped tree route,
//! the unrolled solvers' helpers, the constrained linearisation's and
//! series' entry points, and the runtime's generic Cholesky solver that
//! tests and benchmarks compare the emitted one with. Hidden from the docs
//! and free to change with the code generator; nothing here is for users.

pub mod lanes;
pub mod math;
pub mod series;

pub use crate::constrained::linearize::{
    AccelerationPartials, ConstrainedPartials, ManifoldChart, constrained_accelerations_jacobian,
    linearize_on_constraints,
};
pub use crate::constrained::multipliers::SaddlePoint;
pub use crate::constrained::series::{SeriesSolver, constrained_series};
pub use crate::dynamics::adjoint_rows::{
    WEIGHT_LANES, WeightLanes, put_rows, weight_lanes, weight_passes,
};
pub use crate::dynamics::cholesky::{check_pivots, cholesky_accelerations, pivot_tolerance};
pub use crate::dynamics::null_motion::{NULL_MOTION_NAMES, with_null_motion};
pub use crate::dynamics::pairs::{
    TreeLink, TreeSpeed, add_to_diagonal, add_tree_pairs, tree_mass_matrix,
};
pub use crate::dynamics::rows::{scale_and_subtract, subtract_on_runs};
pub use crate::dynamics::tree_vectors::{LinkState, TreeRecursion};

/// `vector[index]`, or zero past its end: how the looped tree route reads
/// the runtime's bias and residual at constant indices without an indexing
/// panic path in generated code (inlined, it is the load alone).
#[inline(always)]
pub fn vector_entry<const N: usize>(vector: &[f64; N], index: usize) -> f64 {
    vector.get(index).copied().unwrap_or(0.0)
}

/// `matrix[row][column]`, or zero outside it: the looped tree route's read
/// of the runtime's mass matrix, as [`vector_entry`].
#[inline(always)]
pub fn matrix_entry<const N: usize>(matrix: &[[f64; N]; N], row: usize, column: usize) -> f64 {
    matrix
        .get(row)
        .and_then(|entries| entries.get(column))
        .copied()
        .unwrap_or(0.0)
}
