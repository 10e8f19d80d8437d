//! GPU path (feature `gpu`): WGSL for the lookup (the deferred sky-lighting pass, thesis
//! 5.3.6) and the brute-force fill (thesis 5.3.4), and the `#[repr(C)]` data they read.
//!
//! Storage layout: [`PROBE_UVEC4S`] `vec4<u32>` per point (64 bytes), in grid order (x
//! fastest, then z, then y): the 27 coefficients of [`SkyVolume::probes`]' point (r, g, b x 9
//! radiance SH) as IEEE half floats, two to a word, then zeros ([`SkyVolume::gpu_probe_bytes`],
//! [`pack_probe`]), so that the lookup reads a point in four loads. Halves keep a coefficient
//! to 1 part in 2048 (the lookup's result within about 1e-3 of the CPU's, which keeps `f32`);
//! with 32-bit floats the lookup took seven loads a point, and on a software adapter the
//! loads are what the lookup's time is made of (`docs/figures.md`).
//! Coefficients beyond a half's range are clamped to +-65504. Bindings
//! are listed at the top of each shader. [`ResidentSkyVolume`] runs both as resident passes (the
//! fill layer by layer, the lookup bound once to the caller's buffers).

pub use crate::resident::{LookupBinding, ResidentSkyVolume};
use crate::sky::sanitize;
use crate::{OcclusionQuad, SkyRadiance, SkyVolume};
use bytemuck::{Pod, Zeroable};

/// `vec4<u32>` per point in the shaders' probe buffer: 27 coefficients as halves, two to a
/// word, and five zero halves.
pub const PROBE_UVEC4S: usize = 4;

/// Largest finite half float: what the packing clamps a coefficient to.
pub const HALF_MAX: f32 = 65504.0;

/// One point's 27 coefficients as the probe buffer holds them (halves, two to a word: the
/// lower 16 bits hold the even coefficient).
pub fn pack_probe(p: &[f32; 27]) -> [u32; PROBE_UVEC4S * 4] {
    let half = |k: usize| {
        let x = p.get(k).copied().unwrap_or(0.0).clamp(-HALF_MAX, HALF_MAX);
        u32::from(half::f16::from_f32(x).to_bits())
    };
    std::array::from_fn(|w| half(2 * w) | (half(2 * w + 1) << 16))
}

/// The inverse of [`pack_probe`].
pub fn unpack_probe(words: &[u32; PROBE_UVEC4S * 4]) -> [f32; 27] {
    std::array::from_fn(|k| {
        let bits = (words[k / 2] >> (16 * (k % 2))) & 0xffff;
        half::f16::from_bits(bits as u16).to_f32()
    })
}

/// WGSL snippet of the lookup, `sky_volume_irradiance(pos, normal)`, for a renderer's own
/// shaders (after the `sh_math` snippet): the includer provides `sky_volume_params()` (the
/// [`LookupParams`] uniform, [`ResidentSkyVolume::lookup_params`]) and `sky_volume_probe(i)`
/// (the probe buffer, [`ResidentSkyVolume::probes`]).
pub const LOOKUP_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/lookup.inc.wgsl"));
/// WGSL of the lookup kernel (entry point `lookup`) over [`LOOKUP_INC_WGSL`]; use
/// [`lookup_shader`].
pub const LOOKUP_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/lookup.wgsl"));
/// WGSL of the brute-force fill (entry point `fill`); use [`fill_shader`].
pub const FILL_WGSL: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/fill.wgsl"));

/// The complete lookup shader (sh_math snippet + [`LOOKUP_INC_WGSL`] + [`LOOKUP_WGSL`]).
pub fn lookup_shader() -> String {
    format!("{}\n{}\n{}", sh_math::WGSL, LOOKUP_INC_WGSL, LOOKUP_WGSL)
}

/// The complete fill shader (sh_math snippet + [`FILL_WGSL`]).
pub fn fill_shader() -> String {
    format!("{}\n{}", sh_math::WGSL, FILL_WGSL)
}

/// Uniform of the lookup shader.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct LookupParams {
    pub origin: [f32; 4],
    pub spacing: [f32; 4],
    pub dims: [u32; 4],
    pub kernel: [f32; 12],
}
const _: () = assert!(std::mem::size_of::<LookupParams>() == 96);

/// One lookup query (storage array element).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Query {
    pub position: [f32; 4],
    pub normal: [f32; 4],
    pub albedo: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<Query>() == 48);

/// Uniform of the fill shader.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FillParams {
    pub origin: [f32; 4],
    pub spacing: [f32; 4],
    /// Points along x, y, z; one past the last point to fill.
    pub dims: [u32; 4],
    /// Samples, quads, the first point to fill.
    pub counts: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<FillParams>() == 64);

/// An occlusion quad as the fill shader reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuQuad {
    pub center_half_u: [f32; 4],
    pub axis_u_half_v: [f32; 4],
    pub axis_v_opacity: [f32; 4],
    pub tint: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuQuad>() == 64);

impl From<&OcclusionQuad> for GpuQuad {
    fn from(q: &OcclusionQuad) -> Self {
        let (c, u, v, t) = (q.center, q.axis_u, q.axis_v, q.tint);
        Self {
            center_half_u: [c.x, c.y, c.z, q.half_u],
            axis_u_half_v: [u.x, u.y, u.z, q.half_v],
            axis_v_opacity: [v.x, v.y, v.z, q.opacity],
            tint: [t.x, t.y, t.z, 0.0],
        }
    }
}

/// Everything the fill shader's bindings 0..=3 hold.
#[derive(Clone, Debug, PartialEq)]
pub struct FillInputs {
    pub params: FillParams,
    /// Direction and solid-angle weight per sample.
    pub samples: Vec<[f32; 4]>,
    /// Sky radiance per sample (sanitised: non-finite or negative channels are zero).
    pub sky: Vec<[f32; 4]>,
    pub quads: Vec<GpuQuad>,
}

impl SkyVolume {
    /// The lookup shader's uniform for this volume.
    pub fn gpu_lookup_params(&self) -> LookupParams {
        let g = &self.grid;
        let mut kernel = [0.0; 12];
        kernel[..9].copy_from_slice(&self.kernel);
        LookupParams {
            origin: g.origin.extend(0.0).to_array(),
            // w: 1 for the oriented lookup (`Settings::oriented_lookup`).
            spacing: g
                .spacing
                .extend(f32::from(u8::from(self.settings.oriented_lookup)))
                .to_array(),
            dims: [g.dims.x, g.dims.y, g.dims.z, g.len() as u32],
            kernel,
        }
    }

    /// The probes as the shaders' buffer ([`PROBE_UVEC4S`] `vec4<u32>` per point,
    /// [`pack_probe`]).
    pub fn gpu_probe_bytes(&self) -> Vec<u8> {
        self.gpu_layer_bytes(0..self.grid.dims.y).1
    }

    /// The probes of `layers` (clamped to the volume) as the shaders' buffer holds them, and
    /// the byte offset in that buffer where they go: what to upload after
    /// [`SkyVolume::fill_layers`] of those layers.
    pub fn gpu_layer_bytes(&self, layers: std::ops::Range<u32>) -> (u64, Vec<u8>) {
        let per_layer = (self.grid.dims.x * self.grid.dims.z) as usize;
        let end = (layers.end.min(self.grid.dims.y) as usize) * per_layer;
        let start = (layers.start as usize * per_layer).min(end);
        let floats: &[f32] = bytemuck::cast_slice(&self.probes[start..end]);
        let words: Vec<u32> = floats
            .chunks_exact(27)
            .flat_map(|p| pack_probe(p.try_into().expect("27 coefficients")))
            .collect();
        ((start * PROBE_UVEC4S * 16) as u64, bytemuck::cast_slice(&words).to_vec())
    }

    /// The fill shader's inputs for this volume, its quads and `sky`.
    pub fn gpu_fill_inputs(&self, sky: &impl SkyRadiance) -> FillInputs {
        let g = &self.grid;
        let dirs = self.sample_directions();
        let w = std::f32::consts::TAU / dirs.len() as f32;
        FillInputs {
            params: FillParams {
                origin: g.origin.extend(0.0).to_array(),
                spacing: g.spacing.extend(0.0).to_array(),
                dims: [g.dims.x, g.dims.y, g.dims.z, g.len() as u32],
                counts: [dirs.len() as u32, self.quads().len() as u32, 0, 0],
            },
            samples: dirs.iter().map(|d| d.extend(w).to_array()).collect(),
            sky: dirs.iter().map(|d| sanitize(sky.radiance(*d)).extend(0.0).to_array()).collect(),
            quads: self.quads().iter().map(GpuQuad::from).collect(),
        }
    }
}
