//! A small deterministic generator for the unit tests' random inputs (64-bit LCG with
//! Knuth's MMIX constants, the top 53 bits as a uniform number in [0, 1)): the same
//! sequence on every machine, no dependency.

/// Uniform numbers in [0, 1) from `seed`.
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next number in [−1, 1).
    pub fn sym(&mut self) -> f64 {
        2.0 * self.next() - 1.0
    }
}
