#![doc = include_str!("../README.md")]
//!
//! ## Contents
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
//! 2. **Near-singularity** (Dachsbacher & Stamminger's fix, as the seed thesis
//!    describes it in 3.3.2.1): where two walls meet, `1/r^4`
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
//!    pattern cancels exactly (a Gaussian left a residue; the figures in `docs/measured.md`
//!    were taken with it).
//! 5. **Low resolution** (`low_res` 2 or 4, the seed thesis's 512x512 indirect
//!    buffer, 4.1.1): evaluate
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
//! What the sweep measured when each choice was made (the energy of interleaved splatting,
//! the speed-up of interleaving, the light that leaks through walls, the sample pattern's
//! luck, `r_max`): `docs/measured.md`.

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
