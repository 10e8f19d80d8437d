//! `view_points`: a grid of pinhole rays finds the points of a plane where the pinhole
//! model puts them, in the grid's order, with normals facing the camera; rays that miss
//! (beside the geometry, beyond `far`, looking away) give nothing; the thread count does not
//! change a bit.

use glam::Vec3;
use kdtree_tracer::{Hit, KdTree, Mesh, Settings as TreeSettings};
use radiance_cache::{Pinhole, SurfacePoint, view_points};

/// A mesh of `quads` (each `[corner, edge u, edge v]`, two triangles wound `u x v`) and its
/// kd-tree.
fn scene(quads: &[[Vec3; 3]]) -> (Mesh, KdTree) {
    let tris: Vec<[Vec3; 3]> = quads
        .iter()
        .flat_map(|&[o, u, v]| [[o, o + u, o + u + v], [o, o + u + v, o + v]])
        .collect();
    let mesh = Mesh::from_triangles(&tris).unwrap();
    let tree = KdTree::build(&mesh, &TreeSettings::DEFAULT).unwrap();
    (mesh, tree)
}

/// The wound normal of a hit triangle of `mesh` (what a caller without `Surfaces` passes).
fn wound_normal(mesh: &Mesh) -> impl Fn(&Hit) -> Vec3 + Sync + '_ {
    |h| {
        let [a, b, c] = mesh.triangle(h.triangle);
        (b - a).cross(c - a).normalize()
    }
}

/// A camera at (0.3, -0.2, 4) looking down -z at the plane z = 0, 4 m away.
fn camera() -> Pinhole {
    Pinhole {
        position: Vec3::new(0.3, -0.2, 4.0),
        forward: Vec3::new(0.0, 0.0, -2.0), // need not be unit
        up: Vec3::Y,
        fov_y_deg: 60.0,
        aspect: 1.5,
    }
}

const GRID: (u32, u32) = (16, 9);
/// The rays' length.
const FAR: f32 = 100.0;

/// Where the ray of grid cell `(col, row)` meets the plane z = 0, by the pinhole model.
fn expected(c: &Pinhole, col: u32, row: u32) -> Vec3 {
    let tan_y = c.tan_half_fov_y();
    let x = ((col as f32 + 0.5) / GRID.0 as f32 * 2.0 - 1.0) * tan_y * c.aspect;
    let y = (1.0 - (row as f32 + 0.5) / GRID.1 as f32 * 2.0) * tan_y;
    let d = c.position.z;
    Vec3::new(c.position.x + x * d, c.position.y + y * d, 0.0)
}

/// The plane z = 0, 40 m square, wound towards +z (`facing_camera`) or -z.
fn plane(facing_camera: bool) -> [Vec3; 3] {
    let (u, v) = (Vec3::new(40.0, 0.0, 0.0), Vec3::new(0.0, 40.0, 0.0));
    let o = Vec3::new(-20.0, -20.0, 0.0);
    if facing_camera { [o, u, v] } else { [o, v, u] }
}

#[test]
fn every_ray_finds_the_plane_where_the_pinhole_puts_it() {
    for facing in [true, false] {
        let (mesh, tree) = scene(&[plane(facing)]);
        let c = camera();
        let points = view_points(&tree, wound_normal(&mesh), &c, FAR, GRID);
        assert_eq!(points.len(), (GRID.0 * GRID.1) as usize, "every ray hits the plane");
        for (i, p) in points.iter().enumerate() {
            let (col, row) = (i as u32 % GRID.0, i as u32 / GRID.0);
            let want = expected(&c, col, row);
            assert!(
                (p.position - want).length() < 1e-4,
                "ray ({col}, {row}): {} instead of {want}",
                p.position
            );
            // Whichever way the plane is wound, the normal faces the camera (+z).
            assert!((p.normal - Vec3::Z).length() < 1e-5, "normal {} (wound {facing})", p.normal);
        }
        // Row-major from the top-left: x grows along a row, y falls down the columns.
        let (first, last) = (points[0].position, points[points.len() - 1].position);
        assert!(first.x < c.position.x && first.y > c.position.y, "top left {first}");
        assert!(last.x > c.position.x && last.y < c.position.y, "bottom right {last}");
    }
}

#[test]
fn rays_that_miss_give_no_point() {
    let c = camera();
    // Only the right half of the view has geometry: a quad from x = eye.x to 20 m.
    let right = [Vec3::new(c.position.x, -20.0, 0.0), Vec3::new(20.0, 0.0, 0.0), Vec3::Y * 40.0];
    let (mesh, tree) = scene(&[right]);
    let points = view_points(&tree, wound_normal(&mesh), &c, FAR, GRID);
    assert_eq!(points.len(), (GRID.0 / 2 * GRID.1) as usize, "the right half of the grid");
    assert!(points.iter().all(|p| p.position.x > c.position.x && p.position.z.abs() < 1e-5));
    // The hits keep the grid's order: the first is the top row's first column right of centre.
    let want = expected(&c, GRID.0 / 2, 0);
    assert!((points[0].position - want).length() < 1e-4, "{} vs {want}", points[0].position);

    let (mesh, tree) = scene(&[plane(true)]);
    assert!(view_points(&tree, wound_normal(&mesh), &c, 3.9, GRID).is_empty(), "beyond far");
    let away = Pinhole { forward: Vec3::Z, ..c };
    assert!(view_points(&tree, wound_normal(&mesh), &away, FAR, GRID).is_empty(), "looking away");
    let degenerate = Pinhole { forward: Vec3::ZERO, ..c };
    assert!(view_points(&tree, wound_normal(&mesh), &degenerate, FAR, GRID).is_empty(), "no view");
}

/// Inside a closed box of random-ish size, seen from a seeded set of eyes and directions:
/// every ray hits a wall, each point lies on the box with a normal facing the eye, and one
/// thread gives the same bits as the pool.
#[test]
fn inside_a_box_every_point_is_on_a_wall_facing_the_eye() {
    let (lo, hi) = (Vec3::new(-3.0, -1.0, -2.0), Vec3::new(4.0, 2.5, 5.0));
    let s = hi - lo;
    let (x, y, z) = (Vec3::X * s.x, Vec3::Y * s.y, Vec3::Z * s.z);
    let (mesh, tree) = scene(&[
        [lo, y, z],
        [lo + x, z, y],
        [lo, z, x],
        [lo + y, x, z],
        [lo, x, y],
        [lo + z, y, x],
    ]);
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 40) as f32 / (1u64 << 24) as f32
    };
    for _ in 0..8 {
        let eye = lo + s * Vec3::new(next(), next(), next()) * 0.8 + s * 0.1;
        let forward = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
        let c = Pinhole::new(eye, forward, Vec3::Y, 1.2f32.to_degrees(), 1.3);
        let points = view_points(&tree, wound_normal(&mesh), &c, 50.0, (12, 8));
        assert_eq!(points.len(), 96, "a closed box: every ray hits");
        for p in &points {
            let SurfacePoint { position: q, normal: n } = *p;
            let on_wall = (q - lo).abs().min_element().min((q - hi).abs().min_element()) < 1e-4;
            assert!(on_wall, "{q} is not on the box {lo}..{hi}");
            assert!(q.cmpge(lo - 1e-4).all() && q.cmple(hi + 1e-4).all(), "{q} outside");
            assert!((n.length() - 1.0).abs() < 1e-5 && n.dot(eye - q) > 0.0, "n {n} at {q}");
            // Inside the box the facing normal points inwards: towards the centre's side.
            assert!(n.dot((lo + hi) * 0.5 - q) > 0.0, "n {n} at {q}");
        }
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let serial = one.install(|| view_points(&tree, wound_normal(&mesh), &c, 50.0, (12, 8)));
        assert_eq!(serial, points, "the thread count changes nothing");
    }
}
