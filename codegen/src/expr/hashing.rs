//! The hasher of the pool's lookups (hash-consing and memoised
//! derivatives): rustc's Fx hash, one rotate, xor and multiply per word.
//! The keys are the engine's own small integers and slices of them, never
//! an attacker's, so SipHash's resistance to chosen collisions buys nothing,
//! and hashing with it was a quarter of a derivation's time. The maps are
//! looked up, never iterated, so the output does not depend on the hasher.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A `HashMap` hashed by [`FxHasher`].
pub(super) type FxHashMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// rustc's `FxHasher` (rustc-hash 1): a word at a time.
#[derive(Clone, Copy, Default)]
pub(super) struct FxHasher {
    hash: u64,
}

/// The multiplier of rustc-hash 1 (from the golden ratio, odd).
const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl FxHasher {
    fn add(&mut self, word: u64) {
        self.hash = (self.hash.rotate_left(5) ^ word).wrapping_mul(SEED);
    }
}

impl Hasher for FxHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.add(u64::from_le_bytes(word));
        }
    }

    fn write_u8(&mut self, i: u8) {
        self.add(u64::from(i));
    }

    fn write_u16(&mut self, i: u16) {
        self.add(u64::from(i));
    }

    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
    }

    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }

    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }

    fn finish(&self) -> u64 {
        self.hash
    }
}
