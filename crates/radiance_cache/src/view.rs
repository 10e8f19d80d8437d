//! The surface points a view sees, found with camera rays on the CPU: what
//! [`RadianceCache::allocate`](crate::RadianceCache::allocate) takes when a renderer has no
//! G-buffer on the CPU (the engine's G-buffer lives on the GPU, and reading it back would
//! cost more than tracing a coarse grid of rays through the kd-tree it already has).

use crate::cache::SurfacePoint;
use glam::Vec3;
use kdtree_tracer::{Hit, Ray, RayQuery};
use rayon::prelude::*;

/// The camera [`view_points`] looks through: the one pinhole camera of the serein crates.
pub use vocab::Pinhole;

/// Unit directions of a `cols x rows` grid of rays through pixel centres of `camera`,
/// row-major with the top row first (`i = row * cols + col`), in parallel (indexed, so the
/// order is kept). A degenerate camera (zero `forward`, `up` along `forward`) gives zero
/// directions.
pub fn grid_directions(
    camera: &Pinhole,
    cols: u32,
    rows: u32,
) -> impl IndexedParallelIterator<Item = Vec3> + '_ {
    (0..cols * rows).into_par_iter().map(move |i| {
        let (x, y) = ((i % cols) as f32 + 0.5, (i / cols) as f32 + 0.5);
        camera.pixel_direction(x, y, cols, rows)
    })
}

/// The surface points `camera` sees through a `cols x rows` grid of rays
/// ([`grid_directions`]) traced through `tracer` up to `far`, in the grid's order;
/// rays that hit nothing give no point.
///
/// `normal` gives the unit geometric normal of a hit's triangle (any orientation: each
/// point's normal is turned to face the camera). [`RayQuery`] answers where a ray hits, not
/// how the surface there is oriented, so the caller, who knows its mesh, says it: for a
/// [`kdtree_tracer::Surfaces`], `|h| surfaces.normal(h.triangle)`; for a plain
/// [`kdtree_tracer::Mesh`], the normalised cross product of the corners of
/// `mesh.triangle(h.triangle)`.
///
/// Deterministic: the same inputs give the same points, bit for bit, whatever the number of
/// threads.
pub fn view_points<T, N>(
    tracer: &T,
    normal: N,
    camera: &Pinhole,
    far: f32,
    (cols, rows): (u32, u32),
) -> Vec<SurfacePoint>
where
    T: RayQuery + ?Sized,
    N: Fn(&Hit) -> Vec3 + Sync,
{
    let eye = camera.position;
    grid_directions(camera, cols, rows)
        .filter_map(|d| {
            let h = tracer.intersect(&Ray::new(eye, d), far)?;
            let n = normal(&h);
            let n = if n.dot(d) > 0.0 { -n } else { n };
            Some(SurfacePoint::new(eye + d * h.t, n))
        })
        .collect()
}
