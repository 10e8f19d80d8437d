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
