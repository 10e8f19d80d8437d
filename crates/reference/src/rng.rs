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

/// Sub-pixel position of sample `k` of pixel `pixel`: sample `k` belongs to batch
/// `b = k % BATCHES` ([`crate::stats::BATCHES`]) and is point `k / BATCHES` of the
/// (0,2)-sequence (van der Corput in x, Sobol's second dimension in y; every run of `2^m`
/// consecutive points from a multiple of `2^m` puts one point in each of the `2^m`
/// elementary intervals of the pixel), shifted by a random offset of its own for each
/// `(pixel, batch)` (Cranley-Patterson rotation): each batch is stratified over the pixel by
/// itself and independent of the others, so the spread of the batch means measures the
/// error (see [`crate::PixelSums`]), and neighbouring pixels do not share a pattern.
/// Stratifying the pixel matters where a pixel holds an edge or a highlight smaller than
/// itself (the sun's highlight on chrome): the error falls faster than with independent
/// jitter. Depends only on `(seed, pixel, k)`.
pub fn pixel_jitter(seed: u64, pixel: u64, k: u64) -> (f32, f32) {
    let batches = crate::stats::BATCHES as u64;
    let batch = k % batches;
    let mut shift = Rng::for_sample(seed ^ 0x0F1E_2D3C_4B5A_6978, pixel, u64::MAX - batch);
    let (sx, sy) = shift.next_2d();
    let (x, y) = sobol_02((k / batches) as u32);
    let wrap = |v: f32| if v >= 1.0 { v - 1.0 } else { v };
    (wrap(x + sx), wrap(y + sy))
}

/// Point `k` of the (0,2)-sequence in base 2, in `[0, 1)²` (24-bit precision).
fn sobol_02(k: u32) -> (f32, f32) {
    let x = k.reverse_bits();
    let (mut y, mut v, mut i) = (0u32, 1u32 << 31, k);
    while i != 0 {
        if i & 1 != 0 {
            y ^= v;
        }
        i >>= 1;
        v ^= v >> 1;
    }
    let unit = |b: u32| (b >> 8) as f32 * (1.0 / 16_777_216.0);
    (unit(x), unit(y))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The (0,2) property: every `2^m` points from a multiple of `2^m` fill each elementary
    /// interval `2^-a x 2^-(m-a)` exactly once.
    #[test]
    fn sobol_points_are_a_0_2_sequence() {
        for m in 0..=8u32 {
            for start in [0u32, 1 << m, 5 << m] {
                for a in 0..=m {
                    let mut seen = vec![false; 1 << m];
                    for k in start..start + (1 << m) {
                        let (x, y) = sobol_02(k);
                        let (ix, iy) =
                            ((x * (1 << a) as f32) as u32, (y * (1 << (m - a)) as f32) as u32);
                        let cell = (iy << a | ix) as usize;
                        assert!(!seen[cell], "m {m} a {a} start {start}: cell {cell} twice");
                        seen[cell] = true;
                    }
                }
            }
        }
    }

    #[test]
    fn pixel_jitter_is_in_the_pixel_and_per_pixel() {
        for k in 0..64 {
            let (x, y) = pixel_jitter(7, 3, k);
            assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
        }
        assert_ne!(pixel_jitter(7, 3, 0), pixel_jitter(7, 4, 0));
        assert_eq!(pixel_jitter(7, 3, 5), pixel_jitter(7, 3, 5));
    }

    /// Each batch is its own shifted (0,2)-sequence: the x of a batch's first `2^m` points
    /// lie exactly `2^-m` apart (modulo 1), and batches are shifted apart.
    #[test]
    fn each_batch_is_a_stratified_sequence_of_its_own() {
        let batches = crate::stats::BATCHES as u64;
        let m = 4;
        let mut firsts = Vec::new();
        for b in 0..batches {
            let mut xs: Vec<f32> =
                (0..1u64 << m).map(|j| pixel_jitter(7, 3, b + j * batches).0).collect();
            firsts.push(xs[0]);
            xs.sort_by(f32::total_cmp);
            let gaps = xs.windows(2).map(|w| w[1] - w[0]).chain([xs[0] + 1.0 - xs[xs.len() - 1]]);
            for g in gaps {
                assert!((g - 1.0 / (1 << m) as f32).abs() < 1e-5, "batch {b}: gap {g}");
            }
        }
        firsts.sort_by(f32::total_cmp);
        firsts.dedup();
        assert_eq!(firsts.len(), batches as usize, "batches share a shift");
    }

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
