//! Resident sun shadow maps: the cascades' depth in one texture array, their [`CsmCascade`]
//! blocks and the PCSS tap table in storage buffers, all created once; each frame writes the
//! blocks and records one depth pass per cascade into the caller's encoder
//! ([`CascadeShadows::record`]), or only into the maps whose view moved
//! ([`CascadeShadows::record_moved`]: stabilised cascades keep their view until the camera
//! moves by one of their texels, so over static geometry the far maps are mostly reused).

use super::depth_layers::DepthLayers;
use super::geometry::{Geometry, VertexLayout};
use super::readback;
use crate::csm_lookup::CsmCascade;
use crate::depth_map::DepthMap;
use crate::error::ShadowError;
use glam::{Mat4, Vec2};
use std::sync::Mutex;

/// The most PCSS taps (blocker + PCF) the tap buffer holds.
pub const MAX_TAPS: u32 = 256;

/// What the lighting shader binds: the depth array (`texture_depth_2d_array`), the
/// `array<CsmCascade>` and the `array<vec2<f32>>` taps for `csm.inc.wgsl`.
#[derive(Clone, Copy, Debug)]
pub struct CascadeMaps<'a> {
    pub depth: &'a wgpu::TextureView,
    pub cascades: &'a wgpu::Buffer,
    pub taps: &'a wgpu::Buffer,
    /// Cascades written by the last record.
    pub count: u32,
}

/// Cascaded shadow maps that live on the GPU.
pub struct CascadeShadows {
    layers: DepthLayers,
    array: wgpu::TextureView,
    cascades: wgpu::Buffer,
    taps: wgpu::Buffer,
    /// The view-projection (its bits) each map holds the depth of; `None`: not rendered yet.
    held: Mutex<Vec<Option<[u32; 16]>>>,
}

/// What a record left: the bindings, and how many maps it rendered (the rest were reused).
#[derive(Clone, Copy, Debug)]
pub struct RecordedCascades<'a> {
    pub maps: CascadeMaps<'a>,
    pub rendered: u32,
}

impl CascadeShadows {
    /// Up to `cascades` maps of `resolution`² for geometry laid out as `vertex`.
    pub fn new(
        device: &wgpu::Device,
        vertex: VertexLayout,
        resolution: u32,
        cascades: u32,
    ) -> Result<Self, ShadowError> {
        let layers = DepthLayers::new(device, "sun cascades", vertex, resolution, cascades)?;
        let array = layers.texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let size = std::mem::size_of::<CsmCascade>() as u64 * cascades as u64;
        Ok(Self {
            layers,
            array,
            cascades: gpu_harness::empty_storage(device, "sun cascades", size),
            taps: gpu_harness::empty_storage(device, "pcss taps", 8 * MAX_TAPS as u64),
            held: Mutex::new(vec![None; cascades as usize]),
        })
    }

    pub fn resolution(&self) -> u32 {
        self.layers.size
    }

    /// The bindings, also before the first record (then with `count` 0).
    pub fn maps(&self, count: u32) -> CascadeMaps<'_> {
        CascadeMaps { depth: &self.array, cascades: &self.cascades, taps: &self.taps, count }
    }

    /// Writes `cascades` (one per map, [`CsmCascade::new`]) and the shared PCSS `taps`, and
    /// records the depth of `geometry` into each map.
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        geometry: &Geometry<'_>,
        cascades: &[CsmCascade],
        taps: &[Vec2],
    ) -> Result<CascadeMaps<'_>, ShadowError> {
        Ok(self.record_views(queue, encoder, geometry, (cascades, taps), false)?.maps)
    }

    /// [`Self::record`] for `geometry` that has not changed since this pass last rendered
    /// it: renders only the maps whose view-projection differs (bit for bit) from the one
    /// the map holds, and reuses the others, which are then identical to a render. After
    /// the geometry changes, [`Self::record`] (which renders every map) must come first; the
    /// encoder must be submitted (a map counts as holding its view once recorded).
    pub fn record_moved(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        geometry: &Geometry<'_>,
        cascades: &[CsmCascade],
        taps: &[Vec2],
    ) -> Result<RecordedCascades<'_>, ShadowError> {
        self.record_views(queue, encoder, geometry, (cascades, taps), true)
    }

    fn record_views(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        geometry: &Geometry<'_>,
        (cascades, taps): (&[CsmCascade], &[Vec2]),
        only_moved: bool,
    ) -> Result<RecordedCascades<'_>, ShadowError> {
        let n = cascades.len() as u32;
        if n > self.layers.layers() || taps.len() > MAX_TAPS as usize {
            return Err(ShadowError::InvalidParameter {
                name: "cascades",
                reason: format!(
                    "{n} cascades and {} taps for a pass made for {} and {MAX_TAPS}",
                    taps.len(),
                    self.layers.layers()
                ),
            });
        }
        let mut held = self.held.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let views: Vec<(u32, Mat4)> = (0..n)
            .zip(cascades)
            .map(|(i, c)| (i, Mat4::from_cols_array_2d(&c.view_proj)))
            .filter(|(i, m)| !only_moved || held[*i as usize] != Some(bits(m)))
            .collect();
        // Forgotten first: a failed record leaves no map claiming a view it may not hold.
        views.iter().for_each(|(i, _)| held[*i as usize] = None);
        self.layers.record(queue, encoder, geometry, &views)?;
        views.iter().for_each(|(i, m)| held[*i as usize] = Some(bits(m)));
        if n > 0 {
            queue.write_buffer(&self.cascades, 0, bytemuck::cast_slice(cascades));
        }
        if !taps.is_empty() {
            queue.write_buffer(&self.taps, 0, bytemuck::cast_slice(taps));
        }
        Ok(RecordedCascades { maps: self.maps(n), rendered: views.len() as u32 })
    }

    /// Reads map `cascade` back (tests and tools; a renderer never needs it).
    pub fn read_back(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        cascade: u32,
    ) -> Result<DepthMap, ShadowError> {
        readback::depth_layer(device, queue, &self.layers.texture, cascade)
    }
}

fn bits(m: &Mat4) -> [u32; 16] {
    m.to_cols_array().map(f32::to_bits)
}
