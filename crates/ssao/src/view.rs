//! The view a depth buffer was rendered from, and its block as the WGSL reads it.

use crate::error::SsaoError;
use crate::estimator::SsaoSettings;
use glam::{Mat4, Vec3};

/// Camera and image size of a depth buffer of linear view depths (distance along the unit
/// `forward` from `position`, 0 where nothing was drawn), row-major, top row first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenView {
    /// World to clip (wgpu conventions: y up in NDC, top row first in the image).
    pub view_proj: Mat4,
    pub position: Vec3,
    pub forward: Vec3,
    pub width: u32,
    pub height: u32,
}

impl ScreenView {
    /// Checks the matrix and vectors are finite, `forward` non-zero (it is normalised) and the
    /// size non-zero.
    pub fn new(
        view_proj: Mat4,
        position: Vec3,
        forward: Vec3,
        width: u32,
        height: u32,
    ) -> Result<Self, SsaoError> {
        if !view_proj.is_finite() || !position.is_finite() {
            return Err(SsaoError::NonFinite("view-projection or camera position"));
        }
        let forward = forward.try_normalize().ok_or(SsaoError::NonFinite("camera forward"))?;
        if width == 0 || height == 0 {
            return Err(SsaoError::InvalidParameter {
                name: "size",
                reason: format!("{width}x{height}"),
            });
        }
        Ok(Self { view_proj, position, forward, width, height })
    }

    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

/// `SsaoParams` of `ssao.inc.wgsl` (112 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuSsaoParams {
    pub view_proj: [[f32; 4]; 4],
    /// xyz camera position, w unused.
    pub camera_pos: [f32; 4],
    /// xyz unit camera forward, w unused.
    pub camera_fwd: [f32; 4],
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    pub radius: f32,
}

const _: () = assert!(std::mem::size_of::<GpuSsaoParams>() == 112);

impl GpuSsaoParams {
    pub fn new(view: &ScreenView, settings: &SsaoSettings) -> Self {
        Self {
            view_proj: view.view_proj.to_cols_array_2d(),
            camera_pos: view.position.extend(0.0).to_array(),
            camera_fwd: view.forward.extend(0.0).to_array(),
            width: view.width,
            height: view.height,
            samples: settings.samples,
            radius: settings.radius,
        }
    }
}
