//! Tiled parallel tracing of image-shaped ray buffers (thesis 6.2.5: 40x40-pixel jobs taken
//! from a queue by one thread per core; here rayon's work stealing is the queue). Tiles are
//! handed to rayon along a Z-order (Morton) curve, so each thread's contiguous share of the
//! list is a compact block of the image (rays of nearby pixels meet nearby geometry). Every
//! tile is its own rayon job (`with_max_len(1)`): left to itself, rayon splits the list into a
//! few runs of tiles per thread and a run, once started, cannot be stolen, so on the mirror
//! buffer one of two threads sat idle for the last quarter of the call.

use std::cell::RefCell;

use rayon::prelude::*;

use crate::error::Error;
use crate::ray::{Hit, Ray, RayQuery};

/// The thesis's job size.
pub const DEFAULT_TILE: u32 = 40;

/// Evaluates `f(x, y)` for every pixel of a `width x height` image, one rayon task per
/// `tile x tile` block (handed out along the Z-order curve), and returns the results row by
/// row. The result does not depend on the number of threads (each pixel is computed
/// independently).
pub fn map_tiles<T, F>(width: u32, height: u32, tile: u32, f: F) -> Vec<T>
where
    T: Send,
    F: Fn(u32, u32) -> T + Sync,
{
    let tile = tile.max(1);
    let (tx, ty) = (width.div_ceil(tile), height.div_ceil(tile));
    let order = z_order(tx, ty);
    let done: Vec<Vec<T>> = order
        .par_iter()
        .with_max_len(1)
        .map(|&i| {
            let [x0, y0, x1, y1] = tile_rect(i, width, height, tile);
            (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x, y))).map(|(x, y)| f(x, y)).collect()
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

/// Tile `i` (row-major) of a `width x height` image in `tile x tile` blocks (`tile >= 1`) as
/// `[x0, y0, x1, y1]`, `x1` and `y1` exclusive.
fn tile_rect(i: u32, width: u32, height: u32, tile: u32) -> [u32; 4] {
    let tx = width.div_ceil(tile);
    let (x0, y0) = ((i % tx) * tile, (i / tx) * tile);
    [x0, y0, (x0 + tile).min(width), (y0 + tile).min(height)]
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
/// `rays.len() != width * height`. A renderer tracing a buffer every frame keeps its output
/// and calls [`trace_tiles_into`].
pub fn trace_tiles<A: RayQuery + ?Sized>(
    accel: &A,
    width: u32,
    height: u32,
    rays: &[Option<Ray>],
    t_max: f32,
    tile: u32,
) -> Result<Vec<Option<Hit>>, Error> {
    let mut out = vec![None; rays.len()];
    trace_tiles_into(accel, width, height, rays, t_max, tile, &mut out)?;
    Ok(out)
}

/// [`trace_tiles`] into the caller's buffer (`width * height` hits, row by row; every pixel
/// is written), which a renderer keeps from frame to frame: nothing of the image's size is
/// allocated (each tile writes its hits into place). Errors when `rays` or `out` does not
/// hold `width * height` pixels.
pub fn trace_tiles_into<A: RayQuery + ?Sized>(
    accel: &A,
    width: u32,
    height: u32,
    rays: &[Option<Ray>],
    t_max: f32,
    tile: u32,
    out: &mut [Option<Hit>],
) -> Result<(), Error> {
    let expected = width as usize * height as usize;
    for len in [rays.len(), out.len()] {
        if len != expected {
            return Err(Error::BufferSize { len, width, height, expected });
        }
    }
    let tile = tile.max(1);
    let image = Pixels(out.as_mut_ptr());
    z_order(width.div_ceil(tile), height.div_ceil(tile)).par_iter().with_max_len(1).for_each(
        |&i| {
            let rect = tile_rect(i, width, height, tile);
            // The thread's buffers, or new ones when this thread is already inside a tile (an
            // `intersect_many` that waits on rayon may run another tile meanwhile).
            SCRATCH.with(|cell| match cell.try_borrow_mut() {
                Ok(mut s) => {
                    trace_tile(accel, rect, width, rays, t_max, &image, &mut s);
                    // A huge tile's buffers are not kept for the thread's life.
                    if s.0.capacity() > KEPT_SCRATCH {
                        *s = TileScratch::default();
                    }
                }
                Err(_) => {
                    trace_tile(accel, rect, width, rays, t_max, &image, &mut Default::default())
                }
            })
        },
    );
    Ok(())
}

/// Traces the tile `[x0, x1) x [y0, y1)` block by block into `image`, with a [`TileScratch`] for
/// the tile's rays in block order and their hits.
fn trace_tile<A: RayQuery + ?Sized>(
    accel: &A,
    [x0, y0, x1, y1]: [u32; 4],
    width: u32,
    rays: &[Option<Ray>],
    t_max: f32,
    image: &Pixels,
    (order, hits): &mut TileScratch,
) {
    // The tile's rays block by block (partial blocks padded with `None`).
    order.clear();
    for_blocks(x0, y0, x1, y1, |x, y| {
        let inside = x < x1 && y < y1;
        order.push(if inside { rays[(y * width + x) as usize] } else { None });
    });
    hits.clear();
    hits.resize(order.len(), None);
    accel.intersect_many(order, t_max, hits);
    let mut k = 0;
    for_blocks(x0, y0, x1, y1, |x, y| {
        if x < x1 && y < y1 {
            // SAFETY: `(x, y)` is inside the image (`x < x1 <= width`, `y < y1 <= height`, so
            // below the image's length) and inside this tile; the tiles are disjoint, so no
            // other task writes this pixel, and the image is borrowed mutably for the whole
            // call of `trace_tiles_into`.
            unsafe { image.write((y * width + x) as usize, hits[k]) };
        }
        k += 1;
    });
}

/// Rays of the largest tile whose buffers a thread keeps (a 128x128 tile; the default 40x40
/// holds 1,600).
const KEPT_SCRATCH: usize = 1 << 14;

/// A tile's rays in block order and their hits.
type TileScratch = (Vec<Option<Ray>>, Vec<Option<Hit>>);

thread_local! {
    /// A tile's rays in block order and their hits, kept per thread from tile to tile (a tile
    /// is its own rayon job, so buffers made per job would be made per tile).
    static SCRATCH: RefCell<TileScratch> = const {
        RefCell::new((Vec::new(), Vec::new()))
    };
}

/// Calls `f(x, y)` for the pixels of the tile `[x0, x1) x [y0, y1)` in [`BLOCK`]s (row by
/// row within a block), partial blocks at the tile's right and bottom edges padded to whole
/// ones.
#[inline(always)]
fn for_blocks(x0: u32, y0: u32, x1: u32, y1: u32, mut f: impl FnMut(u32, u32)) {
    for by in (y0..y1).step_by(BLOCK.1 as usize) {
        for bx in (x0..x1).step_by(BLOCK.0 as usize) {
            for y in by..by + BLOCK.1 {
                for x in bx..bx + BLOCK.0 {
                    f(x, y);
                }
            }
        }
    }
}

/// The output image shared by the tile tasks, each writing only its own pixels.
struct Pixels(*mut Option<Hit>);

// SAFETY: the tasks write disjoint pixels (see `trace_tiles_into`); `Option<Hit>` is `Send`.
unsafe impl Sync for Pixels {}

impl Pixels {
    /// # Safety
    /// `i` is inside the image and no other thread reads or writes pixel `i` meanwhile.
    #[inline(always)]
    unsafe fn write(&self, i: usize, hit: Option<Hit>) {
        // SAFETY: the caller's contract.
        unsafe { self.0.add(i).write(hit) }
    }
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

    /// A thread keeps the buffers of default-sized tiles from call to call, not those of a
    /// huge tile.
    #[test]
    fn threads_keep_small_tile_buffers_only() {
        let mesh = crate::test_util::city_block(1, 200);
        let tree = crate::KdTree::build(&mesh, &crate::Settings::DEFAULT).unwrap();
        let (w, h) = (200u32, 150u32);
        let rays: Vec<Option<Ray>> = (0..w * h)
            .map(|i| Some(Ray::new(glam::Vec3::new(i as f32 % 7.0, 50.0, 1.0), -glam::Vec3::Y)))
            .collect();
        let mut out = vec![None; rays.len()];
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let kept = |tile: u32, out: &mut [Option<Hit>]| {
            pool.install(|| {
                trace_tiles_into(&tree, w, h, &rays, f32::INFINITY, tile, out).unwrap();
                SCRATCH.with(|s| s.borrow().0.capacity())
            })
        };
        assert!((1600..=KEPT_SCRATCH).contains(&kept(DEFAULT_TILE, &mut out)));
        assert_eq!(kept(200, &mut out), 0, "a 200x200 tile's buffers were kept");
        assert!(out.iter().all(Option::is_some));
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
