//! Deterministic random numbers: a PCG32 stream per (seed, pixel or point, sample).

/// PCG-XSH-RR 32-bit generator (M. E. O'Neill, "PCG: A Family of Simple Fast Space-Efficient
/// Statistically Good Algorithms for Random Number Generation", 2014).
#[derive(Clone, Debug)]
pub struct Rng {
    state: u64,
    inc: u64,
}

const MULT: u64 = 6_364_136_223_846_793_005;

/// SplitMix64 finaliser: decorrelates neighbouring keys.
pub(crate) const fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Rng {
    /// A generator for one `(seed, index, sample)` key: the same key always gives the same
    /// stream, whatever thread evaluates it.
    pub fn for_sample(seed: u64, index: u64, sample: u64) -> Self {
        let a = mix64(seed ^ mix64(index.wrapping_add(0x5851_F42D_4C95_7F2D)));
        let b = mix64(a ^ sample.wrapping_mul(0x2545_F491_4F6C_DD1D));
        let mut r = Self { state: 0, inc: (mix64(b ^ 0xDA3E_39CB_94B9_5BDB) << 1) | 1 };
        r.next_u32();
        r.state = r.state.wrapping_add(b);
        r.next_u32();
        r
    }

    /// Next 32 random bits.
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(MULT).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in `[0, 1)`.
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// Two uniforms in `[0, 1)`.
    pub fn next_2d(&mut self) -> (f32, f32) {
        (self.next_f32(), self.next_f32())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_key_same_stream_and_uniform_mean() {
        let mut a = Rng::for_sample(1, 2, 3);
        let mut b = Rng::for_sample(1, 2, 3);
        assert_eq!(a.next_u32(), b.next_u32());
        let mut c = Rng::for_sample(1, 2, 4);
        let n = 100_000;
        let mean: f64 = (0..n).map(|_| c.next_f32() as f64).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
    }
}
