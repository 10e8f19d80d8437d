//! Occlusion quads derived from a scene's own geometry, for scenes that author none (a glTF or
//! OBJ file): without them the sky volume sees the whole sky from inside every room.
//!
//! The triangles are grouped by plane (the same unit normal up to sign within about a degree
//! and the same offset within a quarter cell) and by opacity (`1 - transparency`; alpha-tested
//! materials are left out: leaves and fences let most of the sky through). Each plane's
//! triangles are rasterised onto a grid of square cells in the plane (a cell is covered when
//! its centre lies in a triangle) and the covered cells are merged greedily into rectangles:
//! runs along each row, then runs of equal extent down the rows. A wall with a window becomes
//! the rectangles around the window. Each rectangle is one quad; at most
//! [`DeriveSettings::max_quads`] are kept, the largest first.

use crate::{OcclusionQuad, Scene};
use glam::{Vec2, Vec3};
use std::collections::HashMap;

/// Knobs of [`derive_occlusion_quads`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeriveSettings {
    /// Side of a grid cell, metres (smaller holes are closed, smaller pieces dropped).
    pub cell: f32,
    /// Most quads kept (the sky volume's fill tests every quad for every probe).
    pub max_quads: usize,
}

impl DeriveSettings {
    pub const DEFAULT: Self = Self { cell: 0.25, max_quads: 1024 };
}

impl Default for DeriveSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// One plane's triangles in its own 2D frame.
struct Plane {
    normal: Vec3,
    u: Vec3,
    v: Vec3,
    offset: f32,
    opacity: f32,
    triangles: Vec<[Vec2; 3]>,
}

/// An in-plane basis for a unit normal: `u` along the world axis the plane leans on least.
fn basis(n: Vec3) -> (Vec3, Vec3) {
    let a = n.abs();
    let helper = if a.x <= a.y && a.x <= a.z {
        Vec3::X
    } else if a.y <= a.z {
        Vec3::Y
    } else {
        Vec3::Z
    };
    let u = (helper - n * n.dot(helper)).normalize();
    (u, n.cross(u))
}

/// The normal with its largest component positive (a plane's two sides share a key).
fn canonical(n: Vec3) -> Vec3 {
    let m = if n.x.abs() >= n.y.abs() && n.x.abs() >= n.z.abs() {
        n.x
    } else if n.y.abs() >= n.z.abs() {
        n.y
    } else {
        n.z
    };
    if m < 0.0 { -n } else { n }
}

/// Planes of the scene's opaque and transparent (not alpha-tested) triangles.
fn planes(scene: &Scene, cell: f32) -> Vec<Plane> {
    let mut by_key: HashMap<(i32, i32, i32, i32, u32), usize> = HashMap::new();
    let mut planes: Vec<Plane> = Vec::new();
    let tris = scene.triangles();
    for (t, &mesh) in tris.indices.iter().zip(&tris.mesh_ids) {
        let Some(m) = scene.meshes.get(mesh as usize) else { continue };
        let Some(mat) = scene.materials.get(m.material.index()) else { continue };
        let opacity = (1.0 - mat.transparency).clamp(0.0, 1.0);
        if mat.alpha_mask.is_some() || opacity <= 0.0 {
            continue;
        }
        let [a, b, c] = t.map(|i| tris.positions[i as usize]);
        let Some(n) = (b - a).cross(c - a).try_normalize() else { continue };
        let n = canonical(n);
        let offset = n.dot(a);
        // About 1.1 degrees per normal step, a quarter cell per offset step.
        let q = |x: f32| (x * 50.0).round() as i32;
        let key =
            (q(n.x), q(n.y), q(n.z), (offset / (0.25 * cell)).round() as i32, opacity.to_bits());
        let i = *by_key.entry(key).or_insert_with(|| {
            let (u, v) = basis(n);
            planes.push(Plane { normal: n, u, v, offset, opacity, triangles: Vec::new() });
            planes.len() - 1
        });
        let p = &mut planes[i];
        p.triangles.push([a, b, c].map(|x| Vec2::new(x.dot(p.u), x.dot(p.v))));
    }
    planes
}

fn inside(p: Vec2, [a, b, c]: &[Vec2; 3]) -> bool {
    let d = |x: Vec2, y: Vec2| (y - x).perp_dot(p - x);
    let (d0, d1, d2) = (d(*a, *b), d(*b, *c), d(*c, *a));
    (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0)
}

/// Most cells along one side of a plane's grid (a bound on memory for huge planes).
const MAX_CELLS_PER_SIDE: usize = 1024;

/// The covered cells of a plane's grid merged into rectangles `(min corner, max corner)` in
/// the plane's 2D frame.
fn rectangles(plane: &Plane, cell: f32) -> Vec<(Vec2, Vec2)> {
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for t in &plane.triangles {
        for p in t {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    // The grid spans the plane's extent exactly (cells at most `cell`), so that a wall's
    // rectangle ends where the wall ends and meets its neighbours without a gap.
    let cell = cell.max((hi - lo).max_element() / MAX_CELLS_PER_SIDE as f32);
    let (nx, ny) = (((hi.x - lo.x) / cell).ceil() as usize, ((hi.y - lo.y) / cell).ceil() as usize);
    if nx == 0 || ny == 0 {
        return Vec::new();
    }
    let cell = (hi - lo) / Vec2::new(nx as f32, ny as f32);
    let mut covered = vec![false; nx * ny];
    for t in &plane.triangles {
        let (tl, th) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
        let (c0, c1) = ((tl - lo) / cell, (th - lo) / cell);
        let (x0, y0) = (c0.x.floor().max(0.0) as usize, c0.y.floor().max(0.0) as usize);
        let (x1, y1) = ((c1.x.ceil() as usize).min(nx), (c1.y.ceil() as usize).min(ny));
        for y in y0..y1 {
            for x in x0..x1 {
                let centre = lo + (Vec2::new(x as f32, y as f32) + 0.5) * cell;
                if !covered[y * nx + x] && inside(centre, t) {
                    covered[y * nx + x] = true;
                }
            }
        }
    }
    // Runs along each row, then each run grown down the rows while the same run is covered.
    let mut out = Vec::new();
    for y in 0..ny {
        let mut x = 0;
        while x < nx {
            if !covered[y * nx + x] {
                x += 1;
                continue;
            }
            let start = x;
            while x < nx && covered[y * nx + x] {
                x += 1;
            }
            let run = start..x;
            let mut bottom = y + 1;
            while bottom < ny && run.clone().all(|i| covered[bottom * nx + i]) {
                bottom += 1;
            }
            for row in y..bottom {
                covered[row * nx + run.start..row * nx + run.end].fill(false);
            }
            let min = lo + Vec2::new(run.start as f32, y as f32) * cell;
            let max = lo + Vec2::new(run.end as f32, bottom as f32) * cell;
            out.push((min, max));
        }
    }
    out
}

/// Occlusion quads that stand for `scene`'s planar surfaces (see the module doc); empty for a
/// scene without such surfaces.
pub fn derive_occlusion_quads(scene: &Scene, settings: &DeriveSettings) -> Vec<OcclusionQuad> {
    let cell = if settings.cell.is_finite() && settings.cell > 0.0 { settings.cell } else { 0.25 };
    let mut quads: Vec<(f32, OcclusionQuad)> = Vec::new();
    for plane in planes(scene, cell) {
        for (min, max) in rectangles(&plane, cell) {
            let (c, h) = ((min + max) * 0.5, (max - min) * 0.5);
            let centre = plane.u * c.x + plane.v * c.y + plane.normal * plane.offset;
            let q = OcclusionQuad::new(centre, plane.u, plane.v, h.x, h.y)
                .with_opacity(plane.opacity, Vec3::ONE);
            quads.push((h.x * h.y, q));
        }
    }
    quads.sort_by(|a, b| b.0.total_cmp(&a.0));
    quads.truncate(settings.max_quads);
    quads.into_iter().map(|(_, q)| q).collect()
}

impl Scene {
    /// The occlusion quads that shape this scene's sky light: the authored ones, or when
    /// there are none, [`derive_occlusion_quads`] with the default settings.
    pub fn sky_occluders(&self) -> std::borrow::Cow<'_, [OcclusionQuad]> {
        if self.occlusion_quads.is_empty() {
            std::borrow::Cow::Owned(derive_occlusion_quads(self, &DeriveSettings::DEFAULT))
        } else {
            std::borrow::Cow::Borrowed(&self.occlusion_quads)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Material, MeshData};

    fn quad_mesh(corner: Vec3, u: Vec3, v: Vec3) -> (Vec<Vec3>, Vec<u32>) {
        (vec![corner, corner + u, corner + u + v, corner + v], vec![0, 1, 2, 0, 2, 3])
    }

    /// A 4 x 3 x 4 m box room (six faces, two triangles each) and, when `window`, a 1 x 1 m
    /// hole in its +X wall (that wall made of four quads around the hole).
    fn room(window: bool) -> Scene {
        let mut s = Scene::new("room");
        let m = s.add_material(Material::diffuse("wall", Vec3::splat(0.5)));
        let (x, y, z) = (Vec3::X * 4.0, Vec3::Y * 3.0, Vec3::Z * 4.0);
        let mut faces = vec![
            quad_mesh(Vec3::ZERO, z, x),
            quad_mesh(Vec3::Y * 3.0, x, z),
            quad_mesh(Vec3::ZERO, y, z),
            quad_mesh(Vec3::ZERO, x, y),
            quad_mesh(Vec3::Z * 4.0, y, x),
        ];
        if window {
            // The +X wall around a hole spanning y 1..2, z 1.5..2.5.
            let w = Vec3::X * 4.0;
            faces.push(quad_mesh(w, Vec3::Z * 4.0, Vec3::Y));
            faces.push(quad_mesh(w + Vec3::Y * 2.0, Vec3::Z * 4.0, Vec3::Y));
            faces.push(quad_mesh(w + Vec3::Y, Vec3::Z * 1.5, Vec3::Y));
            faces.push(quad_mesh(w + Vec3::Y + Vec3::Z * 2.5, Vec3::Z * 1.5, Vec3::Y));
        } else {
            faces.push(quad_mesh(Vec3::X * 4.0, z, y));
        }
        for (positions, indices) in faces {
            let data = MeshData { positions, normals: None, uvs: None, indices };
            s.meshes.push(crate::Mesh::build("face", data, m).unwrap().0);
        }
        s
    }

    fn blocked(quads: &[OcclusionQuad], origin: Vec3, dir: Vec3) -> bool {
        quads.iter().any(|q| {
            let n = q.axis_u.cross(q.axis_v);
            let denom = n.dot(dir);
            if denom.abs() < 1e-9 {
                return false;
            }
            let t = n.dot(q.center - origin) / denom;
            let p = origin + dir * t - q.center;
            t > 0.0
                && p.dot(q.axis_u).abs() <= q.half_u + 1e-4
                && p.dot(q.axis_v).abs() <= q.half_v + 1e-4
        })
    }

    /// Directions spread over the sphere (a Fibonacci lattice).
    fn directions(n: usize) -> impl Iterator<Item = Vec3> {
        (0..n).map(move |i| {
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let phi = i as f32 * 2.399_963;
            let r = (1.0 - z * z).sqrt();
            Vec3::new(r * phi.cos(), z, r * phi.sin())
        })
    }

    #[test]
    fn a_closed_room_is_closed_and_a_window_lets_the_sky_in() {
        let centre = Vec3::new(2.0, 1.5, 2.0);
        let closed = derive_occlusion_quads(&room(false), &DeriveSettings::DEFAULT);
        assert_eq!(closed.len(), 6, "one quad per face");
        for d in directions(500) {
            assert!(blocked(&closed, centre, d), "the closed room leaks towards {d}");
        }
        let open = derive_occlusion_quads(&room(true), &DeriveSettings::DEFAULT);
        let to_window = (Vec3::new(4.0, 1.5, 2.0) - centre).normalize();
        assert!(!blocked(&open, centre, to_window), "the window lets the sky in");
        let leaks = directions(2000).filter(|&d| !blocked(&open, centre, d)).count();
        // The window's solid angle from the centre: about 1 / (2^2) sr of 4 pi.
        let share = leaks as f32 / 2000.0;
        assert!((0.01..0.04).contains(&share), "{share} of the sphere leaks");
        for q in &open {
            assert!(q.half_u > 0.0 && q.half_v > 0.0 && q.opacity == 1.0);
        }
    }

    #[test]
    fn authored_quads_win_and_hostile_scenes_give_none() {
        let mut s = room(false);
        assert_eq!(s.sky_occluders().len(), 6);
        s.occlusion_quads = vec![OcclusionQuad::new(Vec3::ZERO, Vec3::X, Vec3::Z, 1.0, 1.0)];
        assert_eq!(s.sky_occluders().len(), 1);
        assert!(derive_occlusion_quads(&Scene::new("empty"), &DeriveSettings::DEFAULT).is_empty());
        // A wall that is no whole number of cells long still gets one quad its own size.
        let mut wall = Scene::new("wall");
        let m = wall.add_material(Material::diffuse("wall", Vec3::splat(0.5)));
        let (positions, indices) = quad_mesh(Vec3::ONE, Vec3::X * 4.1, Vec3::Y * 3.05);
        let data = MeshData { positions, normals: None, uvs: None, indices };
        wall.meshes.push(crate::Mesh::build("wall", data, m).unwrap().0);
        let q = derive_occlusion_quads(&wall, &DeriveSettings::DEFAULT);
        assert_eq!(q.len(), 1);
        let (hu, hv) = (q[0].half_u.max(q[0].half_v), q[0].half_u.min(q[0].half_v));
        assert!((hu - 2.05).abs() < 1e-4 && (hv - 1.525).abs() < 1e-4, "{hu} x {hv}");
        assert!((q[0].center - Vec3::new(3.05, 2.525, 1.0)).length() < 1e-4, "{}", q[0].center);
        let bad = DeriveSettings { cell: f32::NAN, max_quads: 2 };
        assert_eq!(derive_occlusion_quads(&room(false), &bad).len(), 2);
    }
}
