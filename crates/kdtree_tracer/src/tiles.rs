//! Tiled parallel tracing of image-shaped ray buffers (thesis 6.2.5: 40x40-pixel jobs taken
//! from a queue by one thread per core; here rayon's work stealing is the queue). Tiles are
//! handed to rayon along a Z-order (Morton) curve, so each thread's contiguous share of the
//! list is a compact block of the image (rays of nearby pixels meet nearby geometry).

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
    run_tiles(
        width,
        height,
        tile,
        || (),
        |_, x0, y0, x1, y1, out| {
            for y in y0..y1 {
                for x in x0..x1 {
                    out.push(f(x, y));
                }
            }
        },
    )
}

/// Runs `fill(scratch, x0, y0, x1, y1, out)` once per tile (it pushes the tile's pixels row
/// by row into `out`; `scratch` comes from `init`, once per rayon job rather than per tile),
/// tiles handed to rayon along the Z-order curve, and stitches the tiles into one row-major
/// image.
fn run_tiles<S, T, I, F>(width: u32, height: u32, tile: u32, init: I, fill: F) -> Vec<T>
where
    T: Send,
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, u32, u32, u32, u32, &mut Vec<T>) + Sync + Send,
{
    let tile = tile.max(1);
    let (tx, ty) = (width.div_ceil(tile), height.div_ceil(tile));
    let order = z_order(tx, ty);
    let done: Vec<Vec<T>> = order
        .par_iter()
        .map_init(init, |scratch, &i| {
            let (x0, y0) = ((i % tx) * tile, (i / tx) * tile);
            let (x1, y1) = ((x0 + tile).min(width), (y0 + tile).min(height));
            let mut out = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
            fill(scratch, x0, y0, x1, y1, &mut out);
            debug_assert_eq!(out.len(), ((x1 - x0) * (y1 - y0)) as usize);
            out
        })
        .collect();
    // Back to row-major tile order, then stitch tiles into rows.
    let mut tiles: Vec<Vec<T>> = (0..order.len()).map(|_| Vec::new()).collect();
    for (&i, t) in order.iter().zip(done) {
        tiles[i as usize] = t;
    }
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

/// Row-major indices of a `tx x ty` grid of tiles, sorted along the Z-order curve.
fn z_order(tx: u32, ty: u32) -> Vec<u32> {
    let mut order: Vec<u32> = (0..tx * ty).collect();
    order.sort_unstable_by_key(|&i| spread(i % tx) | (spread(i / tx) << 1));
    order
}

/// The bits of `v` moved to the even bit positions (Morton interleave).
fn spread(v: u32) -> u64 {
    let mut x = u64::from(v);
    x = (x | (x << 16)) & 0x0000_FFFF_0000_FFFF;
    x = (x | (x << 8)) & 0x00FF_00FF_00FF_00FF;
    x = (x | (x << 4)) & 0x0F0F_0F0F_0F0F_0F0F;
    x = (x | (x << 2)) & 0x3333_3333_3333_3333;
    (x | (x << 1)) & 0x5555_5555_5555_5555
}

/// Pixel blocks traced together by [`trace_tiles`]: 4 x 4 pixels (a kd-tree packet).
const BLOCK: (u32, u32) = (4, 4);

/// Traces an image-shaped buffer of rays (`None` = no ray for that pixel, the thesis's
/// reflection flag) in tiles of `tile` pixels (use [`DEFAULT_TILE`]) and returns the closest
/// hit per pixel, row by row. Each tile goes to [`RayQuery::intersect_many`] in blocks of
/// 4 x 4 neighbouring pixels (the kd-tree traces each block as a packet; every answer is the
/// one [`RayQuery::intersect`] gives for that ray alone). Errors when
/// `rays.len() != width * height`.
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
    let init = || (Vec::new(), Vec::new());
    Ok(run_tiles(width, height, tile, init, |(order, hits), x0, y0, x1, y1, out| {
        // The tile's rays block by block (partial blocks padded with `None`), then back.
        order.clear();
        for by in (y0..y1).step_by(BLOCK.1 as usize) {
            for bx in (x0..x1).step_by(BLOCK.0 as usize) {
                for y in by..by + BLOCK.1 {
                    for x in bx..bx + BLOCK.0 {
                        let inside = x < x1 && y < y1;
                        order.push(if inside { rays[(y * width + x) as usize] } else { None });
                    }
                }
            }
        }
        hits.clear();
        hits.resize(order.len(), None);
        accel.intersect_many(order, t_max, hits);
        let w = (x1 - x0) as usize;
        out.resize(w * (y1 - y0) as usize, None);
        let mut k = 0;
        for by in (y0..y1).step_by(BLOCK.1 as usize) {
            for bx in (x0..x1).step_by(BLOCK.0 as usize) {
                for y in by..by + BLOCK.1 {
                    for x in bx..bx + BLOCK.0 {
                        if x < x1 && y < y1 {
                            out[(y - y0) as usize * w + (x - x0) as usize] = hits[k];
                        }
                        k += 1;
                    }
                }
            }
        }
    }))
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    #[test]
    fn z_order_walks_two_by_two_blocks() {
        assert_eq!(z_order(4, 2), [0, 1, 4, 5, 2, 3, 6, 7]);
        assert_eq!(spread(0b1011), 0b100_0101);
    }

    proptest! {
        /// Whatever the image and tile sizes, every pixel is computed once and the result is
        /// row-major, as if the tiles had been traced in order.
        #[test]
        fn map_tiles_is_row_major(w in 1u32..90, h in 1u32..90, tile in 1u32..50) {
            let got = map_tiles(w, h, tile, |x, y| (x, y));
            let want: Vec<(u32, u32)> =
                (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).collect();
            prop_assert_eq!(got, want);
        }
    }
}
