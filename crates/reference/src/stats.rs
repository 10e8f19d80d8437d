//! Running mean and variance per value (f64), and the estimate with its standard error.

use glam::Vec3;

/// A Monte Carlo estimate: the mean and its standard error (per channel).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    pub mean: Vec3,
    /// Standard error of the mean, `sqrt(var / n)`.
    pub std_error: Vec3,
    /// Number of samples.
    pub samples: u32,
}

impl Estimate {
    /// True when `value` lies within `k` standard errors of the mean in every channel
    /// (plus an absolute `slack` for zero-variance estimates).
    pub fn agrees_with(&self, value: Vec3, k: f32, slack: f32) -> bool {
        ((self.mean - value).abs() - self.std_error * k).max_element() <= slack
    }
}

/// Sums of samples and of their squares.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Moments {
    pub sum: [f64; 3],
    pub sum_sq: [f64; 3],
    pub n: u32,
}

impl Moments {
    /// Adds one sample; non-finite samples count as zero (a path that went wrong carries no
    /// light rather than poisoning the image).
    pub fn add(&mut self, v: Vec3) {
        let v = if v.is_finite() { v } else { Vec3::ZERO };
        for c in 0..3 {
            let x = v[c] as f64;
            self.sum[c] += x;
            self.sum_sq[c] += x * x;
        }
        self.n += 1;
    }

    pub fn merge(&mut self, o: &Moments) {
        for c in 0..3 {
            self.sum[c] += o.sum[c];
            self.sum_sq[c] += o.sum_sq[c];
        }
        self.n += o.n;
    }

    pub fn estimate(&self) -> Estimate {
        if self.n == 0 {
            return Estimate::default();
        }
        let n = self.n as f64;
        let mut mean = Vec3::ZERO;
        let mut se = Vec3::ZERO;
        for c in 0..3 {
            let m = self.sum[c] / n;
            mean[c] = m as f32;
            if self.n > 1 {
                let var = ((self.sum_sq[c] - n * m * m) / (n - 1.0)).max(0.0);
                se[c] = (var / n).sqrt() as f32;
            }
        }
        Estimate { mean, std_error: se, samples: self.n }
    }
}

/// Independent batches a pixel's samples are split into ([`PixelSums`]): sample `k` of a
/// pixel belongs to batch `k % BATCHES` and is point `k / BATCHES` of that batch's own
/// randomly shifted (0,2)-sequence, so each batch is stratified over the pixel by itself and
/// the batches are independent of each other. The spread of the batch means is then an
/// honest measure of the error of their mean, where the spread of the samples is not: the
/// samples of one stratified sequence are not independent, and on a pixel an edge crosses
/// (an emitter's outline, a silhouette against the sky) their spread overstates the error
/// several-fold. Eight batches give the standard error 7 degrees of freedom (its own
/// relative uncertainty about 27%) at a cost of 8 x 24 bytes per pixel; at an edge the
/// eight sequences of `n / 8` points are about `8^(1/4) = 1.7` times as noisy as one of `n`.
pub const BATCHES: usize = 8;

/// One pixel's samples so far, by batch ([`BATCHES`]): the sums of samples `0..n`, sample
/// `k` in batch `k % BATCHES`. Accumulators of consecutive sample ranges [`PixelSums::merge`]
/// into one that again holds samples `0..n`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelSums {
    /// Samples so far.
    pub n: u32,
    /// Per batch and channel, the sum of the batch's samples.
    pub sums: [[f64; 3]; BATCHES],
}

impl Default for PixelSums {
    fn default() -> Self {
        Self { n: 0, sums: [[0.0; 3]; BATCHES] }
    }
}

impl PixelSums {
    /// Adds sample number `k`; non-finite samples count as zero (as in [`Moments::add`]).
    pub fn add(&mut self, k: u32, v: Vec3) {
        let v = if v.is_finite() { v } else { Vec3::ZERO };
        let s = &mut self.sums[k as usize % BATCHES];
        for (c, s) in s.iter_mut().enumerate() {
            *s += v[c] as f64;
        }
        self.n += 1;
    }

    /// Adds the samples of `o` (another range of the same pixel's samples).
    pub fn merge(&mut self, o: &PixelSums) {
        for (s, t) in self.sums.iter_mut().zip(&o.sums) {
            for c in 0..3 {
                s[c] += t[c];
            }
        }
        self.n += o.n;
    }

    /// Samples in batch `b` (of samples `0..n`).
    pub fn batch_samples(&self, b: usize) -> u32 {
        self.n / BATCHES as u32 + u32::from(b < self.n as usize % BATCHES)
    }

    /// The non-empty batches: their sample counts and means.
    pub fn batch_means(&self) -> Vec<(u32, Vec3)> {
        (0..BATCHES)
            .filter_map(|b| {
                let n = self.batch_samples(b);
                let s = self.sums[b];
                let m = |c: usize| (s[c] / n as f64) as f32;
                (n > 0).then(|| (n, Vec3::new(m(0), m(1), m(2))))
            })
            .collect()
    }

    /// The finished statistics ([`BatchMoments`]).
    pub fn moments(&self) -> BatchMoments {
        let mut m = BatchMoments::default();
        for b in 0..BATCHES {
            let n = self.batch_samples(b);
            if n == 0 {
                continue;
            }
            m.n += n as u64;
            m.batches += 1;
            for c in 0..3 {
                let s = self.sums[b][c];
                m.sum[c] += s;
                m.batch_sq[c] += s * s / n as f64;
            }
        }
        m
    }

    /// The estimate: the mean of all samples and the standard error from the batch means
    /// (see [`BatchMoments::estimate`]).
    pub fn estimate(&self) -> Estimate {
        self.moments().estimate()
    }
}

/// Independent batches' statistics of one pixel, in a form that adds up: renders of the
/// same pixel with different seeds (and so independent batches) [`BatchMoments::merge`]
/// into exactly the statistics of all their batches together.
///
/// With batches `b` of `n_b` samples summing to `S_b`, `N = sum n_b`, `S = sum S_b` and
/// `Q = sum S_b^2 / n_b`: the mean is `S / N` (the sample-count-weighted mean of the batch
/// means), and `sum n_b (m_b - m)^2 = Q - S^2 / N` over `K - 1` (`K` batches) estimates the
/// variance of one sample's worth of the batch means, so the standard error is
/// `sqrt((Q - S^2 / N) / ((K - 1) N))`: for `K` equal batches, the textbook
/// `sqrt(sum (m_b - m)^2 / (K (K - 1)))`; unbiased for batches of unequal size too when
/// samples are independent, and (their variance taken as falling like `1 / n_b`) an
/// approximation when batches of different sizes are stratified.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BatchMoments {
    /// Samples, `N`.
    pub n: u64,
    /// Non-empty batches, `K`.
    pub batches: u32,
    /// Per channel, the sum of all samples, `S`.
    pub sum: [f64; 3],
    /// Per channel, `Q = sum S_b^2 / n_b` over the batches.
    pub batch_sq: [f64; 3],
}

impl BatchMoments {
    /// Adds the batches of `o` (independent of this one's: another seed).
    pub fn merge(&mut self, o: &BatchMoments) {
        self.n += o.n;
        self.batches += o.batches;
        for c in 0..3 {
            self.sum[c] += o.sum[c];
            self.batch_sq[c] += o.batch_sq[c];
        }
    }

    /// True when every sum is finite (what a file read back must hold).
    pub fn is_finite(&self) -> bool {
        self.sum.iter().chain(&self.batch_sq).all(|v| v.is_finite())
    }

    /// The mean and its standard error (zero with fewer than two batches); the sample count
    /// saturates at `u32::MAX`.
    pub fn estimate(&self) -> Estimate {
        if self.n == 0 {
            return Estimate::default();
        }
        let n = self.n as f64;
        let mut mean = Vec3::ZERO;
        let mut se = Vec3::ZERO;
        for c in 0..3 {
            let m = self.sum[c] / n;
            mean[c] = m as f32;
            if self.batches > 1 {
                let spread = (self.batch_sq[c] - self.sum[c] * m).max(0.0);
                se[c] = (spread / ((self.batches - 1) as f64 * n)).sqrt() as f32;
            }
        }
        Estimate { mean, std_error: se, samples: self.n.min(u32::MAX as u64) as u32 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batches_take_samples_in_turn_and_their_spread_is_the_standard_error() {
        let mut s = PixelSums::default();
        // Batch b's samples are all b + 1: batch means 1..=8, 3 samples each.
        for k in 0..24 {
            s.add(k, Vec3::splat((k % 8 + 1) as f32));
        }
        let means = s.batch_means();
        assert_eq!(means.len(), BATCHES);
        for (b, (n, m)) in means.iter().enumerate() {
            assert_eq!((*n, *m), (3, Vec3::splat((b + 1) as f32)));
        }
        let e = s.estimate();
        assert_eq!(e.samples, 24);
        assert!((e.mean.x - 4.5).abs() < 1e-6);
        // Batch means 1..=8: sum (m - 4.5)^2 = 42, se = sqrt(42 / (8 * 7)).
        assert!((e.std_error.x as f64 - (42.0f64 / 56.0).sqrt()).abs() < 1e-6, "{e:?}");
        // Fewer samples than batches: one sample per batch, the samples' own spread.
        let mut t = PixelSums::default();
        for (k, v) in [1.0f32, 3.0, 5.0].into_iter().enumerate() {
            t.add(k as u32, Vec3::splat(v));
        }
        let e = t.estimate();
        assert_eq!(t.moments().batches, 3);
        assert!((e.std_error.x - (4.0f32 / 3.0).sqrt()).abs() < 1e-6, "{e:?}");
        // One sample: no error estimate; none: nothing.
        let mut one = PixelSums::default();
        one.add(0, Vec3::ONE);
        assert_eq!(one.estimate().std_error, Vec3::ZERO);
        assert_eq!(PixelSums::default().estimate(), Estimate::default());
    }

    #[test]
    fn consecutive_ranges_merge_into_the_whole() {
        let v = |k: u32| Vec3::new(k as f32, (k * k % 7) as f32, 1.0 / (k + 1) as f32);
        let mut whole = PixelSums::default();
        (0..37).for_each(|k| whole.add(k, v(k)));
        let (mut a, mut b) = (PixelSums::default(), PixelSums::default());
        (0..16).for_each(|k| a.add(k, v(k)));
        (16..37).for_each(|k| b.add(k, v(k)));
        a.merge(&b);
        assert_eq!(a.n, whole.n);
        let (ea, ew) = (a.estimate(), whole.estimate());
        assert!((ea.mean - ew.mean).abs().max_element() < 1e-6);
        assert!((ea.std_error - ew.std_error).abs().max_element() < 1e-6);
    }

    #[test]
    fn non_finite_samples_count_as_zero() {
        let mut s = PixelSums::default();
        s.add(0, Vec3::NAN);
        s.add(1, Vec3::splat(f32::INFINITY));
        s.add(2, Vec3::ONE);
        let e = s.estimate();
        assert!(e.mean.is_finite() && e.std_error.is_finite() && s.moments().is_finite());
        assert!((e.mean.x - 1.0 / 3.0).abs() < 1e-6);
    }
}
