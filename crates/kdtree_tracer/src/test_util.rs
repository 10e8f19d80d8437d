//! Seeded scene and ray generators for tests, benchmarks and examples: a city-like block of
//! boxes, subdivided spheres, a random triangle soup, a Cornell box, camera rays, incoherent
//! (random hemisphere) rays from surface points and mirror-reflection rays of a view.

use glam::{Vec2, Vec3};

use crate::mesh::Mesh;
use crate::ray::{Hit, Ray, RayQuery};

pub use crate::test_meshes::{atrium, blob, cable, scan};

/// A small seeded generator (PCG32), so scenes are identical on every machine.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        let mut r = Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xDA3E_39CB_94B9_5BDB);
        r.next_u32();
        r
    }
    pub fn next_u32(&mut self) -> u32 {
        let old = self.0;
        self.0 =
            old.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let xs = (((old >> 18) ^ old) >> 27) as u32;
        xs.rotate_right((old >> 59) as u32)
    }
    /// Uniform in `[0, 1)`.
    pub fn f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f32()
    }
    pub fn below(&mut self, n: u32) -> u32 {
        ((self.next_u32() as u64 * n as u64) >> 32) as u32
    }
    /// Uniform direction on the unit sphere.
    pub fn sphere(&mut self) -> Vec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f32::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
    /// Uniform direction in the hemisphere around `n`.
    pub fn hemisphere(&mut self, n: Vec3) -> Vec3 {
        let d = self.sphere();
        if d.dot(n) < 0.0 { -d } else { d }
    }
}

/// The 12 triangles of an axis-aligned box.
pub fn box_triangles(lo: Vec3, hi: Vec3) -> Vec<[Vec3; 3]> {
    let c = |i: u32| {
        Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    const QUADS: [[u32; 4]; 6] =
        [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    QUADS.iter().flat_map(|q| [[c(q[0]), c(q[1]), c(q[2])], [c(q[0]), c(q[2]), c(q[3])]]).collect()
}

/// A city-like block: a ground plane and a grid of box buildings of random footprint and
/// height (y up), about `triangles` triangles in all (12 per building). The thesis's scene
/// had about 19k triangles; `city_block(1, 20_000)` is its stand-in.
pub fn city_block(seed: u64, triangles: usize) -> Mesh {
    let mut rng = Rng::new(seed);
    let buildings = (triangles.saturating_sub(2) / 12).max(1);
    let side = (buildings as f32).sqrt().ceil() as usize;
    let cell = 10.0;
    let extent = side as f32 * cell;
    let mut tris = vec![
        [Vec3::ZERO, Vec3::new(0.0, 0.0, extent), Vec3::new(extent, 0.0, extent)],
        [Vec3::ZERO, Vec3::new(extent, 0.0, extent), Vec3::new(extent, 0.0, 0.0)],
    ];
    for b in 0..buildings {
        let (i, j) = ((b % side) as f32, (b / side) as f32);
        let w = rng.range(3.0, 8.0);
        let d = rng.range(3.0, 8.0);
        let h = rng.range(4.0, 40.0) * if rng.f32() < 0.1 { 2.5 } else { 1.0 };
        let x = i * cell + rng.range(0.5, cell - w - 0.5).max(0.5);
        let z = j * cell + rng.range(0.5, cell - d - 0.5).max(0.5);
        tris.extend(box_triangles(Vec3::new(x, 0.0, z), Vec3::new(x + w, h, z + d)));
    }
    Mesh::from_triangles(&tris).expect("generated geometry is finite")
}

/// An icosphere: the icosahedron subdivided `level` times and projected onto the sphere
/// (20 * 4^level triangles, closed and indexed: shared edges are exactly shared).
pub fn icosphere(center: Vec3, radius: f32, level: u32) -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut v: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mut mid = std::collections::HashMap::new();
        let mut m = |a: u32, b: u32, v: &mut Vec<Vec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(((v[a as usize] + v[b as usize]) * 0.5).normalize());
                v.len() as u32 - 1
            })
        };
        let mut nf = Vec::with_capacity(f.len() * 4);
        for [a, b, c] in f {
            let (ab, bc, ca) = (m(a, b, &mut v), m(b, c, &mut v), m(c, a, &mut v));
            nf.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = nf;
    }
    let p: Vec<Vec3> = v.iter().map(|&q| center + q * radius).collect();
    Mesh::from_indexed(&p, &f).expect("generated geometry is valid")
}

/// A UV sphere with `stacks * slices * 2 - 2 * slices` triangles (use for exact large counts:
/// `uv_sphere(500, 1000)` has 999 000).
pub fn uv_sphere(stacks: u32, slices: u32) -> Mesh {
    let (stacks, slices) = (stacks.max(2), slices.max(3));
    let mut p = Vec::new();
    for i in 0..=stacks {
        let th = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let ph = std::f32::consts::TAU * j as f32 / slices as f32;
            p.push(Vec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()));
        }
    }
    let id = |i: u32, j: u32| i * slices + j % slices;
    let mut f = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b, c, d) = (id(i, j), id(i, j + 1), id(i + 1, j), id(i + 1, j + 1));
            if i > 0 {
                f.push([a, b, d]);
            }
            if i + 1 < stacks {
                f.push([a, d, c]);
            }
        }
    }
    Mesh::from_indexed(&p, &f).expect("generated geometry is valid")
}

/// `n` random triangles (edges up to `size`) inside the unit cube.
pub fn random_soup(seed: u64, n: usize, size: f32) -> Mesh {
    let mut rng = Rng::new(seed);
    let tris: Vec<[Vec3; 3]> = (0..n)
        .map(|_| {
            let c = Vec3::new(rng.f32(), rng.f32(), rng.f32());
            let mut q = || c + (Vec3::new(rng.f32(), rng.f32(), rng.f32()) - 0.5) * size;
            [q(), q(), q()]
        })
        .collect();
    Mesh::from_triangles(&tris).expect("generated geometry is finite")
}

/// A Cornell box (floor, ceiling, three walls, two boxes) in `[-1, 1] x [0, 2] x [-1, 1]`,
/// one mesh id per part (7 meshes).
pub fn cornell_box() -> Mesh {
    let mut m = Mesh::new();
    let quad = |a: Vec3, b: Vec3, c: Vec3, d: Vec3| vec![[a, b, c], [a, c, d]];
    let parts = [
        quad(
            Vec3::new(-1., 0., -1.),
            Vec3::new(-1., 0., 1.),
            Vec3::new(1., 0., 1.),
            Vec3::new(1., 0., -1.),
        ),
        quad(
            Vec3::new(-1., 2., -1.),
            Vec3::new(1., 2., -1.),
            Vec3::new(1., 2., 1.),
            Vec3::new(-1., 2., 1.),
        ),
        quad(
            Vec3::new(-1., 0., -1.),
            Vec3::new(1., 0., -1.),
            Vec3::new(1., 2., -1.),
            Vec3::new(-1., 2., -1.),
        ),
        quad(
            Vec3::new(-1., 0., -1.),
            Vec3::new(-1., 2., -1.),
            Vec3::new(-1., 2., 1.),
            Vec3::new(-1., 0., 1.),
        ),
        quad(
            Vec3::new(1., 0., -1.),
            Vec3::new(1., 0., 1.),
            Vec3::new(1., 2., 1.),
            Vec3::new(1., 2., -1.),
        ),
        box_triangles(Vec3::new(0.1, 0.0, 0.1), Vec3::new(0.6, 0.6, 0.6)),
        box_triangles(Vec3::new(-0.6, 0.0, -0.6), Vec3::new(-0.1, 1.2, -0.1)),
    ];
    for t in parts {
        let p: Vec<Vec3> = t.iter().flatten().copied().collect();
        let idx: Vec<[u32; 3]> =
            (0..t.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        m.push(&p, &idx).expect("generated geometry is finite");
    }
    m
}

/// A pinhole camera.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    /// Vertical field of view in radians.
    pub fov_y: f32,
}

impl Camera {
    /// The ray through the centre of pixel `(x, y)` (y down) of a `width x height` image.
    pub fn ray(&self, x: f32, y: f32, width: u32, height: u32) -> Ray {
        let f = (self.target - self.eye).normalize();
        let r = f.cross(self.up).normalize();
        let u = r.cross(f);
        let h = (self.fov_y * 0.5).tan();
        let aspect = width as f32 / height as f32;
        let sx = (2.0 * (x + 0.5) / width as f32 - 1.0) * h * aspect;
        let sy = (1.0 - 2.0 * (y + 0.5) / height as f32) * h;
        Ray::new(self.eye, (f + r * sx + u * sy).normalize())
    }

    /// A camera looking down over a [`city_block`] so that the screen is filled with geometry.
    pub fn over_city(mesh: &Mesh) -> Self {
        let (lo, hi) = mesh.bounds().unwrap_or((Vec3::ZERO, Vec3::ONE));
        let c = (lo + hi) * 0.5;
        let ext = (hi - lo).max_element();
        Self {
            eye: Vec3::new(c.x - 0.15 * ext, hi.y + 0.35 * ext, c.z - 0.15 * ext),
            target: Vec3::new(c.x, 0.0, c.z),
            up: Vec3::Y,
            fov_y: 50f32.to_radians(),
        }
    }
}

/// Geometric normal of a mesh triangle (zero for degenerate ones).
pub fn triangle_normal(mesh: &Mesh, triangle: u32) -> Vec3 {
    let [a, b, c] = mesh.triangle(triangle);
    (b - a).cross(c - a).normalize_or_zero()
}

/// Incoherent secondary rays for a `width x height` screen (the thesis's reflection-ray
/// buffer, worst case): camera rays are traced, and every pixel that hits gets a ray from
/// the hit point in a uniformly random direction of the hemisphere facing the camera. Pixels
/// that miss get `None`.
pub fn screen_incoherent_rays(
    accel: &impl RayQuery,
    mesh: &Mesh,
    camera: &Camera,
    width: u32,
    height: u32,
    seed: u64,
) -> Vec<Option<Ray>> {
    let mut rng = Rng::new(seed);
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let primary = camera.ray(x as f32, y as f32, width, height);
            out.push(
                accel
                    .intersect(&primary, f32::INFINITY)
                    .map(|h| secondary(&mut rng, mesh, &primary, &h)),
            );
        }
    }
    out
}

/// Mirror-reflection rays for a `width x height` screen (the thesis's reflection buffer as it
/// traces it: every visible pixel reflects its camera ray about the hit triangle's normal).
/// Unlike [`screen_incoherent_rays`] these are spatially coherent: neighbouring pixels on one
/// surface get nearby origins and nearby (on a flat surface, identical up to the camera's
/// spread) directions. Pixels that miss get `None`.
pub fn screen_mirror_rays(
    accel: &impl RayQuery,
    mesh: &Mesh,
    camera: &Camera,
    width: u32,
    height: u32,
) -> Vec<Option<Ray>> {
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let primary = camera.ray(x as f32, y as f32, width, height);
            out.push(accel.intersect(&primary, f32::INFINITY).map(|h| mirror(mesh, &primary, &h)));
        }
    }
    out
}

fn mirror(mesh: &Mesh, primary: &Ray, h: &Hit) -> Ray {
    let n = facing_normal(mesh, primary, h);
    let d = primary.dir;
    Ray::new(offset_point(primary, h, n), d - n * (2.0 * d.dot(n)))
}

/// The hit triangle's normal on the side the ray came from.
fn facing_normal(mesh: &Mesh, primary: &Ray, h: &Hit) -> Vec3 {
    let n = triangle_normal(mesh, h.triangle);
    if n.dot(primary.dir) > 0.0 { -n } else { n }
}

/// The hit point moved off the surface along `n` (scaled to the coordinates' magnitude).
fn offset_point(primary: &Ray, h: &Hit, n: Vec3) -> Vec3 {
    let p = primary.at(h.t);
    p + n * 1e-4 * (1.0 + p.abs().max_element())
}

fn secondary(rng: &mut Rng, mesh: &Mesh, primary: &Ray, h: &Hit) -> Ray {
    let n = facing_normal(mesh, primary, h);
    Ray::new(offset_point(primary, h, n), rng.hemisphere(n)).with_t_min(0.0)
}

/// `n` incoherent rays: from random points on random triangles, in random directions of the
/// hemisphere on a random side of the triangle (kdbench's "incoherent" rays).
pub fn surface_rays(mesh: &Mesh, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    let count = mesh.triangle_count() as u32;
    if count == 0 {
        return Vec::new();
    }
    (0..n)
        .map(|_| {
            let t = rng.below(count);
            let [a, b, c] = mesh.triangle(t);
            let (mut u, mut v) = (rng.f32(), rng.f32());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            let p = a + (b - a) * u + (c - a) * v;
            let mut nrm = triangle_normal(mesh, t);
            if rng.f32() < 0.5 {
                nrm = -nrm;
            }
            let dir = if nrm == Vec3::ZERO { rng.sphere() } else { rng.hemisphere(nrm) };
            Ray::new(p + nrm * 1e-4 * (1.0 + p.abs().max_element()), dir)
        })
        .collect()
}

/// Camera rays for a whole image, row by row.
pub fn camera_rays(camera: &Camera, width: u32, height: u32) -> Vec<Ray> {
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| camera.ray(x as f32, y as f32, width, height))
        .collect()
}

/// Barycentric-weighted point of a hit, for checks.
pub fn hit_point(mesh: &Mesh, h: &Hit) -> Vec3 {
    let [a, b, c] = mesh.triangle(h.triangle);
    h.interpolate([a, b, c])
}

/// Per-vertex UVs for a triangle soup mesh laid out in the xz plane (`uv = xz * scale`).
pub fn planar_uvs(p: [Vec3; 3], scale: f32) -> [Vec2; 3] {
    p.map(|q| Vec2::new(q.x, q.z) * scale)
}
