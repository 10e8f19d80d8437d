//! The GPU path (feature `gpu`): resident passes, made once from a `wgpu::Device` and the
//! caller's HDR images, that record into the caller's command encoder and create nothing per
//! frame.
//!
//! - [`ToneMapPass`] (`shaders/post/tonemap.wgsl`): the frame's log-average luminance reduced
//!   on the GPU, the adapted luminance kept in a GPU buffer from frame to frame, and the
//!   display image written to the RGBA8 texture the pass owns. It is made over any number of
//!   source images (a renderer's lit view, its view with traced effects combined, its
//!   accumulated still view), each bound once; `record` picks one per frame by index.
//! - [`AccumulatePass`] (`shaders/post/accumulate.wgsl`): a still view's frame blended into
//!   the caller's accumulated image with the running-mean weight, from one of its sources.
//!
//! Reading back is a separate call for tests and tools ([`ToneMapPass::read_back`],
//! [`ToneMapPass::read_adaptation`]; the accumulated image is the caller's texture, read
//! with `gpu_harness::read_texture`).

mod accumulate;
mod tonemap;

pub use accumulate::AccumulatePass;
pub use tonemap::{REDUCE_GROUPS, ToneMapPass};

/// The tone-mapping shader (`shaders/post/tonemap.wgsl`: entry points `reduce`, `adapt`,
/// `map`).
pub const TONEMAP_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/tonemap.wgsl"));

/// The accumulation shader (`shaders/post/accumulate.wgsl`: entry points `vs_fullscreen`,
/// `fs_accumulate`).
pub const ACCUMULATE_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/accumulate.wgsl"));

/// Every shader of the crate as `(name, source)`, for the naga test.
pub const SHADERS: [(&str, &str); 2] = [("tonemap", TONEMAP_WGSL), ("accumulate", ACCUMULATE_WGSL)];

/// The views of `sources`, each checked to be `width` x `height`.
fn check_sources(
    sources: &[&wgpu::TextureView],
    width: u32,
    height: u32,
) -> Result<(), crate::PostError> {
    if width == 0 || height == 0 {
        return Err(crate::PostError::EmptyImage { width, height });
    }
    if sources.is_empty() {
        return Err(crate::PostError::NoSources);
    }
    for (index, view) in sources.iter().enumerate() {
        let t = view.texture();
        if (t.width(), t.height()) != (width, height) {
            return Err(crate::PostError::SourceSize {
                index,
                width: t.width(),
                height: t.height(),
                expected_width: width,
                expected_height: height,
            });
        }
    }
    Ok(())
}

/// `Err(NoSuchSource)` when `index` is not one of `sources` sources.
fn check_index(index: usize, sources: usize) -> Result<(), crate::PostError> {
    if index < sources { Ok(()) } else { Err(crate::PostError::NoSuchSource { index, sources }) }
}
