//! Post-processing of an HDR renderer's frames: tone mapping with eye adaptation, and the
//! still-view anti-aliasing that averages jittered frames. CPU twins of everything, and behind
//! feature `gpu` the resident wgpu passes a renderer records every frame.
//!
//! **Tone mapping** (the Serenity thesis, section 3.7): Reinhard's global operator
//! (Reinhard, Stark, Shirley, Ferwerda, "Photographic tone reproduction for digital images",
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
//! What accumulation buys is measured by `benches/gi_sweep.rs` (`cargo xtask bench`): an
//! analytic image made to alias (a sharp, slightly rotated edge, wires a quarter of a pixel
//! wide, a grating finer than the pixels) is point-sampled at the crate's jitter offsets and
//! averaged by `gpu::AccumulatePass` (in the renderer's half-float target), against the
//! same image box-filtered with 1024 stratified samples per pixel. Entry
//! `post/accumulate_{n}spp` has the relative RMS error of the image after `n` samples
//! (`1`: the centre alone, the image without anti-aliasing) and, as its time, the
//! milliseconds one frame of the accumulation pass costs at 1600x900 (a full-screen blend;
//! the view reaches that error after `n` such frames, plus `n` frames of rendering). The
//! errors are 0.51, 0.24, 0.079 and 0.028 at 1, 4, 16 and 64 samples: they fall about as
//! `n^-0.75`, faster than the `n^-0.5` of independent random offsets, because the Halton
//! points stratify the pixel. `post/accumulate_f32_{n}spp` is the CPU twin's `f32` average
//! beside it: the half-float target costs nothing measurable up to 64 samples and 0.021
//! against 0.017 at 128. One frame of the pass is about 5 ms on lavapipe (2 cores: a CPU
//! figure, like the CPU twin's).
//!
//! ```
//! use post::{Accumulator, Exposure, ToneMapper, frame_jitter};
//! // Tone mapping: a bright sky over a dim ground, 4x2 pixels, shown as the first frame.
//! let sky = [[4.0, 4.0, 5.0, 1.0]; 4];
//! let ground = [[0.05, 0.04, 0.03, 1.0]; 4];
//! let hdr: Vec<[f32; 4]> = sky.into_iter().chain(ground).collect();
//! let mut eye = ToneMapper::default();
//! let first = Exposure { dt: 0.0, rate: 1.5, key: 0.18, reset: true, raw: false };
//! let ldr = eye.tone_map(&hdr, &first);
//! assert_eq!(ldr.len(), 8 * 4);
//! assert!(ldr[0] > ldr[4 * 4], "the sky is brighter than the ground");
//! assert!(ldr[2] < 255, "and not burnt out: the exposure adapted to the frame");
//!
//! // Accumulation: a pixel half covered by a vertical edge, sampled at the jittered
//! // offsets of 64 still samples and averaged, converges to its covered half.
//! let mut still = Accumulator::new(1);
//! for sample in 1..=64 {
//!     let covered = if frame_jitter(sample).x < 0.0 { 1.0 } else { 0.0 };
//!     still.add(&[[covered; 4]], sample).unwrap();
//! }
//! assert!((still.pixels()[0][0] - 0.5).abs() < 0.02, "{:?}", still.pixels());
//! ```

mod accumulate;
mod error;
mod tonemap;

#[cfg(feature = "gpu")]
pub mod gpu;

pub use accumulate::{Accumulator, average_index, frame_jitter, jitter, last_sample, weight};
pub use error::PostError;
pub use tonemap::{Exposure, LOG_DELTA, ToneMapper, linear_to_srgb, log_average, luminance};
