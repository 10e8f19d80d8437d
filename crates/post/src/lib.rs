#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! **Tone mapping** (the Serenity thesis, sections 3.4.2 and 3.4.3; the sRGB encoding,
//! 3.5.1): Reinhard's global operator (Reinhard, Stark, Shirley, Ferwerda, "Photographic tone reproduction for digital images",
//! SIGGRAPH 2002). The frame's log-average luminance `exp(mean(ln(delta + L)))` (with their
//! small `delta`, [`LOG_DELTA`], so that black pixels do not send it to zero) is the scene's
//! key; the eye adapts towards it over frames (`a += (target - a) (1 - exp(-dt rate))`,
//! [`ToneMapper::adapt`]); each pixel's luminance, scaled by `key / adapted`, goes through
//! `L / (1 + L)` with the colour ratio kept, and the result is sRGB-encoded to 8 bits
//! ([`ToneMapper::map`], [`linear_to_srgb`]). Non-finite and negative values are treated as
//! black and left out of the average. `gpu::ToneMapPass` does the same on the GPU:
//! the average reduced in 64 workgroups, the adapted luminance kept in a GPU buffer from frame
//! to frame (nothing is read back), the display image written to an RGBA8 texture it owns.
//!
//! **Still-view accumulation**: a renderer that shades one point per pixel aliases geometry
//! and highlights narrower than a pixel, where a pixel of the truth integrates its whole area.
//! While the view stands still, each frame moves the projection by a sub-pixel offset
//! ([`frame_jitter`]: a Halton (2, 3) sequence, shifted so that the first sample is the
//! pixel's centre) and the frames are averaged with the running-mean weight `1 / k`
//! ([`weight`]; [`Accumulator`] on the CPU, `gpu::AccumulatePass` as a blend on the GPU):
//! after `n` samples each pixel holds the mean of `n` points spread over its area, the box
//! filter a reference path tracer's pixels apply. This is the still-camera half of temporal
//! anti-aliasing: nothing is reprojected, so a moving camera gets no anti-aliasing and no
//! ghosts. A view's first frame (still sample 0) is meant to be shown alone, not averaged
//! (its G-buffer may widen specular lobes by the whole pixel's normal variance); samples
//! `1..=n` are the average's ([`average_index`], [`last_sample`]).
//!
//! What accumulation buys, measured: `docs/measured.md`.

mod accumulate;
mod error;
mod tonemap;

#[cfg(feature = "gpu")]
pub mod gpu;

pub use accumulate::{Accumulator, average_index, frame_jitter, jitter, last_sample, weight};
pub use error::PostError;
pub use tonemap::{Exposure, LOG_DELTA, ToneMapper, linear_to_srgb, log_average, luminance};
