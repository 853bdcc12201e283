//! The `#![no_std]` build (functions from `libm`) computes the same
//! equations as the `std` build of the same models in `dalembert-generated`,
//! to a few ulps (the two libraries may round `sin` and `cos` differently).

use dalembert_generated as with_std;
use dalembert_no_std as without_std;

/// Asserts `a ≈ b` entry by entry, relative to the largest entry.
fn assert_close(what: &str, a: &[f64], b: &[f64]) {
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!((x - y).abs() <= 1e-13 * scale, "{what}[{i}]: {x} vs {y}");
    }
}

/// Deterministic values in `[-2, 2)`.
fn values<const N: usize>(seed: u64) -> [f64; N] {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    std::array::from_fn(|_| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
    })
}

#[test]
fn double_pendulum() {
    let (a, b) = (
        without_std::double_pendulum::DoublePendulum {
            m: 1.3,
            L: 0.7,
            g: 9.81,
        },
        with_std::DoublePendulum {
            m: 1.3,
            L: 0.7,
            g: 9.81,
        },
    );
    for seed in 0..20 {
        let (q, qd) = (values::<2>(seed), values::<2>(seed + 100));
        assert_close(
            "M",
            a.mass_matrix(&q).as_flattened(),
            b.mass_matrix(&q).as_flattened(),
        );
        assert_close(
            "f",
            &a.forcing(0.0, &q, &qd, &[]),
            &b.forcing(0.0, &q, &qd, &[]),
        );
        assert_close(
            "T",
            &[a.kinetic_energy(&q, &qd)],
            &[b.kinetic_energy(&q, &qd)],
        );
        assert_close("V", &[a.potential_energy(&q)], &[b.potential_energy(&q)]);
    }
}

#[test]
fn constrained_pendulum() {
    let (a, b) = (
        without_std::constrained_pendulum::ConstrainedPendulum {
            m: 1.7,
            l: 1.1,
            g: 9.81,
        },
        with_std::ConstrainedPendulum {
            m: 1.7,
            l: 1.1,
            g: 9.81,
        },
    );
    for seed in 0..20 {
        let (q, qd) = (values::<3>(seed), values::<3>(seed + 100));
        let jacobian = (a.constraint_jacobian(&q), b.constraint_jacobian(&q));
        assert_close("A", jacobian.0.as_flattened(), jacobian.1.as_flattened());
        let bias = (
            a.constraint_bias(0.5, &q, &qd),
            b.constraint_bias(0.5, &q, &qd),
        );
        assert_close("b", &bias.0, &bias.1);
        let residual = (
            a.constraint_residual(0.5, &q),
            b.constraint_residual(0.5, &q),
        );
        assert_close("φ", &residual.0, &residual.1);
    }
}

#[test]
fn spatial_chain() {
    let (a, b) = (
        without_std::spatial_chain_06::SpatialChain6 {},
        with_std::SpatialChain6 {},
    );
    for seed in 0..20 {
        let (q, qd) = (values::<6>(seed), values::<6>(seed + 100));
        assert_close(
            "M",
            a.mass_matrix(&q).as_flattened(),
            b.mass_matrix(&q).as_flattened(),
        );
        assert_close(
            "f",
            &a.forcing(0.0, &q, &qd, &[]),
            &b.forcing(0.0, &q, &qd, &[]),
        );
    }
}
