//! Geometry accumulation for the generators: quads, boxes, cylinders, spheres, a torus knot,
//! grouped into one mesh per (part, material).

use crate::{Cleanup, MaterialId, Mesh, MeshData};
use glam::{Affine3A, Vec2, Vec3};

/// Vertices and triangles of one future mesh.
#[derive(Default)]
pub(crate) struct Geo {
    p: Vec<Vec3>,
    n: Vec<Vec3>,
    uv: Vec<Vec2>,
    idx: Vec<u32>,
}

impl Geo {
    fn vertex(&mut self, p: Vec3, n: Vec3, uv: Vec2) -> u32 {
        self.p.push(p);
        self.n.push(n);
        self.uv.push(uv);
        self.p.len() as u32 - 1
    }

    /// A rectangle from `corner` spanning `u` and `v`, facing `u x v`; UVs in units of
    /// `uv_size` metres per texture repeat.
    pub fn quad(&mut self, corner: Vec3, u: Vec3, v: Vec3, uv_size: f32) {
        let n = u.cross(v).normalize_or_zero();
        let (su, sv) = (u.length() / uv_size, v.length() / uv_size);
        let a = self.vertex(corner, n, Vec2::new(0.0, sv));
        let b = self.vertex(corner + u, n, Vec2::new(su, sv));
        let c = self.vertex(corner + u + v, n, Vec2::new(su, 0.0));
        let d = self.vertex(corner + v, n, Vec2::new(0.0, 0.0));
        self.idx.extend_from_slice(&[a, b, c, a, c, d]);
    }

    /// A rectangle centred at `c` with half-extent vectors `u`, `v`, UVs over [0, 1].
    pub fn card(&mut self, c: Vec3, u: Vec3, v: Vec3) {
        let n = u.cross(v).normalize_or_zero();
        let a = self.vertex(c - u - v, n, Vec2::new(0.0, 1.0));
        let b = self.vertex(c + u - v, n, Vec2::new(1.0, 1.0));
        let d = self.vertex(c + u + v, n, Vec2::new(1.0, 0.0));
        let e = self.vertex(c - u + v, n, Vec2::new(0.0, 0.0));
        self.idx.extend_from_slice(&[a, b, d, a, d, e]);
    }

    /// An axis-aligned box with outward faces; `faces` masks +X, -X, +Y, -Y, +Z, -Z.
    pub fn boxed(&mut self, min: Vec3, max: Vec3, uv_size: f32, faces: [bool; 6]) {
        let s = max - min;
        let (x, y, z) = (Vec3::X * s.x, Vec3::Y * s.y, Vec3::Z * s.z);
        let list = [
            (Vec3::new(max.x, min.y, max.z), -z, y),
            (Vec3::new(min.x, min.y, min.z), z, y),
            (Vec3::new(min.x, max.y, max.z), x, -z),
            (Vec3::new(min.x, min.y, min.z), x, z),
            (Vec3::new(min.x, min.y, max.z), x, y),
            (Vec3::new(max.x, min.y, min.z), -x, y),
        ];
        for (i, (c, u, v)) in list.into_iter().enumerate() {
            if faces[i] {
                self.quad(c, u, v, uv_size);
            }
        }
    }

    pub fn cube(&mut self, min: Vec3, max: Vec3, uv_size: f32) {
        self.boxed(min, max, uv_size, [true; 6]);
    }

    /// A box rotated about +Y by `angle` radians around its centre.
    pub fn rotated_box(&mut self, center: Vec3, half: Vec3, angle: f32, uv_size: f32) {
        let start = self.p.len();
        self.cube(-half, half, uv_size);
        let r = glam::Quat::from_rotation_y(angle);
        for i in start..self.p.len() {
            self.p[i] = center + r * self.p[i];
            self.n[i] = r * self.n[i];
        }
    }

    /// An open cylinder along +Y (side only) from `base`.
    pub fn cylinder(&mut self, base: Vec3, radius: f32, height: f32, segments: u32) {
        let start = self.p.len() as u32;
        for i in 0..=segments {
            let a = i as f32 / segments as f32 * std::f32::consts::TAU;
            let n = Vec3::new(a.cos(), 0.0, -a.sin());
            let u = i as f32 / segments as f32;
            self.vertex(base + n * radius, n, Vec2::new(u, 1.0));
            self.vertex(base + n * radius + Vec3::Y * height, n, Vec2::new(u, 0.0));
        }
        for i in 0..segments {
            let (a, b, c, d) =
                (start + 2 * i, start + 2 * i + 2, start + 2 * i + 3, start + 2 * i + 1);
            self.idx.extend_from_slice(&[a, b, c, a, c, d]);
        }
    }

    /// A latitude-longitude sphere; `inward` flips the faces (a closed room).
    pub fn sphere(&mut self, center: Vec3, radius: f32, slices: u32, stacks: u32, inward: bool) {
        let start = self.p.len() as u32;
        for j in 0..=stacks {
            let theta = j as f32 / stacks as f32 * std::f32::consts::PI;
            for i in 0..=slices {
                let phi = i as f32 / slices as f32 * std::f32::consts::TAU;
                let d = Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin());
                let n = if inward { -d } else { d };
                self.vertex(
                    center + d * radius,
                    n,
                    Vec2::new(i as f32 / slices as f32, j as f32 / stacks as f32),
                );
            }
        }
        let row = slices + 1;
        for j in 0..stacks {
            for i in 0..slices {
                let a = start + j * row + i;
                let (b, c, d) = (a + row, a + row + 1, a + 1);
                // Skip the zero-area triangles at the poles.
                if j != 0 {
                    self.tri(a, b, d, inward);
                }
                if j != stacks - 1 {
                    self.tri(d, b, c, inward);
                }
            }
        }
    }

    fn tri(&mut self, a: u32, b: u32, c: u32, flip: bool) {
        if flip {
            self.idx.extend_from_slice(&[a, c, b]);
        } else {
            self.idx.extend_from_slice(&[a, b, c]);
        }
    }

    #[allow(clippy::too_many_arguments)] // the knot's own parameters, private to the generators
    /// A (p, q) torus knot tube: a non-convex shiny object that sees itself in reflections.
    pub fn torus_knot(
        &mut self,
        center: Vec3,
        scale: f32,
        tube: f32,
        p: u32,
        q: u32,
        segments: u32,
        sides: u32,
    ) {
        let curve = |t: f32| {
            let (pt, qt) = (p as f32 * t, q as f32 * t);
            let r = 2.0 + qt.cos();
            Vec3::new(r * pt.cos(), -qt.sin(), r * pt.sin()) * (scale / 3.0)
        };
        let start = self.p.len() as u32;
        for i in 0..=segments {
            let t = i as f32 / segments as f32 * std::f32::consts::TAU;
            let c0 = curve(t);
            let tangent = (curve(t + 1e-3) - curve(t - 1e-3)).normalize();
            let side =
                tangent.cross((c0 + curve(t + 1e-3)).normalize_or(Vec3::Y)).normalize_or(Vec3::X);
            let up = side.cross(tangent);
            for k in 0..=sides {
                let a = k as f32 / sides as f32 * std::f32::consts::TAU;
                let n = side * a.cos() + up * a.sin();
                self.vertex(
                    center + c0 + n * tube,
                    n,
                    Vec2::new(i as f32 / segments as f32 * 8.0, k as f32 / sides as f32),
                );
            }
        }
        let row = sides + 1;
        for i in 0..segments {
            for k in 0..sides {
                let a = start + i * row + k;
                let (b, c, d) = (a + row, a + row + 1, a + 1);
                self.idx.extend_from_slice(&[a, d, c, a, c, b]);
            }
        }
    }
}

/// Meshes under construction, one per (part name, material), in insertion order, each with
/// its object-to-world transform (the identity unless placed with [`Parts::placed`]).
#[derive(Default)]
pub(crate) struct Parts {
    parts: Vec<(String, MaterialId, Geo, Affine3A)>,
}

impl Parts {
    /// The part's geometry, in world space.
    pub fn get(&mut self, name: &str, material: MaterialId) -> &mut Geo {
        self.placed(name, material, Affine3A::IDENTITY)
    }

    /// The part's geometry in object space, `transform` taking it to the world (an instance:
    /// the same object-space geometry under several transforms, as a glTF file stores it).
    /// A part met again keeps the transform it was first given.
    pub fn placed(&mut self, name: &str, material: MaterialId, transform: Affine3A) -> &mut Geo {
        let i = match self.parts.iter().position(|(n, m, _, _)| n == name && *m == material) {
            Some(i) => i,
            None => {
                self.parts.push((name.to_owned(), material, Geo::default(), transform));
                self.parts.len() - 1
            }
        };
        &mut self.parts[i].2
    }

    /// Builds the meshes through the same clean-up path the loaders use.
    pub fn finish(self) -> (Vec<Mesh>, Cleanup) {
        let mut cleanup = Cleanup::default();
        let meshes = self
            .parts
            .into_iter()
            .filter(|(_, _, g, _)| !g.idx.is_empty())
            .filter_map(|(name, mat, g, transform)| {
                let data = MeshData {
                    positions: g.p,
                    normals: Some(g.n),
                    uvs: Some(g.uv),
                    indices: g.idx,
                };
                // Generated data is finite and in range by construction; a failure would be a
                // bug, and the mesh is then left out (the scene tests would catch it).
                let (mut m, c) = Mesh::build(name, data, mat).ok()?;
                m.transform = transform;
                cleanup += c;
                Some(m)
            })
            .collect();
        (meshes, cleanup)
    }
}
