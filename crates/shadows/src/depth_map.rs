//! A CPU depth map: what a shadow pass writes, and what PCF/PCSS read.

use crate::error::ShadowError;

/// Row-major depths, row 0 at the top (like a texture). Texel `(x, y)` covers
/// `[x, x + 1) x [y, y + 1)` in map coordinates. Cleared to `1.0` (the far plane).
///
/// Depth is stored as the pass writes it: for orthographic (sun) maps the `[0, 1]` value is
/// linear in metres along the light; perspective maps can be converted to linear depth with
/// [`DepthMap::linearize_perspective`] before PCSS in perspective mode.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthMap {
    width: u32,
    height: u32,
    depth: Vec<f32>,
}

impl DepthMap {
    /// A map of `width x height` texels cleared to 1.
    pub fn new(width: u32, height: u32) -> Result<Self, ShadowError> {
        Self::filled(width, height, 1.0)
    }

    /// A map cleared to `value`.
    pub fn filled(width: u32, height: u32, value: f32) -> Result<Self, ShadowError> {
        if width == 0 || height == 0 || width > 32768 || height > 32768 {
            return Err(ShadowError::InvalidParameter {
                name: "depth map size",
                reason: format!("must be in 1..=32768, got {width}x{height}"),
            });
        }
        Ok(Self { width, height, depth: vec![value; width as usize * height as usize] })
    }

    /// Wraps existing depths (row-major, `width * height` values).
    pub fn from_vec(width: u32, height: u32, depth: Vec<f32>) -> Result<Self, ShadowError> {
        let m = Self::new(width, height)?;
        if depth.len() != m.depth.len() {
            return Err(ShadowError::InvalidParameter {
                name: "depth",
                reason: format!("expected {} values, got {}", m.depth.len(), depth.len()),
            });
        }
        Ok(Self { depth, ..m })
    }

    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    pub fn as_slice(&self) -> &[f32] {
        &self.depth
    }
    pub fn as_mut_slice(&mut self) -> &mut [f32] {
        &mut self.depth
    }

    /// The depth of texel `(x, y)`, clamped to the edge.
    #[inline(always)]
    pub fn at(&self, x: i32, y: i32) -> f32 {
        let xi = x.clamp(0, self.width as i32 - 1) as usize;
        let yi = y.clamp(0, self.height as i32 - 1) as usize;
        // SAFETY-free: indices are clamped into range.
        self.depth[yi * self.width as usize + xi]
    }

    /// Sets every texel back to `value`.
    pub fn clear(&mut self, value: f32) {
        self.depth.fill(value);
    }

    /// Converts `[0, 1]` right-handed perspective depth (0 at `near`, 1 at `far`, as
    /// [`cube_face_view_proj`](crate::cube_face_view_proj) writes it) into linear
    /// view distance in metres. Returns an error for `near <= 0` or `far <= near`.
    pub fn linearize_perspective(&mut self, near: f32, far: f32) -> Result<(), ShadowError> {
        if !(near > 0.0 && far > near && far.is_finite()) {
            return Err(ShadowError::InvalidParameter {
                name: "near/far",
                reason: format!("need 0 < near < far, got {near}, {far}"),
            });
        }
        for d in &mut self.depth {
            // perspective_rh: d = far/(far-near) * (1 - near/z)  =>  z = near*far/(far - d*(far-near)).
            *d = near * far / (far - d.clamp(0.0, 1.0) * (far - near));
        }
        Ok(())
    }

    /// Every depth is finite.
    pub fn validate(&self) -> Result<(), ShadowError> {
        if self.depth.len() != self.width as usize * self.height as usize {
            return Err(ShadowError::Invariant("depth length != width * height".into()));
        }
        if let Some(i) = self.depth.iter().position(|d| !d.is_finite()) {
            return Err(ShadowError::Invariant(format!("texel {i} has a non-finite depth")));
        }
        Ok(())
    }
}
