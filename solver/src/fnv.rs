//! 64-bit FNV-1a (Fowler–Noll–Vo; offset basis 0xcbf29ce484222325, prime 2⁴⁰ + 2⁸ + 0xb3),
//! the checksum of checkpoint files and the hash of the case and mesh they were written
//! for (`stage::checkpoint_seal`, `case::fingerprint`).
//!
//! Not a cryptographic hash: it guards against corruption and against resuming from the
//! wrong case, not against forgery. Each byte does `h = (h ⊕ b) · p mod 2⁶⁴`; with p odd
//! both operations are bijections of the state, so two inputs of the same length that
//! differ in a single byte (one flipped bit, say) always hash differently.

/// An FNV-1a hash being accumulated.
#[derive(Clone, Copy, Debug)]
pub struct Fnv64(u64);

const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
const PRIME: u64 = 0x0000_0100_0000_01b3;

impl Default for Fnv64 {
    fn default() -> Self {
        Self::new()
    }
}

impl Fnv64 {
    /// The empty hash (the offset basis).
    pub fn new() -> Self {
        Fnv64(OFFSET_BASIS)
    }

    /// Hash `bytes` in.
    #[inline]
    pub fn update(&mut self, bytes: &[u8]) {
        let mut h = self.0;
        for &b in bytes {
            h = (h ^ b as u64).wrapping_mul(PRIME);
        }
        self.0 = h;
    }

    /// Hash a `u64` in (little-endian bytes).
    pub fn u64(&mut self, x: u64) {
        self.update(&x.to_le_bytes());
    }

    /// Hash a string in, prefixed by its length (so that "ab","c" ≠ "a","bc").
    pub fn str(&mut self, s: &str) {
        self.u64(s.len() as u64);
        self.update(s.as_bytes());
    }

    /// The hash so far.
    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// FNV-1a of `bytes`.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h = Fnv64::new();
    h.update(bytes);
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference values of the FNV-1a 64 test suite (Noll's `test_fnv.c`).
    #[test]
    fn published_test_vectors() {
        assert_eq!(fnv1a64(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a64(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
    }

    #[test]
    fn incremental_equals_one_shot() {
        let mut h = Fnv64::new();
        h.update(b"foo");
        h.update(b"bar");
        assert_eq!(h.finish(), fnv1a64(b"foobar"));
    }
}
