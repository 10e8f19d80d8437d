//! The surface points a view sees, found with camera rays on the CPU: what
//! [`RadianceCache::allocate`](crate::RadianceCache::allocate) takes when a renderer has no
//! G-buffer on the CPU (the engine's G-buffer lives on the GPU, and reading it back would
//! cost more than tracing a coarse grid of rays through the kd-tree it already has).

use crate::cache::SurfacePoint;
use glam::Vec3;
use kdtree_tracer::{Hit, Ray, RayQuery};
use rayon::prelude::*;

/// A pinhole camera as plain data (a renderer fills it from its own camera type).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pinhole {
    /// Where the rays start.
    pub eye: Vec3,
    /// Viewing direction (need not be unit).
    pub forward: Vec3,
    /// Up, roughly (the image's up is made orthogonal to `forward`).
    pub up: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Width / height.
    pub aspect: f32,
    /// Rays stop at this distance: surfaces farther away are not seen.
    pub far: f32,
}

impl Pinhole {
    /// Unit directions of a `cols x rows` grid of rays through pixel centres, row-major with
    /// the top row first (`i = row * cols + col`), in parallel (indexed, so the order is kept).
    /// A degenerate camera (zero `forward`, `up` along `forward`) gives zero directions.
    pub fn directions(&self, cols: u32, rows: u32) -> impl IndexedParallelIterator<Item = Vec3> {
        let forward = self.forward.normalize_or_zero();
        let right = forward.cross(self.up).normalize_or_zero();
        let up = right.cross(forward);
        let tan_y = (self.fov_y * 0.5).tan();
        let tan_x = tan_y * self.aspect;
        (0..cols * rows).into_par_iter().map(move |i| {
            let x = ((i % cols) as f32 + 0.5) / cols as f32 * 2.0 - 1.0;
            let y = 1.0 - ((i / cols) as f32 + 0.5) / rows as f32 * 2.0;
            (forward + right * (x * tan_x) + up * (y * tan_y)).normalize_or_zero()
        })
    }
}

/// The surface points `camera` sees through a `cols x rows` grid of rays
/// ([`Pinhole::directions`]) traced through `tracer` up to `camera.far`, in the grid's order;
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
    (cols, rows): (u32, u32),
) -> Vec<SurfacePoint>
where
    T: RayQuery + ?Sized,
    N: Fn(&Hit) -> Vec3 + Sync,
{
    let eye = camera.eye;
    camera
        .directions(cols, rows)
        .filter_map(|d| {
            let h = tracer.intersect(&Ray::new(eye, d), camera.far)?;
            let n = normal(&h);
            let n = if n.dot(d) > 0.0 { -n } else { n };
            Some(SurfacePoint::new(eye + d * h.t, n))
        })
        .collect()
}
