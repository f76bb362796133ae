//! Cheap, deterministic hashing for the engine's own tables (hash-consing, value
//! numbering).
//!
//! A proc-macro runs unoptimised in a default debug build, and there the standard
//! library's SipHash and `num-rational`'s `Hash` (which reduces every ratio by a
//! continued-fraction recursion of big-integer divisions, so that unreduced ratios hash
//! alike) took 40–60 % of a 6- or 7-joint expansion (issue 17, measured with callgrind).
//! The engine's rationals are always reduced, so hashing a ratio's numerator and
//! denominator digits is consistent with its equality; the hasher is the multiply-rotate
//! one of rustc's `FxHasher`. Hashes never decide the output: the tables are only looked
//! up, never iterated, and every hit is confirmed by an exact comparison.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use num_bigint::Sign;

use crate::model::value::Rat;

/// A `HashMap` with [`FxHasher`].
pub type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// A `HashSet` with [`FxHasher`].
pub type FastSet<K> = std::collections::HashSet<K, BuildHasherDefault<FxHasher>>;

/// rustc's Fx hash: per word, rotate, xor, multiply. Not for untrusted keys (no DoS
/// resistance) — the engine's keys are its own.
#[derive(Clone, Copy, Debug, Default)]
pub struct FxHasher {
    hash: u64,
}

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
        self.add(i.into());
    }
    fn write_u32(&mut self, i: u32) {
        self.add(i.into());
    }
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }
    fn finish(&self) -> u64 {
        // The last multiply leaves the low bits, which pick the bucket, depending only on
        // the low bits of the last word: names such as `t1234` (a low byte `t` in every
        // first word) crowded a few buckets, and a 4 000-joint chain's statements spent
        // seconds comparing strings. The rotation brings the well-mixed high bits down
        // (as rustc-hash 2 does).
        self.hash.rotate_left(26)
    }
}

/// Feeds a reduced rational to `h`: its sign, then [`hash_magnitude`].
pub fn hash_rat(r: &Rat, h: &mut impl Hasher) {
    h.write_u8(match r.numer().sign() {
        Sign::Minus => 0,
        Sign::NoSign => 1,
        Sign::Plus => 2,
    });
    hash_magnitude(r, h);
}

/// Feeds `|r|` of a reduced rational to `h`: the 64-bit digits of numerator and
/// denominator, each preceded by its bit length so that digit strings cannot run
/// together.
pub fn hash_magnitude(r: &Rat, h: &mut impl Hasher) {
    for part in [r.numer().magnitude(), r.denom().magnitude()] {
        h.write_u64(part.bits());
        for d in part.iter_u64_digits() {
            h.write_u64(d);
        }
    }
}

/// Mixes a 64-bit value into a well-spread one (the SplitMix64 finaliser).
pub fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::Hash;

    fn hash_of(r: &Rat) -> u64 {
        let mut h = FxHasher::default();
        hash_rat(r, &mut h);
        h.finish()
    }

    #[test]
    fn equal_ratios_hash_alike_and_signs_differ() {
        let a = Rat::new(6.into(), 4.into());
        let b = Rat::new(3.into(), 2.into());
        assert_eq!(hash_of(&a), hash_of(&b));
        assert_ne!(hash_of(&a), hash_of(&-b.clone()));
        let big = Rat::new(num_bigint::BigInt::from(1u8) << 200, 3.into());
        assert_ne!(
            hash_of(&big),
            hash_of(&(big.clone() + Rat::from_integer(1.into())))
        );
        // The hasher itself is deterministic: no per-process random state.
        let mut h = FxHasher::default();
        (1u32, 2u32).hash(&mut h);
        let mut g = FxHasher::default();
        (1u32, 2u32).hash(&mut g);
        assert_eq!(h.finish(), g.finish());
    }
}
