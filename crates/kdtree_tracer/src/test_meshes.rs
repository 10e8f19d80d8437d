//! More seeded test meshes of different character, for the sweep's comparisons: a closed
//! organic blob, a long thin cable, an architectural atrium with large open areas, and a
//! scanned-style closed mesh with very uneven triangle sizes.

use glam::Vec3;

use crate::mesh::Mesh;
use crate::test_util::{box_triangles, icosphere};

/// A closed organic mesh: an icosphere (`20 * 4^level` triangles) with its vertices pushed in
/// and out along the normal by a sum of waves (a lumpy potato, not a sphere).
pub fn blob(level: u32) -> Mesh {
    let s = icosphere(Vec3::ZERO, 1.0, level);
    let p: Vec<Vec3> = s
        .positions()
        .iter()
        .map(|&q| {
            let bump = 0.25 * (3.0 * q.x + 1.0).sin() * (2.0 * q.y).cos()
                + 0.12 * (7.0 * q.z + 2.0 * q.x).sin()
                + 0.05 * (17.0 * q.y + 5.0 * q.z).sin();
            q * (1.0 + bump)
        })
        .collect();
    Mesh::from_indexed(&p, s.indices()).expect("generated geometry is valid")
}

/// How strongly [`scan`] crowds its vertices to one side: triangle areas shrink by up to
/// `SCAN_CROWD^2` on the dense side and grow by as much on the sparse one.
const SCAN_CROWD: f64 = 6.0;

/// A scanned-style closed mesh with very uneven triangle sizes: an icosphere
/// (`20 * 4^level` triangles: level 3 about 1k, 5 about 20k, 7 about 330k, 8 about 1.3M)
/// whose vertices are crowded towards one side by a Möbius map of the sphere (stereographic
/// projection, scaled by [`SCAN_CROWD`], projected back), as a scan's triangles gather where
/// the scanner saw detail; then pushed in and out along the radius by waves of a coarse, a
/// middle and a fine frequency and stretched into a standing figure (2 high). The smallest and
/// largest triangles differ in area by about a thousandfold; the map is conformal (no
/// slivers) and radial displacement keeps the surface closed and free of self-intersections;
/// shared edges stay exactly shared.
pub fn scan(level: u32) -> Mesh {
    let s = icosphere(Vec3::ZERO, 1.0, level);
    let k = SCAN_CROWD;
    let p: Vec<Vec3> = s
        .positions()
        .iter()
        .map(|&q| {
            let q = q.as_dvec3();
            // Stereographic projection from the pole +y, scaled, and back onto the sphere.
            let d = 1.0 - q.y;
            let q = if d < 1e-12 {
                q
            } else {
                let (wx, wz) = (k * q.x / d, k * q.z / d);
                let r2 = wx * wx + wz * wz;
                glam::DVec3::new(2.0 * wx, r2 - 1.0, 2.0 * wz) / (r2 + 1.0)
            };
            let r = 1.0
                + 0.18 * (2.1 * q.x + 0.3).sin() * (1.7 * q.y).cos()
                + 0.07 * (5.0 * q.z + 3.0 * q.x).sin()
                + 0.015 * (23.0 * q.x + 19.0 * q.y + 17.0 * q.z).sin();
            (q * r * glam::DVec3::new(0.7, 1.0, 0.55)).as_vec3()
        })
        .collect();
    Mesh::from_indexed(&p, s.indices()).expect("generated geometry is valid")
}

/// A long thin mesh: a tube of radius 0.15 wound loosely around the x axis over a length of
/// 200, `segments * sides * 2` triangles (closed around, open at the ends).
pub fn cable(segments: u32, sides: u32) -> Mesh {
    let (segments, sides) = (segments.max(1), sides.max(3));
    let mut p = Vec::new();
    for i in 0..=segments {
        let s = i as f32 / segments as f32;
        let x = 200.0 * s;
        let centre = Vec3::new(x, 1.5 * (0.2 * x).sin(), 1.5 * (0.2 * x).cos());
        for j in 0..sides {
            let a = std::f32::consts::TAU * j as f32 / sides as f32;
            p.push(centre + Vec3::new(0.0, a.cos(), a.sin()) * 0.15);
        }
    }
    let id = |i: u32, j: u32| i * sides + j % sides;
    let mut f = Vec::new();
    for i in 0..segments {
        for j in 0..sides {
            f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh::from_indexed(&p, &f).expect("generated geometry is valid")
}

/// A cylinder (side only) from `base` up by `height`, `sides` around and `rings` high.
fn column(base: Vec3, radius: f32, height: f32, sides: u32, rings: u32) -> Vec<[Vec3; 3]> {
    let at = |i: u32, j: u32| {
        let a = std::f32::consts::TAU * j as f32 / sides as f32;
        base + Vec3::new(a.cos() * radius, height * i as f32 / rings as f32, a.sin() * radius)
    };
    let mut out = Vec::new();
    for i in 0..rings {
        for j in 0..sides {
            out.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            out.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    out
}

/// An architectural scene with large open areas: a 120 x 80 hall of three storeys whose floor
/// slabs leave a central atrium open, a grid of round columns, partition walls with doorways
/// on each storey, and outer walls with window openings (about 40k triangles).
pub fn atrium() -> Mesh {
    let (w, d, storey, storeys) = (120.0f32, 80.0f32, 6.0f32, 3);
    let mut t = Vec::new();
    let slab = |t: &mut Vec<[Vec3; 3]>, y: f32, lo: Vec3, hi: Vec3| {
        t.extend(box_triangles(Vec3::new(lo.x, y - 0.3, lo.z), Vec3::new(hi.x, y, hi.z)));
    };
    for s in 0..=storeys {
        let y = s as f32 * storey;
        if s == 0 || s == storeys {
            slab(&mut t, y.max(0.3), Vec3::ZERO, Vec3::new(w, 0.0, d));
            continue;
        }
        // A ring of slab around the open atrium [40, 80] x [25, 55].
        slab(&mut t, y, Vec3::ZERO, Vec3::new(40.0, 0.0, d));
        slab(&mut t, y, Vec3::new(80.0, 0.0, 0.0), Vec3::new(w, 0.0, d));
        slab(&mut t, y, Vec3::new(40.0, 0.0, 0.0), Vec3::new(80.0, 0.0, 25.0));
        slab(&mut t, y, Vec3::new(40.0, 0.0, 55.0), Vec3::new(80.0, 0.0, d));
    }
    for s in 0..storeys {
        let y = s as f32 * storey;
        for i in 0..12 {
            for j in 0..8 {
                let c = Vec3::new(5.0 + 10.0 * i as f32, y, 5.0 + 10.0 * j as f32);
                t.extend(column(c, 0.4, storey - 0.3, 24, 4));
            }
        }
        // Partition walls with a doorway, in the side wings.
        for k in 0..8 {
            let z = 10.0 * k as f32;
            for (x0, x1) in [(0.0, 17.0), (20.0, 38.0), (82.0, 100.0), (103.0, 120.0)] {
                t.extend(box_triangles(
                    Vec3::new(x0, y, z + 0.1),
                    Vec3::new(x1, y + storey - 0.3, z + 0.3),
                ));
            }
        }
        // Outer walls: piers between windows and a sill below and lintel above them.
        for k in 0..24 {
            let x = 5.0 * k as f32;
            for z in [0.0f32, d - 0.4] {
                t.extend(box_triangles(
                    Vec3::new(x, y, z),
                    Vec3::new(x + 1.5, y + storey, z + 0.4),
                ));
                t.extend(box_triangles(
                    Vec3::new(x + 1.5, y, z),
                    Vec3::new(x + 5.0, y + 1.0, z + 0.4),
                ));
                t.extend(box_triangles(
                    Vec3::new(x + 1.5, y + storey - 1.0, z),
                    Vec3::new(x + 5.0, y + storey, z + 0.4),
                ));
            }
        }
    }
    Mesh::from_triangles(&t).expect("generated geometry is finite")
}
