//! What the tests and the sweep share: an analytic image made to alias, sampled at a point
//! per pixel or box-filtered over each pixel; and on the GPU, half-float HDR textures filled
//! from the CPU.
#![allow(dead_code)]

use rayon::prelude::*;

/// An analytic HDR image over `width` x `height` pixels that aliases when it is sampled at
/// one point per pixel: a dim gradient, a sharp edge three degrees off vertical, a disc,
/// six wires a quarter of a pixel wide at assorted angles (bright, like highlights), and a
/// grating of period 1.37 pixels in one corner (moiré).
#[derive(Clone, Copy, Debug)]
pub struct Pattern {
    pub width: u32,
    pub height: u32,
}

/// The wires: angle of their direction (degrees) and a point they pass through, as fractions
/// of the image.
const WIRES: [(f64, [f64; 2]); 6] = [
    (10.0, [0.5, 0.2]),
    (37.0, [0.4, 0.5]),
    (61.0, [0.7, 0.6]),
    (85.0, [0.15, 0.5]),
    (120.0, [0.6, 0.4]),
    (150.0, [0.3, 0.8]),
];

impl Pattern {
    /// Radiance (grey) at `(x, y)` in pixels, the image's top-left corner at 0.
    pub fn radiance(&self, x: f64, y: f64) -> f32 {
        let (w, h) = (self.width as f64, self.height as f64);
        let mut v = 0.1 + 0.2 * y / h;
        let tilt = 3f64.to_radians();
        if (x - 0.62 * w) * tilt.cos() + (y - 0.5 * h) * tilt.sin() > 0.0 {
            v += 0.9;
        }
        let (dx, dy) = (x - 0.8 * w, y - 0.3 * h);
        if dx * dx + dy * dy < (0.18 * h) * (0.18 * h) {
            v += 2.0;
        }
        for (angle, [px, py]) in WIRES {
            let a = angle.to_radians();
            // Distance to the line through (px, py) along (cos a, sin a).
            let d = (x - px * w) * a.sin() - (y - py * h) * a.cos();
            if d.abs() < 0.125 {
                v += 8.0;
            }
        }
        if x < 0.3 * w && y > 0.7 * h && (x / 1.37).fract() < 0.5 {
            v += 1.5;
        }
        v as f32
    }

    /// The image sampled at one point per pixel, the pixel's centre moved by `offset` pixels.
    pub fn sampled(&self, offset: glam::Vec2) -> Vec<[f32; 4]> {
        let w = self.width as usize;
        (0..w * self.height as usize)
            .into_par_iter()
            .map(|i| {
                let x = (i % w) as f64 + 0.5 + offset.x as f64;
                let y = (i / w) as f64 + 0.5 + offset.y as f64;
                let v = self.radiance(x, y);
                [v, v, v, 1.0]
            })
            .collect()
    }

    /// The image box-filtered over each pixel: the mean of `n` x `n` stratified points.
    pub fn box_filtered(&self, n: u32) -> Vec<[f32; 4]> {
        let w = self.width as usize;
        (0..w * self.height as usize)
            .into_par_iter()
            .map(|i| {
                let (x0, y0) = ((i % w) as f64, (i / w) as f64);
                let mut sum = 0.0f64;
                for j in 0..n * n {
                    let u = ((j % n) as f64 + 0.5) / n as f64;
                    let v = ((j / n) as f64 + 0.5) / n as f64;
                    sum += self.radiance(x0 + u, y0 + v) as f64;
                }
                let v = (sum / (n * n) as f64) as f32;
                [v, v, v, 1.0]
            })
            .collect()
    }
}

/// `sqrt(sum (a - r)^2 / sum r^2)` over the RGB channels.
pub fn rel_rms(a: &[[f32; 4]], r: &[[f32; 4]]) -> f64 {
    let rgb = |img: &[[f32; 4]]| -> Vec<f64> {
        img.iter().flat_map(|p| p[..3].iter().map(|&c| c as f64)).collect()
    };
    gi_report::rel_rms(&rgb(a), &rgb(r))
}

/// `pixels` as a half-float texture stores them.
pub fn halves(pixels: &[[f32; 4]]) -> Vec<[f32; 4]> {
    pixels.iter().map(|p| p.map(|c| half::f16::from_f32(c).to_f32())).collect()
}

/// The usages of the HDR images the tests make: sampled, rendered into, copied both ways.
const HDR_USAGE: wgpu::TextureUsages = wgpu::TextureUsages::TEXTURE_BINDING
    .union(wgpu::TextureUsages::RENDER_ATTACHMENT)
    .union(wgpu::TextureUsages::COPY_DST)
    .union(wgpu::TextureUsages::COPY_SRC);

/// An `Rgba16Float` image of `width` x `height`, black.
pub fn hdr_texture(device: &wgpu::Device, width: u32, height: u32) -> wgpu::Texture {
    let format = wgpu::TextureFormat::Rgba16Float;
    gpu_harness::texture_2d(device, "test hdr", (width, height), format, HDR_USAGE)
}

/// Writes `pixels` (rows top first) into the half-float `texture`.
pub fn upload(queue: &wgpu::Queue, texture: &wgpu::Texture, pixels: &[[f32; 4]]) {
    let data: Vec<half::f16> = pixels.iter().flat_map(|p| p.map(half::f16::from_f32)).collect();
    queue.write_texture(
        texture.as_image_copy(),
        bytemuck::cast_slice(&data),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(texture.width() * 8),
            rows_per_image: Some(texture.height()),
        },
        texture.size(),
    );
}

/// Reads the half-float `texture` back as `f32` RGBA.
pub fn download(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Vec<[f32; 4]> {
    let all = wgpu::TextureAspect::All;
    let bytes = gpu_harness::read_texture(device, queue, texture, 0, all, 8).expect("read back");
    let h: Vec<half::f16> = gpu_harness::cast_vec(&bytes);
    h.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]].map(f32::from)).collect()
}
