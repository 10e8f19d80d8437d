//! Use `kdtree_tracer` in your renderer: build a tree once over your triangles, then trace an
//! image's worth of camera rays per frame in parallel tiles into a buffer you keep, and shade
//! each hit with a shadow ray (an any-hit query). Prints the image as text.
//!
//! `cargo run -p serein-kdtree-tracer --example render`

use glam::Vec3;
use kdtree_tracer::{DEFAULT_TILE, Hit, KdTree, Mesh, Ray, Settings, test_util};

fn main() -> Result<(), kdtree_tracer::Error> {
    // Your triangles: a ground quad and two boxes (`box_triangles` is a helper for tests).
    let (a, b) = (Vec3::new(-6.0, 0.0, -6.0), Vec3::new(6.0, 0.0, 6.0));
    let mut triangles = vec![[a, Vec3::new(b.x, 0.0, a.z), b], [a, b, Vec3::new(a.x, 0.0, b.z)]];
    triangles
        .extend(test_util::box_triangles(Vec3::new(-2.5, 0.0, -1.0), Vec3::new(-0.5, 2.0, 1.0)));
    triangles.extend(test_util::box_triangles(Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 3.5, 1.0)));
    let mesh = Mesh::from_triangles(&triangles)?;

    // Build once (static geometry) and check the tree's invariants.
    let tree = KdTree::build(&mesh, &Settings::DEFAULT)?;
    tree.validate(&mesh)?;

    // Every frame: one ray per pixel (`None` where a pixel needs no ray), traced in parallel
    // tiles into a buffer the renderer keeps. Text cells are twice as tall as wide.
    let (width, height) = (72u32, 28u32);
    let camera = test_util::Camera {
        eye: Vec3::new(0.0, 4.0, 9.0),
        target: Vec3::new(0.0, 1.0, 0.0),
        up: Vec3::Y,
        fov_y: 40f32.to_radians(),
    };
    let rays: Vec<Option<Ray>> = (0..width * height)
        .map(|i| {
            let (x, y) = ((i % width) as f32, (i / width) as f32);
            Some(camera.ray(x, 2.0 * y + 0.5, width, 2 * height))
        })
        .collect();
    let mut hits: Vec<Option<Hit>> = vec![None; rays.len()];
    kdtree_tracer::trace_tiles_into(
        &tree,
        width,
        height,
        &rays,
        f32::INFINITY,
        DEFAULT_TILE,
        &mut hits,
    )?;

    // Shade: Lambert under a sun, with a shadow ray from each visible point.
    let to_sun = Vec3::new(0.5, 1.0, 0.3).normalize();
    let shades = b" .:-=+*#%@";
    for y in 0..height {
        let row: String = (0..width)
            .map(|x| {
                let i = (y * width + x) as usize;
                let (Some(hit), Some(ray)) = (hits[i], rays[i]) else { return ' ' };
                let n = test_util::triangle_normal(&mesh, hit.triangle);
                let n = if n.dot(ray.dir) > 0.0 { -n } else { n };
                let p = ray.at(hit.t) + n * 1e-3;
                let lit = !tree.occluded(&Ray::new(p, to_sun), f32::INFINITY);
                let e = 0.1 + if lit { 0.9 * n.dot(to_sun).max(0.0) } else { 0.0 };
                shades[((e * 9.99) as usize).min(9)] as char
            })
            .collect();
        println!("{row}");
    }
    Ok(())
}
