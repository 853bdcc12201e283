//! The one pseudo-random generator of the project's tests and benchmarks:
//! xorshift64 from a scrambled seed. Small, fast and deterministic, so that
//! every run on every machine draws the same states.

/// A deterministic xorshift64 generator.
#[derive(Clone, Debug)]
pub struct Random(u64);

impl Random {
    /// A generator whose sequence is fixed by `seed` (any value, zero too).
    pub fn new(seed: u64) -> Random {
        Random(
            seed.wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407)
                | 1,
        )
    }

    /// A value uniform in `[low, high)`.
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        low + (high - low) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::Random;

    #[test]
    fn draws_are_reproducible_and_cover_the_interval() {
        let draws = |seed| -> Vec<f64> {
            let mut random = Random::new(seed);
            (0..1000).map(|_| random.uniform(-2.0, 3.0)).collect()
        };
        assert_eq!(draws(7), draws(7));
        assert_ne!(draws(7), draws(8));
        let values = draws(0);
        assert!(values.iter().all(|x| (-2.0..3.0).contains(x)));
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        assert!((mean - 0.5).abs() < 0.15, "mean {mean}");
        assert!(values.iter().any(|&x| x < -1.5) && values.iter().any(|&x| x > 2.5));
    }
}
