//! One bounce of sunlight straight from a reflective shadow map: gathered (Dachsbacher &
//! Stamminger 2005, "Reflective Shadow Maps", I3D) or splatted (Dachsbacher & Stamminger
//! 2006, "Splatting Indirect Illumination", I3D), both with interleaved sampling (Keller &
//! Heidrich 2001, "Interleaved Sampling"; Segovia et al. 2006, "Non-interleaved Deferred
//! Shading of Interleaved Sample Patterns"), as the seed thesis combined them (Brink,
//! "Integrating Interleaved Sampling into Reflective Shadow Maps and Splatting Indirect
//! Illumination").
//!
//! Inputs are plain slices ([`RsmInput`]: flux, normal, position per RSM texel and the
//! RSM's [`RsmProjection`]; [`GBuffer`]: world position and normal per pixel and the
//! camera's `view_proj`), so the engine passes the sun RSM `shadows` renders and its own
//! G-buffer. Output: irradiance per pixel ([`Output`]), what the `reference` crate's
//! `SunIndirectDiffuse` computes.
//!
//! 1. **Gather** ([`RsmGi::gather`]): each pixel projects into the RSM and sums the VPLs
//!    of the texels at `vpls` offsets in a disc of `r_max` (fraction of the RSM width)
//!    around it, each texel a disc of its surface's area ([`vpl_irradiance_area`], the
//!    area from the map's orthographic footprint, [`RsmProjection::texel_footprint`]; the
//!    paper's point-to-point form factor [`vpl_irradiance`] where the projection gives no
//!    area, and for the splat's VPLs). Offsets are the
//!    paper's polar pattern (density compensated: weight `2 pi xi1`) or a Poisson disk
//!    ([`Sampling`], [`samples`]); each sample stands for the texels around it, so the sum
//!    is an unbiased estimate of the whole disc's.
//! 2. **Near-singularity** (the paper's fix, section 4): where two walls meet, `1/r^4`
//!    explodes; every VPL is moved `vpl_offset` against its normal before it lights
//!    anything, which also stops a texel from lighting its own plane. Since nothing is
//!    occluded, the move has no other cost (thin objects may light their far side). The
//!    disc form factor bounds what is left: a texel never lights a point more than its own
//!    radiosity does (in the engine, the point form made the 1024-VPL preset 5x too bright,
//!    its samples reaching the near texels the 512-VPL pattern skips).
//! 3. **Splat** ([`RsmGi::splat`]): `vpls` VPLs chosen from the RSM with probability
//!    proportional to their flux ([`RsmGi::splat_vpls`], flux divided by the probability), each
//!    added to the pixels within `splat_radius` of it, found through its projected box.
//! 4. **Interleaving** ([`Interleave`]: 2x2, 2x4, 4x4, 8x8): pixel `(x, y)` uses only
//!    sub-buffer `(x mod N, y mod M)`'s share of the VPLs; the gather swizzles the
//!    G-buffer into the `N M` sub-buffer tiles, shades each with its subset and swizzles
//!    back; a separable geometry-aware tent (depth and normal, half-width `N` along x and
//!    `M` along y, weights `1 - d / N`, stopping at a discontinuity) spreads the result over
//!    the pattern: on a flat surface every sub-buffer gets the same total weight, so the
//!    pattern cancels exactly (a Gaussian left a residue; the sweep figures below were taken
//!    with it).
//! 5. **Low resolution** (`low_res` 2 or 4, the seed's smaller indirect buffer): evaluate
//!    every `f`-th pixel, upsample with geometry-aware bilinear weights, and evaluate the
//!    pixels no coarse neighbour fits at full resolution.
//!
//! **GPU** (feature `gpu`, [`gpu`]): the gather, the blur and the upsampling, and the splat
//! (full resolution), resident and parity-tested against this CPU path on lavapipe.
//!
//! Non-finite pixels and texels are skipped and counted in [`Stats`], never propagated;
//! sizes and settings are checked ([`RsmGiError`]). The CPU path is rayon over rows, and
//! deterministic (no reduction depends on the thread count).
//!
//! **Measured** (`benches/gi_sweep.rs`, quick mode: 64 spp reference, 6 x 32² cube faces
//! per room, city 160x90; CPU path on 2 shared cores at load ~10, so times are rough and
//! the `*_vs_1x1` ratios, timed interleaved, are the figures to trust):
//! - **The energy question** (seed §5.2: interleaved SII's error grows with the VPL count
//!   because "each pixel receives about 1/(N M) of every VPL"). The explanation is right,
//!   exactly: on `two_rooms` at 1024 VPLs the best-fit scale of the unscaled interleaved
//!   splat against the truth is 3.64 / 7.25 / 14.8 / 59.3 for 2x2 / 2x4 / 4x4 / 8x8, i.e.
//!   `N M` times the scaled splat's (0.91..0.93), and its rel_rms is 0.80 / 0.90 / 0.95 /
//!   0.99 (tending to `1 - 1/(N M)`); scaling each sub-buffer's VPLs by `N M`
//!   (`splat_energy_scale`, the default) gives 0.49 / 0.50 / 0.49 / 0.53, the
//!   non-interleaved splat's 0.49. The seed measured interleaved against non-interleaved
//!   output, so the missing `(N M - 1) / (N M)` of the energy showed up as a difference that
//!   grows with the total flux it splats.
//! - **Interleaving** (gather, 1024 VPLs, vs the 1x1 gather of the same VPL count): 4x4 is
//!   10x / 6x / 13x faster on `cornell_window` / `two_rooms` / city at 0.87x / 1.06x /
//!   1.28x its error; 8x8 15x / 9x / 36x at 0.98x / 1.05x / 1.86x (the city's small
//!   features are where the blur over an 8x8 pattern costs accuracy).
//! - **Against the truth and the LPV on the same pixels** (rel_rms; lpv's best setting:
//!   geometry volume, 1.5-cell lookup offset): `two_rooms` gather 0.48..0.51 vs LPV 1.50;
//!   city 0.55 (2x2, 1024) / 0.82 (4x4, 1024) vs LPV 1.12; `cornell_window` 3.45 (default)
//!   vs LPV 1.16. RSM wins where the light it gathers is seen: no propagation blur, exact
//!   flux (best-fit scale near 1 on `two_rooms`, where the LPV's is 0.25).
//! - **Where it loses: light through walls.** The RSM has no occlusion. In
//!   `cornell_window`, 74% of the light the default gather collects comes through walls
//!   (the sunlit ground and outer walls seen through the closed box), and that is 98% of
//!   its squared error: the same gather keeping only the VPLs the path tracer says a pixel
//!   sees scores 0.51 (0.44x the LPV's best). On `two_rooms` the leak is 11% of the light
//!   and 7% of the squared error, on the city 8%. Removing it is the job of an occlusion
//!   structure (`radiance_cache`); [`RsmGi::gather_occluded`] measures it. The sweep races
//!   the radiance cache on the same pixels (quick run, idle, 8 converging updates): rel_rms
//!   0.56-0.68 on `cornell_window`, 0.52 on `two_rooms`, 0.48-0.60 on the city, the best of
//!   the four techniques on each (the report's race chart of this truth shows all of them).
//! - **The fixed pattern's luck.** Every pixel uses the same offsets, so the near field of
//!   the disc (the texels right beside a receiver, where a floor meets a wall) is sampled or
//!   missed coherently over the image. The uniform (Poisson) pattern misses it at 512 VPLs
//!   and finds it at 1024: in the engine, `cornell_window`'s bounce at 1024 VPLs is 12.9x the
//!   truth against 2.8x at 512; the polar pattern (dense near the centre) converges at any
//!   count, to 10.7-16.6x there: what the open gather converges to when the sunlit ground
//!   outside is in its disc. Each texel is a disc of its area ([`vpl_irradiance_area`]),
//!   which bounds a single texel's light but not this.
//! - `r_max` matters more than the pattern, and its best value depends on the scene's size
//!   against the RSM's: on `cornell_window` (Poisson, 4x4, 512 VPLs) 6.0 / 3.5 / 1.2 / 0.98
//!   at 0.1 / 0.3 / 0.6 / 1.0; with `r_max` 1 everywhere (a second run, 4x4 at 1024 VPLs)
//!   `cornell_window` 1.07 (leaks then 17% of the squared error, 0.90 with visibility),
//!   `two_rooms` 0.57, but the city 2.1 (its RSM spans 60 m: samples too sparse). The
//!   default keeps 0.3, the city's best. The polar pattern is noisier at every radius
//!   (10.5 / 10.8 / 8.8 / 4.8 on `cornell_window`): its density compensation gives rim
//!   samples large weights.
//! - City, scene camera at 320x180 (CPU, 2 threads, machine at load ~10): default 40 ms,
//!   `Settings::LOW` (half resolution) 18 ms in one run; 16 ms and 9.7 ms (with `r_max` 1)
//!   in another: about the 15 ms target, too noisy here to say more.
//!
//! ```
//! use glam::{Mat4, Vec3};
//! use rsm_gi::{GBuffer, RsmGi, RsmInput, RsmProjection, Settings};
//!
//! // A sunlit floor patch (8 x 8 texels of 1 W each) seen by an RSM looking straight down.
//! let (w, h) = (8u32, 8u32);
//! let position: Vec<Vec3> =
//!     (0..w * h).map(|i| Vec3::new((i % w) as f32 * 0.25, 0.0, (i / w) as f32 * 0.25)).collect();
//! let normal = vec![Vec3::Y; 64];
//! let flux = vec![Vec3::ONE; 64];
//! // World x, z in 0..2 m onto texels 0..8.
//! let projection = RsmProjection {
//!     world_to_texel: Mat4::from_cols_array(&[
//!         4.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 4.0, 0.0, 0.0, 0.5, 0.5, 0.0, 1.0,
//!     ]),
//! };
//! let rsm = RsmInput { width: w, height: h, flux: &flux, normal: &normal, position: &position, projection };
//! // A one-pixel G-buffer: a ceiling point 2 m above the patch, facing down.
//! let p = [Vec3::new(1.0, 2.0, 1.0)];
//! let n = [-Vec3::Y];
//! let view_proj = glam::camera::rh::proj::directx::perspective(1.0, 1.0, 0.1, 100.0)
//!     * glam::camera::rh::view::look_at_mat4(Vec3::new(1.0, 1.0, 1.0), p[0], Vec3::X);
//! let g = GBuffer { width: 1, height: 1, position: &p, normal: &n, view_proj };
//! let settings = Settings { r_max: 1.0, vpls: 256, ..Settings::REFERENCE };
//! let out = RsmGi::new(settings).unwrap().gather(&rsm, &g).unwrap();
//! // 64 W from about 2 m below: close to 64 / (pi 4) = 5.1 (a bit less: the patch is wide).
//! let e = out.irradiance[0].x;
//! assert!(e > 3.0 && e < 5.5, "{e}");
//! ```

mod error;
mod filter;
mod gather;
mod input;
mod interleave;
mod pattern;
mod pipeline;
mod settings;
mod splat;

#[cfg(feature = "gpu")]
pub mod gpu;

pub use error::RsmGiError;
pub use input::{
    GBuffer, MAX_TEXEL_STRETCH, RsmInput, RsmProjection, Stats, texel_area, vpl_irradiance,
    vpl_irradiance_area,
};
pub use interleave::Interleave;
pub use pattern::{Sample, samples};
pub use pipeline::{Output, RsmGi};
pub use settings::{Sampling, Settings};
pub use splat::SplatVpl;
