//! Where a second sampling stage goes, and how many samples each pixel gets
//! ([`crate::Renderer::refine`]).
//!
//! Most of an image converges at one rate, but a few pixels hold light that samples find
//! rarely: the sun's reflection in a smooth mirror is a dot far smaller than a pixel (on the
//! city's chrome statue at 320x180, one sample in 500 to 5000 lands in it, each worth some
//! 10 000 times the pixels around it), and those pixels hold nearly all of the image's
//! squared error. More samples everywhere pay for every pixel to fix a few; refinement gives
//! the few what they need:
//!
//! - **The precision target.** A block of 8 x 8 pixels needs refining when its relative
//!   error, `sum se / sum mean` in luminance, is above [`Refinement::target`]. Its noisiest
//!   pixels are refined, as many as it takes for the others to hold half the block's
//!   allowed error, and each of them is given an equal share of the other half: its new
//!   sample count is what its per-sample deviation `sigma` says that share needs,
//!   `(sigma / share)^2`, rounded up to a power of two times the first stage's count (so
//!   the pixel's points stay a whole (0,2)-net), at least [`Refinement::min_factor`] and at
//!   most [`Refinement::max_factor`] times it. The neediest blocks go first while the
//!   round's budget lasts.
//! - **Glints the first stage never saw.** A glint found by no sample leaves a pixel that
//!   looks converged. Before the first round, a deterministic probe ([`glint_pixels`])
//!   traces a 4 x 4 grid of rays through each pixel, follows them through up to
//!   [`GLINT_BOUNCES`] mirror or glass reflections, and marks the pixel when the sun's disk
//!   lies within the spread of the directions they leave in: those pixels get
//!   `min_factor` times the samples even when their variance is zero.
//! - **Which errors.** The standard errors are the batch means' ([`crate::BatchMoments`]),
//!   honest on pixels an edge crosses; the samples' own spread, several times too large
//!   there (the sub-pixel positions are stratified), would spend the budget on emitters'
//!   outlines and silhouettes against the sky. `sigma` is the standard error times the
//!   square root of the samples: with stratification the error falls faster than that
//!   predicts, so the counts it asks for err on the generous side.
//! - **Rounds.** The glints' own variance is known only once they have been found, so
//!   [`Refinement::rounds`] rounds run, each choosing from the estimates the last left.
//!
//! Every choice depends only on earlier samples and on the probe, and every chosen pixel's
//! new samples come from streams of their own and **replace** its earlier ones, so each
//! pixel's final estimate is an unbiased mean of samples whose number was fixed before they
//! were drawn.
//!
//! **Measured** (the city at 320x180, caustic photons on, seeds 1 and 2, 2 cores idle;
//! `cargo run --release -p serein-reference --example caustics -- --spp 1024 --refine`):
//!
//! | | 1024 spp | 1024 spp + [`Refinement::DEFAULT`] |
//! |---|---|---|
//! | time per render | 84-102 s | 113-116 s (the second stage 25-29 s) |
//! | samples | 1024 spp | 24% more: 223-243 pixels, two glints at the cap of 2^20 |
//! | mean relative standard error | 0.025-0.029 | 0.016 |
//! | worst 8 x 8 block | 0.46-0.59 | 0.089-0.093 |
//! | relative RMS between the two renders | 0.69 | 0.040 |
//!
//! Without refinement, two pixels of the statue's glints held 99.9% of the squared
//! difference between the renders (means 2.3 and 14.8 in one, 30 and 17.5 in the other).

use crate::camera::Camera;
use crate::integrator::facing;
use crate::sampling::{luminance, reflect};
use crate::world::World;
use crate::{Error, Estimate};

/// Mirror or glass reflections the glint probe follows from the eye.
pub const GLINT_BOUNCES: u32 = 3;

/// Rays per pixel side of the glint probe.
const PROBE: u32 = 4;

/// Edge of the blocks whose relative error the target holds.
const BLOCK: u32 = 8;

/// Settings of [`crate::Renderer::refine`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refinement {
    /// Largest relative standard error of an 8 x 8 block (`sum se / sum mean`, luminance).
    pub target: f32,
    /// Extra samples per round, as a share of the first stage's.
    pub budget: f32,
    /// Fewest samples of a refined pixel, in multiples of the first stage's (a power of two).
    pub min_factor: u32,
    /// Most samples of a refined pixel, in multiples of the first stage's (a power of two).
    pub max_factor: u32,
    /// Samples of a pixel the glint probe marked, in multiples of the first stage's (a power
    /// of two), at least: a glint too faint for the first stage to see may also hide from
    /// `min_factor` times its samples, and then looks converged to every later round.
    pub glint_factor: u32,
    /// Rounds of refinement (each chooses from the estimates the last one left).
    pub rounds: u32,
    /// Runs the glint probe before the first round.
    pub glint_probe: bool,
}

impl Refinement {
    /// Blocks within 8% (the report holds a whole image's worst block to 10%), three rounds
    /// of at most half the first stage's samples each, refined pixels at 16 to 1024 times
    /// the first stage's samples (64 where the glint probe marked them).
    pub const DEFAULT: Self = Self {
        target: 0.08,
        budget: 0.5,
        min_factor: 16,
        max_factor: 1024,
        glint_factor: 64,
        rounds: 3,
        glint_probe: true,
    };

    pub fn validate(&self) -> Result<(), Error> {
        let bad = |what: String| Err(Error::InvalidSettings(format!("refinement {what}")));
        if !(self.target > 0.0 && self.target.is_finite()) {
            return bad(format!("target {} (a relative error > 0)", self.target));
        }
        if !(self.budget > 0.0 && self.budget <= 64.0) {
            return bad(format!("budget {} (a share of the first stage in (0, 64])", self.budget));
        }
        let factor_ok = |f: u32| f.is_power_of_two() && (2..=1 << 20).contains(&f);
        let (lo, hi, glint) = (self.min_factor, self.max_factor, self.glint_factor);
        if !factor_ok(lo) || !factor_ok(hi) || !factor_ok(glint) || lo > hi || glint > hi {
            return bad(format!(
                "factors {lo}..{hi}, glints {glint} (powers of two from 2 to 2^20, min <= \
                 glints <= max)"
            ));
        }
        if !(1..=8).contains(&self.rounds) {
            return bad(format!("rounds {} (1 to 8)", self.rounds));
        }
        Ok(())
    }

    /// The pixels of a `width x height` image to refine and their new sample counts,
    /// neediest block first, from the `estimates` so far (first stage: `base` samples per
    /// pixel) and the pixels the glint probe marked (`glints`, ascending).
    pub fn select(
        &self,
        estimates: &[Estimate],
        (width, height): (u32, u32),
        base: u32,
        glints: &[u32],
    ) -> Vec<(u32, u32)> {
        let (lo, hi) = (base as u64 * self.min_factor as u64, base as u64 * self.max_factor as u64);
        let glint_n = lo.max(base as u64 * self.glint_factor as u64);
        let se = |p: u32| luminance(estimates[p as usize].std_error) as f64;
        // (need of the block, pixel, samples)
        let mut needy: Vec<(f64, u32, u32)> = Vec::new();
        for by in (0..height).step_by(BLOCK as usize) {
            for bx in (0..width).step_by(BLOCK as usize) {
                let mut members: Vec<u32> = (by..(by + BLOCK).min(height))
                    .flat_map(|y| (bx..(bx + BLOCK).min(width)).map(move |x| y * width + x))
                    .collect();
                let light: f64 =
                    members.iter().map(|&p| luminance(estimates[p as usize].mean) as f64).sum();
                let total: f64 = members.iter().map(|&p| se(p)).sum();
                let limit = self.target as f64 * light;
                let need = if limit > 0.0 { total / limit } else { 0.0 };
                // The noisiest pixels until the rest hold half the limit; each of them is
                // then given a share of the other half.
                members.sort_by(|&a, &b| se(b).total_cmp(&se(a)).then(a.cmp(&b)));
                let mut k = 0;
                if need > 1.0 && need.is_finite() {
                    let mut rest = total;
                    while k < members.len() && rest > 0.5 * limit {
                        rest -= se(members[k]);
                        k += 1;
                    }
                }
                let allowed = 0.5 * limit / k.max(1) as f64;
                for (i, &p) in members.iter().enumerate() {
                    let e = &estimates[p as usize];
                    let glint = e.samples == base && glints.binary_search(&p).is_ok();
                    if i >= k && !glint {
                        continue;
                    }
                    let sigma = se(p) * (e.samples as f64).sqrt();
                    let wanted = if i < k { (sigma / allowed).powi(2).ceil() } else { 0.0 };
                    let mut n = if glint { glint_n } else { lo };
                    while (n as f64) < wanted && n < hi {
                        n *= 2;
                    }
                    // A count a pixel's moments can hold (u32), whatever the first stage.
                    let n = n.min(1 << 31);
                    if n > e.samples as u64 {
                        let need = if need.is_finite() { need.max(1.0) } else { 1.0 };
                        needy.push((need, p, n as u32));
                    }
                }
            }
        }
        needy.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let mut left = self.budget as f64 * base as f64 * estimates.len() as f64;
        let mut chosen = Vec::new();
        for (_, p, n) in needy {
            if (n as f64) <= left {
                left -= n as f64;
                chosen.push((p, n));
            }
        }
        chosen
    }
}

impl Default for Refinement {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Pixels (ascending) of a `width x height` image from `camera` where the sun's disk may
/// show in a mirror or glass reflection: a 4 x 4 grid of rays per pixel follows up to
/// [`GLINT_BOUNCES`] reflections off surfaces with a mirror or glass part (the shading
/// normal's mirror direction); the pixel is marked when a ray leaves the world within the
/// sun's angular radius plus the largest angle between the leaving directions of
/// neighbouring grid rays (so a disk between the grid's directions is caught).
pub fn glint_pixels(world: &World, camera: &Camera, width: u32, height: u32) -> Vec<u32> {
    use rayon::prelude::*;
    let Some(sun) = world.sun() else { return Vec::new() };
    let camera = crate::camera::for_image(camera, width, height);
    let leaving = |x: f32, y: f32| -> Option<glam::Vec3> {
        let mut origin = camera.position;
        let mut dir = camera.pixel_direction(x, y, width, height);
        for bounce in 0..=GLINT_BOUNCES {
            let Some(mut h) = world.intersect(origin, dir, f32::INFINITY) else {
                return (bounce > 0).then_some(dir);
            };
            if bounce == GLINT_BOUNCES || !world.shade(&mut h).has_delta() {
                return None;
            }
            let (n, _) = facing(&h, -dir);
            dir = reflect(dir, n);
            origin = world.offset(h.position, h.normal, dir);
        }
        None
    };
    (0..width * height)
        .into_par_iter()
        .filter(|&p| {
            let (px, py) = ((p % width) as f32, (p / width) as f32);
            let grid: Vec<Option<glam::Vec3>> = (0..PROBE * PROBE)
                .map(|k| {
                    let (i, j) = ((k % PROBE) as f32 + 0.5, (k / PROBE) as f32 + 0.5);
                    leaving(px + i / PROBE as f32, py + j / PROBE as f32)
                })
                .collect();
            let mut spread = 0.0f32;
            for k in 0..(PROBE * PROBE) as usize {
                let (i, j) = (k as u32 % PROBE, k as u32 / PROBE);
                let right = (i + 1 < PROBE).then(|| k + 1);
                let down = (j + 1 < PROBE).then(|| k + PROBE as usize);
                for o in [right, down].into_iter().flatten() {
                    if let (Some(a), Some(b)) = (grid[k], grid[o]) {
                        spread = spread.max(a.dot(b).clamp(-1.0, 1.0).acos());
                    }
                }
            }
            let reach = sun.angular_radius + spread;
            grid.iter().flatten().any(|d| d.dot(sun.direction).clamp(-1.0, 1.0).acos() <= reach)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn est(mean: f32, se: f32, samples: u32) -> Estimate {
        Estimate { mean: Vec3::splat(mean), std_error: Vec3::splat(se), samples }
    }

    #[test]
    fn selects_what_the_target_needs_neediest_block_first_within_the_budget() {
        // A 16 x 8 image (two blocks), every pixel of mean 1 (block light 64), 16 samples;
        // target 0.1: a block may hold a summed error of 6.4.
        let r = Refinement {
            target: 0.1,
            budget: 4.0,
            min_factor: 2,
            max_factor: 64,
            glint_factor: 4,
            ..Refinement::DEFAULT
        };
        let mut e = vec![est(1.0, 0.01, 16); 128];
        // Block 1 (x 8..16): one pixel of se 6.4 (sum 7.03 > 6.4): alone it is refined to
        // half the limit, 3.2: sigma 25.6 wants (25.6 / 3.2)^2 = 64 samples.
        e[9] = est(1.0, 6.4, 16);
        // Block 0: two pixels of se 32 (sum 64.6, need 10): both, each to 1.6: sigma 128
        // wants 6400 -> capped at 64 x 16 = 1024.
        e[70] = est(1.0, 32.0, 16);
        e[71] = est(1.0, 32.0, 16);
        // Converged, in a block within the target, but marked by the probe: the glint
        // factor.
        let glints = [3u32];
        let chosen = r.select(&e, (16, 8), 16, &glints);
        assert_eq!(chosen, vec![(3, 64), (70, 1024), (71, 1024), (9, 64)]);
        // A budget for fewer samples keeps the neediest that fit.
        let small = Refinement { budget: 100.0 / (16.0 * 128.0), ..r };
        assert_eq!(small.select(&e, (16, 8), 16, &glints), vec![(3, 64)]);
        // A block within the target refines nothing; a probe's pixel that already holds
        // more than the first stage is left.
        e[9] = est(1.0, 5.0, 16);
        e[3] = est(1.0, 0.01, 256);
        assert_eq!(r.select(&e, (16, 8), 16, &glints), vec![(70, 1024), (71, 1024)]);
    }

    #[test]
    fn invalid_settings_are_typed_errors() {
        let d = Refinement::DEFAULT;
        for r in [
            Refinement { target: 0.0, ..d },
            Refinement { target: f32::NAN, ..d },
            Refinement { budget: 0.0, ..d },
            Refinement { min_factor: 3, ..d },
            Refinement { min_factor: 64, max_factor: 32, ..d },
            Refinement { glint_factor: 2048, ..d },
            Refinement { rounds: 0, ..d },
        ] {
            assert!(matches!(r.validate(), Err(Error::InvalidSettings(_))), "{r:?}");
        }
        assert!(d.validate().is_ok());
    }
}
