//! The CPU path from a camera, as a renderer without a G-buffer on the CPU runs it: a room
//! (floor, walls, ceiling; one wall missing), a pinhole camera in it, `view_points` for the
//! surfaces it sees, then a few frames of `refresh` lit by VPLs on a sunlit patch of floor.
//! Prints each frame's summary and the irradiance the lookup gives a few of the points.
//!
//! `cargo run -p serein-radiance-cache --example view`

use glam::Vec3;
use kdtree_tracer::{Hit, KdTree, Mesh, Settings as TreeSettings};
use radiance_cache::{Pinhole, RadianceCache, Settings, view_points};
use shadows::Vpl;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A 6 x 3 x 6 m room open towards +z, each wall two triangles.
    let quad = |o: Vec3, u: Vec3, v: Vec3| [[o, o + u, o + u + v], [o, o + u + v, o + v]];
    let (x, y, z) = (Vec3::X * 6.0, Vec3::Y * 3.0, Vec3::Z * 6.0);
    let o = Vec3::new(-3.0, 0.0, -3.0);
    let walls = [quad(o, z, x), quad(o + y, x, z), quad(o, y, z), quad(o + x, z, y), quad(o, x, y)];
    let mesh = Mesh::from_triangles(&walls.concat())?;
    let tree = KdTree::build(&mesh, &TreeSettings::DEFAULT)?;
    let normal = |h: &Hit| {
        let [a, b, c] = mesh.triangle(h.triangle);
        (b - a).cross(c - a).normalize()
    };

    // The camera stands in the opening and looks in, slightly down.
    let camera = Pinhole::new(
        Vec3::new(0.0, 1.6, 2.8),
        Vec3::new(0.0, -0.2, -1.0),
        Vec3::Y,
        60.0,
        16.0 / 9.0,
    );
    let points = view_points(&tree, normal, &camera, 100.0, (64, 36));
    println!("{} of {} camera rays found a surface", points.len(), 64 * 36);

    // A 1 m² sunlit patch on the floor as 16 VPLs.
    let vpls: Vec<Vpl> = (0..16)
        .map(|i| Vpl {
            position: Vec3::new((i % 4) as f32 * 0.25 - 0.4, 0.0, (i / 4) as f32 * 0.25 - 0.4),
            normal: Vec3::Y,
            flux: Vec3::new(1.0, 0.9, 0.7) / 16.0,
        })
        .collect();
    let mut cache = RadianceCache::new(Settings::LOW)?;
    for frame in 0..4 {
        let summary = cache.refresh(camera.position, &points, &vpls, &tree);
        println!("frame {frame}: {summary}");
    }
    for p in points.iter().step_by(points.len() / 5) {
        let e = cache.irradiance(p.position, p.normal);
        println!("E at {:.2} (normal {:.2}) = {e:.4}", p.position, p.normal);
    }
    Ok(())
}
