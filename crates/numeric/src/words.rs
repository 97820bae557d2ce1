//! A hash map for keys made of 64-bit words that the program builds itself (bit patterns of
//! doubles, rounded offsets, interned ids): what the studies key their repeated turns and windows
//! by, so that a long repeat costs its distinct picks.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Multiply-rotate over 64-bit words: much faster than the default SipHash for keys of many words
/// (no adversarial input: the map compares whole keys on a collision, so a poor spread costs time,
/// never a wrong answer).
#[derive(Debug, Default, Clone, Copy)]
pub struct WordHasher(u64);

impl WordHasher {
    const K: u64 = 0x9e37_79b9_7f4a_7c15;

    fn mix(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(26) ^ x).wrapping_mul(Self::K);
    }
}

impl Hasher for WordHasher {
    fn finish(&self) -> u64 {
        self.0 ^ (self.0 >> 29)
    }

    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            self.mix(u64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut w = [0u8; 8];
            w[..rest.len()].copy_from_slice(rest);
            self.mix(u64::from_le_bytes(w));
        }
    }

    fn write_u8(&mut self, x: u8) {
        self.mix(u64::from(x));
    }

    fn write_u32(&mut self, x: u32) {
        self.mix(u64::from(x));
    }

    fn write_u64(&mut self, x: u64) {
        self.mix(x);
    }

    fn write_usize(&mut self, x: usize) {
        self.mix(x as u64);
    }
}

/// A [`HashMap`] hashed by [`WordHasher`].
pub type WordMap<K, V> = HashMap<K, V, BuildHasherDefault<WordHasher>>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_keys_meet_and_distinct_keys_stay_apart() {
        let mut m: WordMap<Vec<u64>, usize> = WordMap::default();
        for i in 0..10_000u64 {
            m.insert(vec![i % 100, i / 100, u64::MAX], i as usize);
        }
        assert_eq!(m.len(), 10_000);
        assert_eq!(m[&vec![7, 42, u64::MAX]], 4207);
        // Keys that differ only in one word's high bits are still told apart.
        let a = vec![1u64 << 63, 0];
        let b = vec![0u64, 0];
        m.insert(a.clone(), 1);
        m.insert(b.clone(), 2);
        assert_eq!((m[&a], m[&b]), (1, 2));
    }
}
