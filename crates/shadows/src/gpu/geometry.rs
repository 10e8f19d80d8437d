//! The caller's geometry as the resident passes draw it: their vertex and index buffers, where
//! positions (and normals) sit in a vertex, and the runs of triangles to draw.

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
}

impl VertexLayout {
    /// Tightly packed positions (12 bytes per vertex), no normals.
    pub const POSITIONS: Self = Self { stride: 12, position_offset: 0, normal_offset: 0 };
    /// Position then normal (24 bytes per vertex).
    pub const POSITION_NORMAL: Self = Self { stride: 24, position_offset: 0, normal_offset: 12 };

    fn attribute(offset: u64, location: u32) -> wgpu::VertexAttribute {
        wgpu::VertexAttribute {
            format: wgpu::VertexFormat::Float32x3,
            offset,
            shader_location: location,
        }
    }

    /// The attributes: position at location 0 and, `with_normals`, normal at location 1.
    pub(crate) fn attributes(&self, with_normals: bool) -> Vec<wgpu::VertexAttribute> {
        let mut a = vec![Self::attribute(self.position_offset, 0)];
        if with_normals {
            a.push(Self::attribute(self.normal_offset, 1));
        }
        a
    }

    pub(crate) fn validate(&self, with_normals: bool) -> Result<(), ShadowError> {
        let fits = |o: u64| o.is_multiple_of(4) && o + 12 <= self.stride;
        if self.stride == 0
            || !self.stride.is_multiple_of(4)
            || !fits(self.position_offset)
            || (with_normals && !fits(self.normal_offset))
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
#[derive(Clone, Copy, Debug)]
pub struct Geometry<'a> {
    pub vertices: &'a wgpu::Buffer,
    pub indices: &'a wgpu::Buffer,
    pub index_format: wgpu::IndexFormat,
    pub draws: &'a [DrawRange],
}

impl Geometry<'_> {
    /// Records the draws into `pass` (bind groups already set).
    pub(crate) fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), self.index_format);
        for d in self.draws {
            pass.draw_indexed(d.indices.clone(), d.base_vertex, 0..1);
        }
    }
}
