//! Procedural textures for the generated scenes, produced as sRGB bytes and decoded through the
//! same path as loaded images (sRGB -> linear, then mips), so generating the city exercises it.

use crate::{ColorSpace, SceneError, Texture};

/// Integer hash -> [0, 1).
fn hash(x: u32, y: u32, seed: u32) -> f32 {
    let mut h =
        x.wrapping_mul(0x8da6_b343) ^ y.wrapping_mul(0xd816_3841) ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^= h >> 15;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

/// Tileable value noise with `cells` cells across the texture.
fn noise(x: u32, y: u32, size: (u32, u32), cells: u32, seed: u32) -> f32 {
    let fx = x as f32 / size.0 as f32 * cells as f32;
    let fy = y as f32 / size.1 as f32 * cells as f32;
    let (ix, iy) = (fx.floor() as u32, fy.floor() as u32);
    let (tx, ty) = (fx - fx.floor(), fy - fy.floor());
    let s = |v: f32| v * v * (3.0 - 2.0 * v);
    let h = |a: u32, b: u32| hash(a % cells, b % cells, seed);
    let top = h(ix, iy) + (h(ix + 1, iy) - h(ix, iy)) * s(tx);
    let bottom = h(ix, iy + 1) + (h(ix + 1, iy + 1) - h(ix, iy + 1)) * s(tx);
    top + (bottom - top) * s(ty)
}

fn fbm(x: u32, y: u32, size: (u32, u32), seed: u32) -> f32 {
    (noise(x, y, size, 4, seed) * 0.5
        + noise(x, y, size, 16, seed + 1) * 0.3
        + noise(x, y, size, 64, seed + 2) * 0.2)
        .clamp(0.0, 1.0)
}

fn build(
    name: &str,
    w: u32,
    h: u32,
    space: ColorSpace,
    f: impl Fn(u32, u32) -> [f32; 4],
) -> Result<Texture, SceneError> {
    let mut bytes = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            for c in f(x, y) {
                bytes.push((c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8);
            }
        }
    }
    Texture::from_rgba8(name, w, h, &bytes, space)
}

/// Grey asphalt with grain (sRGB).
pub(crate) fn asphalt(seed: u32) -> Result<Texture, SceneError> {
    let size = (256, 256);
    build("asphalt", size.0, size.1, ColorSpace::Srgb, |x, y| {
        let v = 0.28 + 0.12 * fbm(x, y, size, seed) + 0.06 * hash(x, y, seed ^ 7);
        [v, v, v * 1.02, 1.0]
    })
}

/// Square paving slabs; 192x192 on purpose (a non-power-of-two texture in the reference scene).
pub(crate) fn paving(seed: u32) -> Result<Texture, SceneError> {
    let size = (192, 192);
    build("paving", size.0, size.1, ColorSpace::Srgb, |x, y| {
        let joint = x % 48 < 2 || y % 48 < 2;
        let slab = hash(x / 48, y / 48, seed) * 0.08;
        let v = if joint { 0.35 } else { 0.62 + slab + 0.05 * fbm(x, y, size, seed + 3) };
        [v, v * 0.97, v * 0.92, 1.0]
    })
}

/// Brick courses (sRGB) and the matching tangent-space normal map (linear).
pub(crate) fn bricks(seed: u32) -> Result<(Texture, Texture), SceneError> {
    let size = (128, 128);
    let mortar = |x: u32, y: u32| {
        let row = y / 16;
        let xo = (x + if row % 2 == 1 { 16 } else { 0 }) % 128;
        y % 16 < 2 || xo % 32 < 2
    };
    let color = build("bricks", size.0, size.1, ColorSpace::Srgb, |x, y| {
        if mortar(x, y) {
            [0.72, 0.70, 0.66, 1.0]
        } else {
            let row = y / 16;
            let xo = (x + if row % 2 == 1 { 16 } else { 0 }) % 128;
            let b = 0.85 + 0.15 * hash(xo / 32, row, seed) - 0.1 * fbm(x, y, size, seed + 5);
            [0.62 * b, 0.30 * b, 0.22 * b, 1.0]
        }
    })?;
    let normal = build("bricks_normal", size.0, size.1, ColorSpace::Linear, |x, y| {
        // Mortar grooves: normals tilt towards the groove centre.
        let gy = if y % 16 == 0 {
            -0.5
        } else if y % 16 == 1 {
            0.5
        } else {
            0.0
        };
        let row = y / 16;
        let xo = (x + if row % 2 == 1 { 16 } else { 0 }) % 128;
        let gx = if xo % 32 == 0 {
            -0.5
        } else if xo % 32 == 1 {
            0.5
        } else {
            0.0
        };
        let n = glam::Vec3::new(gx, gy, 1.0).normalize();
        [n.x * 0.5 + 0.5, n.y * 0.5 + 0.5, n.z * 0.5 + 0.5, 1.0]
    })?;
    Ok((color, normal))
}

/// Painted plaster (sRGB), tinted.
pub(crate) fn plaster(seed: u32, tint: [f32; 3]) -> Result<Texture, SceneError> {
    let size = (128, 128);
    build("plaster", size.0, size.1, ColorSpace::Srgb, |x, y| {
        let v = 0.85 + 0.15 * fbm(x, y, size, seed);
        [tint[0] * v, tint[1] * v, tint[2] * v, 1.0]
    })
}

/// Leaf clusters with an alpha mask (sRGB colour, linear alpha).
pub(crate) fn leaves(seed: u32) -> Result<Texture, SceneError> {
    let size = (128, 128);
    build("leaves", size.0, size.1, ColorSpace::Srgb, |x, y| {
        let (u, v) = (x as f32 / 128.0 - 0.5, y as f32 / 128.0 - 0.5);
        let r = (u * u + v * v).sqrt();
        let holes = noise(x, y, size, 16, seed);
        let a = if r < 0.48 && holes > 0.35 + r * 0.5 { 1.0 } else { 0.0 };
        let g = 0.6 + 0.4 * noise(x, y, size, 32, seed + 1);
        [0.18 * g, 0.42 * g, 0.12 * g, a]
    })
}

/// Bark (sRGB), 64x64.
pub(crate) fn bark(seed: u32) -> Result<Texture, SceneError> {
    let size = (64, 64);
    build("bark", size.0, size.1, ColorSpace::Srgb, |x, y| {
        let v = 0.6 + 0.4 * noise(x, y / 4, size, 16, seed);
        [0.30 * v, 0.22 * v, 0.15 * v, 1.0]
    })
}

/// Side of [`studs`] in texels, and the studs across it.
pub(crate) const STUDS_SIZE: u32 = 128;
const STUDS_ACROSS: u32 = 8;

/// A tangent-space normal map (linear) of round studs on a flat ground: `STUDS_ACROSS` x
/// `STUDS_ACROSS` cells, each holding a smooth bump of radius 0.4 cell, the height field
/// `h cos^2(pi r / 2R)`, whose height `h` the seed draws per cell (a quarter to an eighth of
/// a cell: slopes of up to about 45 degrees). Tileable. `+X` of the map is `+U`, `+Y` is up
/// the image (`-V`), so a stud's normals lean out of its centre on every side.
pub(crate) fn studs(seed: u32) -> Result<Texture, SceneError> {
    let cell = STUDS_SIZE / STUDS_ACROSS;
    let radius = 0.4 * cell as f32;
    build("wall_studs_normal", STUDS_SIZE, STUDS_SIZE, ColorSpace::Linear, |x, y| {
        let (cx, cy) = (x / cell, y / cell);
        // Offset from the cell's centre at the texel's centre, +Y up the image.
        let dx = (x % cell) as f32 + 0.5 - 0.5 * cell as f32;
        let dy = 0.5 * cell as f32 - ((y % cell) as f32 + 0.5);
        let r = (dx * dx + dy * dy).sqrt();
        let h = 0.125 * cell as f32 * (1.0 + hash(cx, cy, seed));
        let n = if r < radius && r > 0.0 {
            // -d/dr of the height field, along the offset.
            let k = std::f32::consts::PI / radius;
            let slope = 0.5 * h * k * (k * r).sin();
            glam::Vec3::new(slope * dx / r, slope * dy / r, 1.0).normalize()
        } else {
            glam::Vec3::Z
        };
        [n.x * 0.5 + 0.5, n.y * 0.5 + 0.5, n.z * 0.5 + 0.5, 1.0]
    })
}
