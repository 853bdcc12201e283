//! Shared by the integration tests: reading the reference data copied from
//! `shared/reference` (see `tests/reference/README.md`) and comparing
//! floating-point results with a relative tolerance.

#![allow(dead_code)] // each test binary uses its own subset

use serde_json::Value;
use std::path::Path;

/// Parses a JSON file of `tests/reference/`.
pub fn reference(file: &str) -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/reference")
        .join(file);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("bad JSON in {}: {e}", path.display()))
}

/// A JSON array of numbers as a fixed-size array.
pub fn array<const N: usize>(value: &Value) -> [f64; N] {
    let items = value.as_array().expect("a JSON array");
    assert_eq!(items.len(), N, "array length");
    std::array::from_fn(|i| items[i].as_f64().expect("a number"))
}

/// A JSON array of rows as a fixed-size matrix.
pub fn matrix<const R: usize, const C: usize>(value: &Value) -> [[f64; C]; R] {
    let rows = value.as_array().expect("a JSON array of rows");
    assert_eq!(rows.len(), R, "row count");
    std::array::from_fn(|i| array(&rows[i]))
}

/// Asserts `|actual − expected| ≤ tol · max(|expected|, scale)` entry by
/// entry, where `scale` is the largest magnitude among the expected
/// entries (so that a zero entry is compared at the quantity's scale).
pub fn assert_close(what: &str, actual: &[f64], expected: &[f64], tol: f64) {
    assert_eq!(actual.len(), expected.len(), "{what}: length");
    let scale = expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        let bound = tol * e.abs().max(scale).max(f64::MIN_POSITIVE);
        assert!(
            (a - e).abs() <= bound,
            "{what}[{i}]: got {a:e}, expected {e:e} (|diff| = {:e} > {bound:e})",
            (a - e).abs()
        );
    }
}

/// Flattens a matrix row by row.
pub fn flat<const R: usize, const C: usize>(m: &[[f64; C]; R]) -> Vec<f64> {
    m.iter().flatten().copied().collect()
}
