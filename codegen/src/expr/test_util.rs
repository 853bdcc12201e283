//! Helpers shared by the tests of the engine: points to evaluate at, a
//! small deterministic random generator, and a tolerant comparison.

use std::collections::BTreeMap;

use super::{Env, Sym};

/// A deterministic xorshift generator (tests must not depend on a seed
/// from the environment).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    /// A uniform value in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        lo + (hi - lo) * (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Values of symbols; absent symbols are `NaN` so that a forgotten one
/// shows.
#[derive(Clone, Debug, Default)]
pub struct Point(pub BTreeMap<Sym, f64>);

impl Point {
    /// Each of `syms` uniform in `[-2, 2)`.
    pub fn random(rng: &mut Rng, syms: &[Sym]) -> Point {
        Point(syms.iter().map(|&s| (s, rng.uniform(-2.0, 2.0))).collect())
    }

    /// This point with `s` moved by `delta`.
    pub fn shifted(&self, s: Sym, delta: f64) -> Point {
        let mut moved = self.clone();
        *moved.0.entry(s).or_insert(f64::NAN) += delta;
        moved
    }
}

impl Env for Point {
    fn value(&self, sym: Sym) -> f64 {
        self.0.get(&sym).copied().unwrap_or(f64::NAN)
    }
}

/// Asserts `|a - b| <= tol · max(1, |a|, |b|)`.
pub fn assert_close(a: f64, b: f64, tol: f64, what: &str) {
    let scale = 1f64.max(a.abs()).max(b.abs());
    assert!((a - b).abs() <= tol * scale, "{a} vs {b} for {what}");
}
