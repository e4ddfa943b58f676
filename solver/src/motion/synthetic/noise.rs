//! Portable Gaussian white noise: ChaCha20 (rand_chacha, RFC 7539 block function with a
//! 64-bit stream id) keyed by the seed, one stream per component, turned into standard
//! normal numbers by the Box–Muller transform (Box & Muller 1958) with libm's logarithm,
//! sine and cosine — pure Rust ports of musl's, so the same bits on every platform. The
//! key is the seed's 8 little-endian bytes followed by 24 zero bytes (no seed expansion
//! whose algorithm could change between library versions).

use rand_chacha::ChaCha20Rng;
use rand_core::{Rng, SeedableRng};

/// A reproducible stream of standard normal numbers.
pub struct GaussianStream {
    rng: ChaCha20Rng,
    spare: Option<f64>,
}

impl GaussianStream {
    /// The stream `stream` (component index) of seed `seed`.
    pub fn new(seed: u64, stream: u64) -> Self {
        let mut key = [0u8; 32];
        key[..8].copy_from_slice(&seed.to_le_bytes());
        let mut rng = ChaCha20Rng::from_seed(key);
        rng.set_stream(stream);
        Self { rng, spare: None }
    }

    /// Uniform in (0, 1]: the top 53 bits of a 64-bit word, plus one ulp-step, over 2⁵³.
    fn uniform_open0(&mut self) -> f64 {
        ((self.rng.next_u64() >> 11) + 1) as f64 * (1.0 / 9_007_199_254_740_992.0)
    }

    /// The next standard normal number.
    pub fn next_normal(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        let u1 = self.uniform_open0();
        let u2 = self.uniform_open0();
        let r = libm::sqrt(-2.0 * libm::log(u1));
        let theta = 2.0 * std::f64::consts::PI * u2;
        self.spare = Some(r * libm::sin(theta));
        r * libm::cos(theta)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_normal_moments() {
        let mut g = GaussianStream::new(42, 0);
        let n = 200_000;
        let (mut s1, mut s2) = (0.0, 0.0);
        for _ in 0..n {
            let z = g.next_normal();
            s1 += z;
            s2 += z * z;
        }
        let mean = s1 / n as f64;
        let var = s2 / n as f64 - mean * mean;
        assert!(
            mean.abs() < 0.01 && (var - 1.0).abs() < 0.01,
            "{mean} {var}"
        );
        // Different streams differ.
        assert_ne!(
            GaussianStream::new(42, 0).next_normal(),
            GaussianStream::new(42, 1).next_normal()
        );
    }
}
