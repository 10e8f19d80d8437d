//! Tiled parallel tracing of image-shaped ray buffers (thesis 6.2.5: 40x40-pixel jobs taken
//! from a queue by one thread per core; here rayon's work stealing is the queue).

use rayon::prelude::*;

use crate::error::Error;
use crate::ray::{Hit, Ray, RayQuery};

/// The thesis's job size.
pub const DEFAULT_TILE: u32 = 40;

/// Evaluates `f(x, y)` for every pixel of a `width x height` image, one rayon task per
/// `tile x tile` block, and returns the results row by row. The result does not depend on
/// the number of threads (each pixel is computed independently).
pub fn map_tiles<T, F>(width: u32, height: u32, tile: u32, f: F) -> Vec<T>
where
    T: Send,
    F: Fn(u32, u32) -> T + Sync,
{
    let tile = tile.max(1);
    let (tx, ty) = (width.div_ceil(tile), height.div_ceil(tile));
    let tiles: Vec<Vec<T>> = (0..tx * ty)
        .into_par_iter()
        .map(|i| {
            let (x0, y0) = ((i % tx) * tile, (i / tx) * tile);
            let (x1, y1) = ((x0 + tile).min(width), (y0 + tile).min(height));
            let mut out = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
            for y in y0..y1 {
                for x in x0..x1 {
                    out.push(f(x, y));
                }
            }
            out
        })
        .collect();
    // Stitch tiles back into rows.
    let mut out = Vec::with_capacity((width * height) as usize);
    let mut iters: Vec<std::vec::IntoIter<T>> = tiles.into_iter().map(|t| t.into_iter()).collect();
    for y in 0..height {
        let row = y / tile;
        for c in 0..tx {
            let w = ((c + 1) * tile).min(width) - c * tile;
            out.extend(iters[(row * tx + c) as usize].by_ref().take(w as usize));
        }
    }
    out
}

/// Traces an image-shaped buffer of rays (`None` = no ray for that pixel, the thesis's
/// reflection flag) in tiles of `tile` pixels (use [`DEFAULT_TILE`]) and returns the closest
/// hit per pixel, row by row. Errors when `rays.len() != width * height`.
pub fn trace_tiles<A: RayQuery + ?Sized>(
    accel: &A,
    width: u32,
    height: u32,
    rays: &[Option<Ray>],
    t_max: f32,
    tile: u32,
) -> Result<Vec<Option<Hit>>, Error> {
    let expected = width as usize * height as usize;
    if rays.len() != expected {
        return Err(Error::BufferSize { len: rays.len(), width, height, expected });
    }
    Ok(map_tiles(width, height, tile, |x, y| {
        rays[(y * width + x) as usize].as_ref().and_then(|r| accel.intersect(r, t_max))
    }))
}
