//! What the screen-space passes of this crate read of a rasteriser's frame: the view
//! ([`ScreenView`], which reconstructs a pixel's world position from its linear depth) and the
//! G-buffer ([`ScreenGBuffer`], its CPU form; the GPU path reads the same planes as textures,
//! `crate::gpu::GBufferViews`). The G-buffer's depth is linear, along the camera's forward
//! axis, and 0 where no geometry was drawn.

use glam::{Mat4, Vec2, Vec3, Vec4};

/// The camera and image size a G-buffer was rasterised with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenView {
    /// World to clip space (wgpu's: depth 0..1, y up); a jittered projection is fine.
    pub view_proj: Mat4,
    /// Its inverse.
    pub inv_view_proj: Mat4,
    /// The camera's position.
    pub eye: Vec3,
    /// The camera's unit forward axis, which the G-buffer's depth is measured along.
    pub forward: Vec3,
    /// The image size in pixels.
    pub width: u32,
    pub height: u32,
}

impl ScreenView {
    /// The view of a camera at `eye` looking along `forward` (normalised here; a zero
    /// vector reads as `-z`) through `view_proj`, over a `width x height` image.
    pub fn new(view_proj: Mat4, eye: Vec3, forward: Vec3, (width, height): (u32, u32)) -> Self {
        Self {
            view_proj,
            inv_view_proj: view_proj.inverse(),
            eye,
            forward: forward.normalize_or(Vec3::NEG_Z),
            width,
            height,
        }
    }

    /// The size of the ray casting buffer (thesis 6.2.4, 6.2.6): half the width by half the height,
    /// rounded up (one texel per 2x2 block of pixels).
    pub fn quarter(&self) -> (u32, u32) {
        (self.width.div_ceil(2), self.height.div_ceil(2))
    }

    /// Unit view ray through the centre of pixel `px` (`pixel_view_ray` of
    /// `shaders/traced_effects/screen.inc.wgsl`).
    pub fn view_ray(&self, px: Vec2) -> Vec3 {
        let (w, h) = (self.width as f32, self.height as f32);
        let ndc = Vec2::new((px.x + 0.5) / w * 2.0 - 1.0, 1.0 - (px.y + 0.5) / h * 2.0);
        let far = self.inv_view_proj * Vec4::new(ndc.x, ndc.y, 1.0, 1.0);
        (far.truncate() / far.w - self.eye).normalize()
    }

    /// World position of pixel `px` whose linear depth is `depth` (`pixel_world_position`).
    pub fn world_position(&self, px: Vec2, depth: f32) -> Vec3 {
        let d = self.view_ray(px);
        self.eye + d * (depth / d.dot(self.forward).max(1e-4))
    }
}

/// A G-buffer on the CPU, one entry per pixel, rows top to bottom: what the GPU passes read
/// from its textures (`crate::gpu::GBufferViews`).
#[derive(Clone, Copy, Debug)]
pub struct ScreenGBuffer<'a> {
    /// Shading normal (need not be unit length).
    pub normal: &'a [Vec3],
    /// Index into the material table (the geometry normal's `w` on the GPU).
    pub material: &'a [u32],
    /// Linear depth along the view's forward axis; 0 (or less) for the background.
    pub depth: &'a [f32],
}

impl ScreenGBuffer<'_> {
    /// Whether every plane has the `view`'s pixel count.
    pub fn fits(&self, view: &ScreenView) -> bool {
        let n = view.width as usize * view.height as usize;
        self.normal.len() == n && self.material.len() == n && self.depth.len() == n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pixel's reconstructed position lies on its view ray at the depth it was given.
    #[test]
    fn world_position_is_at_its_depth_along_the_forward_axis() {
        let camera = scene::Camera {
            position: Vec3::new(1.0, 2.0, 3.0),
            forward: Vec3::new(0.2, -0.1, -1.0).normalize(),
            aspect: 1.5,
            ..Default::default()
        };
        let view =
            ScreenView::new(camera.view_projection(), camera.position, camera.forward, (6, 4));
        for px in [Vec2::ZERO, Vec2::new(5.0, 3.0), Vec2::new(2.0, 1.0)] {
            let p = view.world_position(px, 7.0);
            assert!(((p - view.eye).dot(view.forward) - 7.0).abs() < 1e-4, "{p}");
            let clip = view.view_proj * p.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            let back = Vec2::new((ndc.x + 1.0) * 3.0 - 0.5, (1.0 - ndc.y) * 2.0 - 0.5);
            assert!((back - px).length() < 1e-3, "{back} {px}");
        }
    }
}
