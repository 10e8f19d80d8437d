//! The caller's geometry as the resident passes draw it: their vertex and index buffers, where
//! positions (normals, texture coordinates) sit in a vertex, the runs of triangles to draw
//! and the alpha masks of the alpha-tested ones.

use super::mask::AlphaMask;
use crate::error::ShadowError;
use std::ops::Range;

/// Where positions (and, for the RSM pass, normals) sit in the caller's vertex buffer: three
/// `f32` each at a byte offset inside a vertex of `stride` bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VertexLayout {
    pub stride: u64,
    pub position_offset: u64,
    /// Used by [`super::ReflectiveShadowMap`] only.
    pub normal_offset: u64,
    /// Texture coordinates (two `f32`), read by alpha-tested draws only
    /// ([`Geometry::masks`]); `None`: the passes draw no masked geometry.
    pub uv_offset: Option<u64>,
}

impl VertexLayout {
    /// Tightly packed positions (12 bytes per vertex), no normals.
    pub const POSITIONS: Self =
        Self { stride: 12, position_offset: 0, normal_offset: 0, uv_offset: None };
    /// Position then normal (24 bytes per vertex).
    pub const POSITION_NORMAL: Self =
        Self { stride: 24, position_offset: 0, normal_offset: 12, uv_offset: None };
    /// Position, normal, texture coordinates (32 bytes per vertex).
    pub const POSITION_NORMAL_UV: Self =
        Self { stride: 32, position_offset: 0, normal_offset: 12, uv_offset: Some(24) };

    fn attribute(offset: u64, location: u32) -> wgpu::VertexAttribute {
        wgpu::VertexAttribute {
            format: wgpu::VertexFormat::Float32x3,
            offset,
            shader_location: location,
        }
    }

    /// The attributes: position at location 0, `with_normals` normal at location 1 and
    /// `masked` texture coordinates at location 2.
    pub(crate) fn attributes(
        &self,
        with_normals: bool,
        masked: bool,
    ) -> Vec<wgpu::VertexAttribute> {
        let mut a = vec![Self::attribute(self.position_offset, 0)];
        if with_normals {
            a.push(Self::attribute(self.normal_offset, 1));
        }
        if let (true, Some(offset)) = (masked, self.uv_offset) {
            a.push(wgpu::VertexAttribute {
                format: wgpu::VertexFormat::Float32x2,
                offset,
                shader_location: 2,
            });
        }
        a
    }

    pub(crate) fn validate(&self, with_normals: bool) -> Result<(), ShadowError> {
        let fits = |o: u64, size: u64| o.is_multiple_of(4) && o + size <= self.stride;
        if self.stride == 0
            || !self.stride.is_multiple_of(4)
            || !fits(self.position_offset, 12)
            || (with_normals && !fits(self.normal_offset, 12))
            || self.uv_offset.is_some_and(|o| !fits(o, 8))
        {
            return Err(ShadowError::InvalidParameter {
                name: "vertex layout",
                reason: format!(
                    "{self:?}: attributes must be 4-byte aligned and inside the stride"
                ),
            });
        }
        Ok(())
    }
}

/// A run of triangles: `indices` of the index buffer, added to `base_vertex`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DrawRange {
    pub indices: Range<u32>,
    pub base_vertex: i32,
}

/// The caller's world-space geometry, drawn as is (no model matrices: resident passes draw a
/// scene already in world space, as renderers that batch static geometry keep it).
#[derive(Clone, Copy)]
pub struct Geometry<'a> {
    pub vertices: &'a wgpu::Buffer,
    pub indices: &'a wgpu::Buffer,
    pub index_format: wgpu::IndexFormat,
    pub draws: &'a [DrawRange],
    /// Per draw, the mask of an alpha-tested draw (`None`: opaque). Empty: every draw is
    /// opaque; otherwise one entry per draw.
    pub masks: &'a [Option<AlphaMask>],
}

/// A pass's two pipelines: opaque draws, and alpha-tested ones when the vertex layout has
/// texture coordinates.
pub(crate) struct Pipelines {
    pub(crate) opaque: wgpu::RenderPipeline,
    pub(crate) masked: Option<wgpu::RenderPipeline>,
}

impl Geometry<'_> {
    /// Opaque geometry: every draw of `draws`, no masks.
    pub fn opaque<'a>(
        vertices: &'a wgpu::Buffer,
        indices: &'a wgpu::Buffer,
        index_format: wgpu::IndexFormat,
        draws: &'a [DrawRange],
    ) -> Geometry<'a> {
        Geometry { vertices, indices, index_format, draws, masks: &[] }
    }

    fn mask(&self, draw: usize) -> Option<&AlphaMask> {
        self.masks.get(draw).and_then(Option::as_ref)
    }

    /// Errors: masks that are not one per draw, or masked draws for a pass whose vertex layout
    /// has no texture coordinates.
    pub(crate) fn validate(&self, pipelines: &Pipelines) -> Result<(), ShadowError> {
        let counts = self.masks.is_empty() || self.masks.len() == self.draws.len();
        let any = self.masks.iter().any(Option::is_some);
        if !counts || (any && pipelines.masked.is_none()) {
            return Err(ShadowError::InvalidParameter {
                name: "alpha masks",
                reason: format!(
                    "{} masks for {} draws ({}); a pass draws masked geometry only when its \
                     vertex layout has texture coordinates",
                    self.masks.len(),
                    self.draws.len(),
                    if any { "some masked" } else { "none masked" },
                ),
            });
        }
        Ok(())
    }

    /// Records the draws into `pass` with `pipelines` (validated), the opaque or masked one
    /// per draw; `per_draw(pass, i)` sets group 0 before draw `i`.
    pub(crate) fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        pipelines: &Pipelines,
        mut per_draw: impl FnMut(&mut wgpu::RenderPass<'_>, usize),
    ) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), self.index_format);
        // Which pipeline is bound: None, Some(false) opaque, Some(true) masked.
        let mut bound = None;
        for (i, d) in self.draws.iter().enumerate() {
            let mask = self.mask(i).filter(|_| pipelines.masked.is_some());
            let masked = mask.is_some();
            if bound != Some(masked) {
                let masked_pipeline = pipelines.masked.as_ref().filter(|_| masked);
                pass.set_pipeline(masked_pipeline.unwrap_or(&pipelines.opaque));
                bound = Some(masked);
            }
            if let Some(m) = mask {
                pass.set_bind_group(1, &m.group, &[]);
            }
            per_draw(pass, i);
            pass.draw_indexed(d.indices.clone(), d.base_vertex, 0..1);
        }
    }
}
