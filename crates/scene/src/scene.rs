//! The scene: what is in the world, and the plain-data views other crates build from.

use crate::{
    Aabb, Camera, Cleanup, LoadWarning, LpvPlacement, Material, MaterialId, Mesh, OcclusionQuad,
    PointLight, SceneError, SkyVolumePlacement, Sun, Texture, TextureId,
};
use glam::{Affine3A, Vec2, Vec3, Vec4};
use std::fmt;

/// Everything a renderer needs to know about the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub name: String,
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// `None`: no sun (indoor scene, night, the furnace).
    pub sun: Option<Sun>,
    pub point_lights: Vec<PointLight>,
    pub occlusion_quads: Vec<OcclusionQuad>,
    /// Whether the sky is visible (and lights the scene through the atmosphere model).
    pub sky: bool,
    pub camera: Camera,
    pub sky_volume: SkyVolumePlacement,
    pub lpv: LpvPlacement,
    /// What the loaders repaired (dropped degenerate triangles, recomputed normals).
    pub cleanup: Cleanup,
    /// What the loaders could not honour and worked around (a stand-in for a missing texture,
    /// an ignored feature), each once, in the order met; empty for generated scenes.
    pub warnings: Vec<LoadWarning>,
}

/// The scene flattened to world space: plain data an acceleration structure
/// (`kdtree_tracer`, a BVH), a vertex buffer or a ray tracer's surface layer builds from.
/// Vertices are shared within a mesh, never across meshes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneTriangles {
    pub positions: Vec<Vec3>,
    /// Per vertex: the unit world-space normal (the mesh's normal matrix applied), or zero
    /// where the mesh has none or it degenerates.
    pub normals: Vec<Vec3>,
    /// Per vertex: the texture coordinates, or zero where the mesh has none (or a
    /// non-finite one).
    pub uvs: Vec<Vec2>,
    /// Per vertex: the unit world-space tangent along +U with the bitangent sign in `w`
    /// (`B = w N x T`, turned with the transform's handedness), `(1, 0, 0, 1)` where the
    /// mesh has none.
    pub tangents: Vec<Vec4>,
    /// Per vertex: the linear RGB colour multiplied into the base colour (a mesh's
    /// [`Mesh::colors`], white where the mesh has none); empty when no mesh has colours.
    pub colors: Vec<Vec3>,
    pub indices: Vec<[u32; 3]>,
    /// For each triangle, the index of its mesh in [`Scene::meshes`].
    pub mesh_ids: Vec<u32>,
    /// For each triangle, its material's index in [`Scene::materials`].
    pub materials: Vec<u32>,
}

impl SceneTriangles {
    /// Positions as plain arrays.
    pub fn positions_array(&self) -> Vec<[f32; 3]> {
        self.positions.iter().map(|p| p.to_array()).collect()
    }

    /// The three corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        self.indices[t].map(|i| self.positions[i as usize])
    }

    /// The corners' normals of triangle `t` (zero where unknown).
    pub fn corner_normals(&self, t: usize) -> [Vec3; 3] {
        self.indices[t].map(|i| self.normals[i as usize])
    }

    /// The corners' tangents of triangle `t`.
    pub fn corner_tangents(&self, t: usize) -> [Vec4; 3] {
        self.indices[t].map(|i| self.tangents[i as usize])
    }

    /// The corners' colours of triangle `t` (white without any).
    pub fn corner_colors(&self, t: usize) -> [Vec3; 3] {
        if self.colors.is_empty() {
            return [Vec3::ONE; 3];
        }
        self.indices[t].map(|i| self.colors[i as usize])
    }

    /// Whether any mesh has vertex colours (else [`Self::colors`] is empty).
    pub fn has_colors(&self) -> bool {
        !self.colors.is_empty()
    }

    /// The corners' texture coordinates of triangle `t`.
    pub fn corner_uvs(&self, t: usize) -> [Vec2; 3] {
        self.indices[t].map(|i| self.uvs[i as usize])
    }
}

/// Counts a person reads (the example prints them).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneStats {
    pub meshes: usize,
    pub triangles: usize,
    pub vertices: usize,
    pub materials: usize,
    pub textures: usize,
    pub texture_bytes: usize,
    pub mirror_materials: usize,
    pub transparent_materials: usize,
    pub alpha_tested_materials: usize,
    pub emissive_materials: usize,
    pub point_lights: usize,
    pub occlusion_quads: usize,
    pub bounds: Aabb,
    pub cleanup: Cleanup,
}

impl fmt::Display for SceneStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.bounds.size();
        writeln!(f, "meshes            {}", self.meshes)?;
        writeln!(f, "triangles         {}", self.triangles)?;
        writeln!(f, "vertices          {}", self.vertices)?;
        writeln!(
            f,
            "materials         {} ({} mirror, {} transparent, {} alpha-tested, {} emissive)",
            self.materials,
            self.mirror_materials,
            self.transparent_materials,
            self.alpha_tested_materials,
            self.emissive_materials
        )?;
        writeln!(
            f,
            "textures          {} ({:.1} MiB with mips)",
            self.textures,
            self.texture_bytes as f64 / (1 << 20) as f64
        )?;
        writeln!(f, "point lights      {}", self.point_lights)?;
        writeln!(f, "occlusion quads   {}", self.occlusion_quads)?;
        writeln!(f, "extent            {:.1} x {:.1} x {:.1} m", s.x, s.y, s.z)?;
        write!(
            f,
            "repaired          {} degenerate triangles dropped, {} normals recomputed",
            self.cleanup.degenerate_dropped, self.cleanup.normals_recomputed
        )
    }
}

impl Scene {
    /// An empty scene: no meshes, no lights, no sky, a default camera.
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            meshes: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            sun: None,
            point_lights: Vec::new(),
            occlusion_quads: Vec::new(),
            sky: false,
            camera: Camera::default(),
            sky_volume: SkyVolumePlacement::fit(Aabb::EMPTY),
            lpv: LpvPlacement::fit(Aabb::EMPTY),
            cleanup: Cleanup::default(),
            warnings: Vec::new(),
        }
    }

    pub fn add_material(&mut self, m: Material) -> MaterialId {
        self.materials.push(m);
        MaterialId(self.materials.len() as u32 - 1)
    }

    pub fn add_texture(&mut self, t: Texture) -> TextureId {
        self.textures.push(t);
        TextureId(self.textures.len() as u32 - 1)
    }

    pub fn material_by_name(&self, name: &str) -> Option<MaterialId> {
        self.materials.iter().position(|m| m.name == name).map(|i| MaterialId(i as u32))
    }

    pub fn material(&self, id: MaterialId) -> Option<&Material> {
        self.materials.get(id.index())
    }

    /// World-space bounds of all meshes (empty when there are none).
    pub fn bounds(&self) -> Aabb {
        self.meshes.iter().fold(Aabb::EMPTY, |b, m| b.union(m.world_bounds()))
    }

    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(Mesh::triangle_count).sum()
    }

    /// Appends another scene's textures, materials and meshes (ids remapped), point lights and
    /// occlusion quads, all moved by `transform`, and its warnings; keeps this scene's sun, sky and camera.
    pub fn merge(&mut self, other: Scene, transform: Affine3A) {
        let toff = self.textures.len() as u32;
        let moff = self.materials.len() as u32;
        let shift = |t: &mut Option<TextureId>| {
            if let Some(t) = t {
                t.0 += toff;
            }
        };
        self.textures.extend(other.textures);
        for mut m in other.materials {
            shift(&mut m.albedo_texture);
            shift(&mut m.normal_texture);
            shift(&mut m.metallic_roughness_texture);
            shift(&mut m.occlusion_texture);
            shift(&mut m.emissive_texture);
            if let Some(a) = &mut m.alpha_mask {
                a.texture.0 += toff;
            }
            self.materials.push(m);
        }
        for mut mesh in other.meshes {
            mesh.material.0 += moff;
            mesh.transform = transform * mesh.transform;
            self.meshes.push(mesh);
        }
        let scale = transform
            .matrix3
            .x_axis
            .length()
            .max(transform.matrix3.y_axis.length())
            .max(transform.matrix3.z_axis.length());
        for mut l in other.point_lights {
            l.position = transform.transform_point3(l.position);
            l.radius *= scale;
            if let Some(c) = &mut l.spot {
                c.direction = transform.transform_vector3(c.direction).normalize_or(c.direction);
            }
            self.point_lights.push(l);
        }
        for mut q in other.occlusion_quads {
            let (u, v) =
                (transform.transform_vector3(q.axis_u), transform.transform_vector3(q.axis_v));
            q.center = transform.transform_point3(q.center);
            q.half_u *= u.length();
            q.half_v *= v.length();
            q.axis_u = u.normalize_or_zero();
            q.axis_v = v.normalize_or_zero();
            self.occlusion_quads.push(q);
        }
        self.cleanup += other.cleanup;
        for w in other.warnings {
            if !self.warnings.contains(&w) {
                self.warnings.push(w);
            }
        }
    }

    /// Places the sky volume and LPV cascades over the current geometry.
    pub fn fit_volumes(&mut self) {
        let b = self.bounds();
        self.sky_volume = SkyVolumePlacement::fit(b);
        self.lpv = LpvPlacement::fit(b);
    }

    pub fn stats(&self) -> SceneStats {
        let count = |f: fn(&Material) -> bool| self.materials.iter().filter(|m| f(m)).count();
        SceneStats {
            meshes: self.meshes.len(),
            triangles: self.triangle_count(),
            vertices: self.meshes.iter().map(Mesh::vertex_count).sum(),
            materials: self.materials.len(),
            textures: self.textures.len(),
            texture_bytes: self.textures.iter().map(Texture::byte_size).sum(),
            mirror_materials: count(Material::is_mirror),
            transparent_materials: count(Material::is_transparent),
            alpha_tested_materials: count(|m| m.alpha_mask.is_some()),
            emissive_materials: count(Material::is_emissive),
            point_lights: self.point_lights.len(),
            occlusion_quads: self.occlusion_quads.len(),
            bounds: self.bounds(),
            cleanup: self.cleanup,
        }
    }

    /// All triangles in world space with their normals, texture coordinates and materials,
    /// meshes in order, vertices shared within a mesh: the one place a scene is flattened.
    pub fn triangles(&self) -> SceneTriangles {
        let mut out = SceneTriangles::default();
        let (vertices, triangles) =
            (self.meshes.iter().map(Mesh::vertex_count).sum(), self.triangle_count());
        out.positions.reserve(vertices);
        out.normals.reserve(vertices);
        out.uvs.reserve(vertices);
        out.tangents.reserve(vertices);
        out.indices.reserve(triangles);
        out.mesh_ids.reserve(triangles);
        out.materials.reserve(triangles);
        let any_colors = self.meshes.iter().any(|m| !m.colors.is_empty());
        for (id, m) in self.meshes.iter().enumerate() {
            if any_colors {
                out.colors.extend(
                    (0..m.vertex_count()).map(|v| m.colors.get(v).copied().unwrap_or(Vec3::ONE)),
                );
            }
            let base = out.positions.len() as u32;
            let nm = m.normal_matrix();
            out.positions.extend(m.positions.iter().map(|&p| m.transform.transform_point3(p)));
            out.normals.extend(
                (0..m.vertex_count()).map(|v| {
                    m.normals.get(v).map_or(Vec3::ZERO, |&n| (nm * n).normalize_or_zero())
                }),
            );
            out.uvs.extend(
                (0..m.vertex_count())
                    .map(|v| m.uvs.get(v).copied().filter(|u| u.is_finite()).unwrap_or_default()),
            );
            let m3 = glam::Mat3::from(m.transform.matrix3);
            let handedness = m3.determinant().signum();
            out.tangents.extend((0..m.vertex_count()).map(|v| {
                let t = m.tangents.get(v).copied().unwrap_or(Vec4::new(1.0, 0.0, 0.0, 1.0));
                let xyz = (m3 * t.truncate()).try_normalize().unwrap_or(Vec3::X);
                xyz.extend(if t.w * handedness < 0.0 { -1.0 } else { 1.0 })
            }));
            out.indices.extend(m.indices.iter().map(|t| t.map(|i| i + base)));
            out.mesh_ids.extend(std::iter::repeat_n(id as u32, m.indices.len()));
            out.materials.extend(std::iter::repeat_n(m.material.0, m.indices.len()));
        }
        out
    }

    /// Checks every part of the scene (meshes, materials, textures, lights, quads, camera,
    /// volumes).
    pub fn validate(&self) -> Result<(), SceneError> {
        for t in &self.textures {
            t.validate()?;
        }
        for m in &self.materials {
            m.validate(self.textures.len())?;
        }
        for m in &self.meshes {
            m.validate(self.materials.len())?;
        }
        if let Some(s) = &self.sun {
            s.validate()?;
        }
        for l in &self.point_lights {
            l.validate()?;
            if l.emitter.is_some() {
                let reason = "an emitter's stand-in is derived from emissive surfaces \
                              (scene::emitter_lights), not a scene's own light";
                return Err(SceneError::invalid(format!("point light \"{}\"", l.name), reason));
            }
        }
        for (i, q) in self.occlusion_quads.iter().enumerate() {
            q.validate()
                .map_err(|e| SceneError::invalid(format!("occlusion quad {i}"), e.reason))?;
        }
        self.camera.validate()?;
        self.sky_volume.validate()?;
        self.lpv.validate()
    }
}
