//! Triangle meshes and the clean-up every loader runs: validation, degenerate-triangle removal,
//! normal recomputation and tangent generation (MikkTSpace).

use crate::{Aabb, LoadErrorKind, MaterialId, SceneError};
use glam::{Affine3A, Mat3, Vec2, Vec3, Vec4};

/// A triangle mesh with one material. Vertex attributes are in object space; `transform` takes
/// them to the world (+Y up, +X east, -Z north, metres).
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    pub name: String,
    pub positions: Vec<Vec3>,
    /// Unit normals, one per vertex.
    pub normals: Vec<Vec3>,
    /// Unit tangents along +U with the bitangent sign in `w` (`B = w * N x T`).
    pub tangents: Vec<Vec4>,
    pub uvs: Vec<Vec2>,
    /// Vertex colours (glTF's `COLOR_0`, linear RGB in `[0, 1]`), one per vertex, multiplied
    /// into the material's base colour; empty when the mesh has none (white: nothing is
    /// stored or multiplied).
    pub colors: Vec<Vec3>,
    pub indices: Vec<[u32; 3]>,
    pub material: MaterialId,
    pub transform: Affine3A,
}

/// What [`Mesh::build`] repaired.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cleanup {
    /// Triangles with repeated indices or zero area, removed.
    pub degenerate_dropped: usize,
    /// Vertices whose normal was missing, zero-length or non-finite, recomputed from faces.
    pub normals_recomputed: usize,
}

impl std::ops::AddAssign for Cleanup {
    fn add_assign(&mut self, o: Self) {
        self.degenerate_dropped += o.degenerate_dropped;
        self.normals_recomputed += o.normals_recomputed;
    }
}

/// Raw vertex data as a loader reads it.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    pub positions: Vec<Vec3>,
    /// Absent: computed from faces.
    pub normals: Option<Vec<Vec3>>,
    /// Absent: all zero.
    pub uvs: Option<Vec<Vec2>>,
    /// Flat triangle list.
    pub indices: Vec<u32>,
}

impl Mesh {
    /// Validates and cleans raw data: non-finite positions/UVs and out-of-range indices are
    /// errors; degenerate triangles are dropped and counted; missing or zero-length normals are
    /// recomputed (area-weighted face normals); tangents are generated from the UVs (MikkTSpace).
    pub fn build(
        name: impl Into<String>,
        data: MeshData,
        material: MaterialId,
    ) -> Result<(Self, Cleanup), LoadErrorKind> {
        let MeshData { positions, normals, uvs, indices } = data;
        let n = positions.len();
        if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
            return Err(LoadErrorKind::NonFinite { attribute: "position", vertex: v });
        }
        if indices.len() % 3 != 0 {
            return Err(LoadErrorKind::Inconsistent(format!(
                "{} indices is not a multiple of 3",
                indices.len()
            )));
        }
        if let Some(&i) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(LoadErrorKind::IndexOutOfRange { index: i as u64, vertex_count: n });
        }
        let uvs = match uvs {
            Some(u) if u.len() != n => {
                return Err(LoadErrorKind::Inconsistent(format!(
                    "{} UVs for {n} vertices",
                    u.len()
                )));
            }
            Some(u) => {
                if let Some(v) = u.iter().position(|t| !t.is_finite()) {
                    return Err(LoadErrorKind::NonFinite { attribute: "uv", vertex: v });
                }
                u
            }
            None => vec![Vec2::ZERO; n],
        };
        let mut normals = match normals {
            Some(m) if m.len() != n => {
                return Err(LoadErrorKind::Inconsistent(format!(
                    "{} normals for {n} vertices",
                    m.len()
                )));
            }
            Some(m) => m,
            None => vec![Vec3::ZERO; n],
        };
        let mut cleanup = Cleanup::default();
        let mut tris = Vec::with_capacity(indices.len() / 3);
        for t in indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]];
            let (pa, pb, pc) =
                (positions[a as usize], positions[b as usize], positions[c as usize]);
            if a == b || b == c || a == c || is_degenerate(pa, pb, pc) {
                cleanup.degenerate_dropped += 1;
            } else {
                tris.push([a, b, c]);
            }
        }
        // Normals: keep good ones (normalised), recompute the rest from faces.
        // Zero, denormal, huge (length overflows) or non-finite normals cannot be normalised.
        let bad: Vec<bool> =
            normals.iter().map(|m| !(m.length() > 1e-6 && m.length().is_finite())).collect();
        if bad.iter().any(|&b| b) {
            let mut acc = vec![Vec3::ZERO; n];
            for &[a, b, c] in &tris {
                let (pa, pb, pc) =
                    (positions[a as usize], positions[b as usize], positions[c as usize]);
                let f = (pb - pa).cross(pc - pa); // length = 2 x area: area weighting
                for i in [a, b, c] {
                    acc[i as usize] += f;
                }
            }
            for (i, m) in normals.iter_mut().enumerate() {
                if bad[i] {
                    *m = acc[i].try_normalize().unwrap_or(Vec3::Y);
                    cleanup.normals_recomputed += 1;
                }
            }
        }
        for m in &mut normals {
            *m = m.try_normalize().unwrap_or(Vec3::Y);
        }
        let tangents = tangents(&positions, &normals, &uvs, &tris);
        let mesh = Self {
            name: name.into(),
            positions,
            normals,
            tangents,
            uvs,
            colors: Vec::new(),
            indices: tris,
            material,
            transform: Affine3A::IDENTITY,
        };
        Ok((mesh, cleanup))
    }

    /// The file's own tangents (glTF's `TANGENT`: unit xyz along +U, bitangent sign in `w`)
    /// in place of the generated ones, made orthonormal to the normals; an error when their
    /// count is not the vertex count.
    pub fn with_tangents(mut self, tangents: Vec<Vec4>) -> Result<Self, LoadErrorKind> {
        if tangents.len() != self.positions.len() {
            return Err(LoadErrorKind::Inconsistent(format!(
                "{} tangents for {} vertices",
                tangents.len(),
                self.positions.len()
            )));
        }
        self.tangents = tangents
            .iter()
            .zip(&self.normals)
            .map(|(&t, &n)| orthonormal_tangent(Some(t), n))
            .collect();
        Ok(self)
    }

    /// Vertex colours (linear RGB, clamped to `[0, 1]`) multiplied into the base colour; an
    /// error when their count is not the vertex count or one is not finite.
    pub fn with_colors(mut self, colors: Vec<Vec3>) -> Result<Self, LoadErrorKind> {
        if colors.len() != self.positions.len() {
            return Err(LoadErrorKind::Inconsistent(format!(
                "{} colours for {} vertices",
                colors.len(),
                self.positions.len()
            )));
        }
        if let Some(v) = colors.iter().position(|c| !c.is_finite()) {
            return Err(LoadErrorKind::NonFinite { attribute: "colour", vertex: v });
        }
        self.colors = colors.into_iter().map(|c| c.clamp(Vec3::ZERO, Vec3::ONE)).collect();
        Ok(self)
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Bounds of the object-space positions.
    pub fn local_bounds(&self) -> Aabb {
        Aabb::from_points(self.positions.iter().copied())
    }

    /// Bounds in world space (the transformed local box: conservative).
    pub fn world_bounds(&self) -> Aabb {
        self.local_bounds().transformed(&self.transform)
    }

    /// The matrix that takes object-space normals to world space (inverse transpose).
    pub fn normal_matrix(&self) -> Mat3 {
        Mat3::from(self.transform.matrix3).inverse().transpose()
    }

    /// Total world-space surface area.
    pub fn world_area(&self) -> f32 {
        self.indices
            .iter()
            .map(|&[a, b, c]| {
                let p = |i: u32| self.transform.transform_point3(self.positions[i as usize]);
                0.5 * (p(b) - p(a)).cross(p(c) - p(a)).length()
            })
            .sum()
    }

    /// Checks attribute lengths, index ranges, finiteness, unit normals/tangents and that the
    /// material exists (`material_count` materials).
    pub fn validate(&self, material_count: usize) -> Result<(), SceneError> {
        let el = || format!("mesh \"{}\"", self.name);
        let n = self.positions.len();
        if self.normals.len() != n || self.tangents.len() != n || self.uvs.len() != n {
            return Err(SceneError::invalid(el(), "attribute arrays differ in length"));
        }
        if let Some(t) = self.indices.iter().find(|t| t.iter().any(|&i| i as usize >= n)) {
            return Err(SceneError::invalid(
                el(),
                format!("triangle {t:?} indexes past {n} vertices"),
            ));
        }
        if self.positions.iter().any(|p| !p.is_finite()) || self.uvs.iter().any(|u| !u.is_finite())
        {
            return Err(SceneError::invalid(el(), "non-finite position or UV"));
        }
        if !(self.colors.is_empty() || self.colors.len() == n) {
            return Err(SceneError::invalid(el(), "colours differ in length from the vertices"));
        }
        if self
            .colors
            .iter()
            .any(|c| !c.is_finite() || c.min_element() < 0.0 || c.max_element() > 1.0)
        {
            return Err(SceneError::invalid(el(), "vertex colour outside [0, 1]"));
        }
        if self.normals.iter().any(|m| !m.is_finite() || (m.length() - 1.0).abs() > 1e-3) {
            return Err(SceneError::invalid(el(), "normal not of unit length"));
        }
        if self.tangents.iter().any(|t| {
            !t.is_finite() || (t.truncate().length() - 1.0).abs() > 1e-3 || t.w.abs() != 1.0
        }) {
            return Err(SceneError::invalid(el(), "tangent not unit or sign not +-1"));
        }
        if self.material.index() >= material_count {
            return Err(SceneError::invalid(
                el(),
                format!("material {} does not exist ({material_count} materials)", self.material.0),
            ));
        }
        if !self.transform.is_finite() || self.transform.matrix3.determinant().abs() < 1e-12 {
            return Err(SceneError::invalid(el(), "transform is not finite and invertible"));
        }
        Ok(())
    }
}

/// Zero (or numerically zero) area relative to the triangle's size.
pub(crate) fn is_degenerate(a: Vec3, b: Vec3, c: Vec3) -> bool {
    let cross = (b - a).cross(c - a).length();
    let longest =
        (b - a).length_squared().max((c - a).length_squared()).max((c - b).length_squared());
    cross.is_nan() || cross <= 1e-7 * longest || !cross.is_finite()
}

/// Any unit vector perpendicular to `n`.
fn perpendicular(n: Vec3) -> Vec3 {
    n.any_orthonormal_vector()
}

/// Per-vertex tangents by MikkTSpace (Mikkelsen 2008, the tangent space glTF's normal maps are
/// baked against), through `bevy_mikktspace`, with the bitangent up the image (`-V`: the
/// normal maps' `+Y`, see `tex_coord` below). MikkTSpace gives a tangent per triangle corner;
/// a vertex shared by corners of different tangent spaces (mirrored UVs on one vertex) keeps
/// the last one. Corners it cannot give a tangent (no usable UVs) get an arbitrary
/// perpendicular with `w = 1`; every tangent is orthogonalised against the vertex normal.
fn tangents(p: &[Vec3], n: &[Vec3], uv: &[Vec2], tris: &[[u32; 3]]) -> Vec<Vec4> {
    struct Geometry<'a> {
        p: &'a [Vec3],
        n: &'a [Vec3],
        uv: &'a [Vec2],
        tris: &'a [[u32; 3]],
        out: Vec<Option<Vec4>>,
    }
    impl Geometry<'_> {
        fn vertex(&self, face: usize, vert: usize) -> usize {
            self.tris[face][vert] as usize
        }
    }
    impl bevy_mikktspace::Geometry for Geometry<'_> {
        fn num_faces(&self) -> usize {
            self.tris.len()
        }
        fn num_vertices_of_face(&self, _face: usize) -> usize {
            3
        }
        fn position(&self, face: usize, vert: usize) -> [f32; 3] {
            self.p[self.vertex(face, vert)].to_array()
        }
        fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
            self.n[self.vertex(face, vert)].to_array()
        }
        fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
            // glTF's V runs down the image and its normal maps' +Y up it; MikkTSpace's
            // bitangent follows +V, so it is given V flipped (as the glTF sample models'
            // NormalTangentTest expects; KhronosGroup/glTF-Sample-Models#174).
            let uv = self.uv[self.vertex(face, vert)];
            [uv.x, 1.0 - uv.y]
        }
        fn set_tangent(
            &mut self,
            space: Option<bevy_mikktspace::TangentSpace>,
            face: usize,
            vert: usize,
        ) {
            let v = self.vertex(face, vert);
            if let Some(s) = space {
                self.out[v] = Some(Vec4::from_array(s.tangent_encoded()));
            }
        }
    }
    let mut g = Geometry { p, n, uv, tris, out: vec![None; p.len()] };
    // The error type has no variants: generation cannot fail.
    let _ = bevy_mikktspace::generate_tangents(&mut g);
    g.out.iter().zip(n).map(|(t, &n)| orthonormal_tangent(*t, n)).collect()
}

/// `t` made a unit tangent perpendicular to `n` with a bitangent sign of +-1 (an arbitrary
/// perpendicular with `w = 1` when `t` is missing, parallel to `n` or not finite).
pub fn orthonormal_tangent(t: Option<Vec4>, n: Vec3) -> Vec4 {
    let Some(t) = t.filter(|t| t.is_finite()) else { return perpendicular(n).extend(1.0) };
    let xyz = (t.truncate() - n * n.dot(t.truncate())).try_normalize();
    match xyz {
        Some(xyz) => xyz.extend(if t.w < 0.0 { -1.0 } else { 1.0 }),
        None => perpendicular(n).extend(1.0),
    }
}
