//! Filter tap patterns on the unit disk: a golden-angle spiral (Vogel) and Poisson-disk
//! sets built by best-candidate sampling from a fixed seed, so both are deterministic and
//! can be uploaded to the GPU unchanged.

use glam::Vec2;

/// Which point set a filter uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TapPattern {
    /// Golden-angle spiral: `r = sqrt((i + 0.5) / n)`, `phi = i * 2.39996`.
    Spiral,
    /// Poisson disk (best candidate, 16 candidates per point, fixed seed).
    Poisson,
}

/// `n` points in the unit disk (`n` may be any count; 8/16/32/64 are the usual ones).
pub fn taps(pattern: TapPattern, n: usize) -> Vec<Vec2> {
    match pattern {
        TapPattern::Spiral => spiral(n),
        TapPattern::Poisson => poisson(n),
    }
}

fn spiral(n: usize) -> Vec<Vec2> {
    let golden = std::f64::consts::PI * (3.0 - 5.0f64.sqrt());
    (0..n)
        .map(|i| {
            let r = ((i as f64 + 0.5) / n as f64).sqrt();
            let phi = i as f64 * golden;
            Vec2::new((r * phi.cos()) as f32, (r * phi.sin()) as f32)
        })
        .collect()
}

/// SplitMix64: a tiny deterministic generator (no dependency for a fixed table).
struct SplitMix(u64);
impl SplitMix {
    fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
    fn in_disk(&mut self) -> (f64, f64) {
        loop {
            let x = self.next_f64() * 2.0 - 1.0;
            let y = self.next_f64() * 2.0 - 1.0;
            if x * x + y * y <= 1.0 {
                return (x, y);
            }
        }
    }
}

fn poisson(n: usize) -> Vec<Vec2> {
    let mut rng = SplitMix(0x5EED_0000 + n as u64);
    let mut pts: Vec<(f64, f64)> = Vec::with_capacity(n);
    for _ in 0..n {
        let mut best = (0.0, 0.0);
        let mut best_d = -1.0;
        for _ in 0..16 {
            let c = rng.in_disk();
            let d = pts
                .iter()
                .map(|p| (p.0 - c.0).powi(2) + (p.1 - c.1).powi(2))
                .fold(f64::INFINITY, f64::min);
            if d > best_d {
                best_d = d;
                best = c;
            }
        }
        pts.push(best);
    }
    pts.into_iter().map(|(x, y)| Vec2::new(x as f32, y as f32)).collect()
}
