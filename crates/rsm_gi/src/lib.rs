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
//!    around it, with the point-to-point form factor [`vpl_irradiance`]. Offsets are the
//!    paper's polar pattern (density compensated: weight `2 pi xi1`) or a Poisson disk
//!    ([`Sampling`], [`samples`]); each sample stands for the texels around it, so the sum
//!    is an unbiased estimate of the whole disc's.
//! 2. **Near-singularity** (the paper's fix, section 4): where two walls meet, `1/r^4`
//!    explodes; every VPL is moved `vpl_offset` against its normal before it lights
//!    anything, which also stops a texel from lighting its own plane. Since nothing is
//!    occluded, the move has no other cost (thin objects may light their far side).
//! 3. **Splat** ([`RsmGi::splat`]): `vpls` VPLs chosen from the RSM with probability
//!    proportional to their flux ([`RsmGi::splat_vpls`], flux divided by the probability), each
//!    added to the pixels within `splat_radius` of it, found through its projected box.
//! 4. **Interleaving** ([`Interleave`]: 2x2, 2x4, 4x4, 8x8): pixel `(x, y)` uses only
//!    sub-buffer `(x mod N, y mod M)`'s share of the VPLs; the gather swizzles the
//!    G-buffer into the `N M` sub-buffer tiles, shades each with its subset and swizzles
//!    back; a separable geometry-aware Gaussian (depth and normal, radius `N` along x and
//!    `M` along y, stopping at a discontinuity) spreads the result over the pattern.
//! 5. **Low resolution** (`low_res` 2 or 4, the seed's smaller indirect buffer): evaluate
//!    every `f`-th pixel, upsample with geometry-aware bilinear weights, and evaluate the
//!    pixels no coarse neighbour fits at full resolution.
//!
//! Non-finite pixels and texels are skipped and counted in [`Stats`], never propagated;
//! sizes and settings are checked ([`RsmGiError`]). The CPU path is rayon over rows, and
//! deterministic (no reduction depends on the thread count).
//!
//! **The energy question** (seed §5.2: interleaved SII's error grows with the VPL count,
//! "each pixel receives about 1/(N M) of every VPL"). See `benches/gi_sweep.rs` and the
//! figures below: splatting each sub-buffer's VPLs at their plain flux leaves the image
//! at `1/(N M)` of the right level after the blur (an error that tends to `1 - 1/(N M)` as
//! the VPL count grows, exactly the seed's trend); scaling them by `N M`
//! (`splat_energy_scale`, the default) makes each sub-buffer an unbiased estimate.
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
pub use input::{GBuffer, RsmInput, RsmProjection, Stats, vpl_irradiance};
pub use interleave::Interleave;
pub use pattern::{Sample, samples};
pub use pipeline::{Output, RsmGi};
pub use settings::{Sampling, Settings};
pub use splat::SplatVpl;
