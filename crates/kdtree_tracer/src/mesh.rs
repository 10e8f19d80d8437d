//! Triangle mesh input: positions + indices, any number of meshes concatenated with a mesh id.

use glam::Vec3;

use crate::error::Error;

/// Triangles to trace against: one or more indexed meshes concatenated.
///
/// Every mesh added with [`Mesh::push`] gets the next mesh id (0, 1, ...); triangle indices
/// in a [`crate::Hit`] are global (over the concatenation), and [`Mesh::first_triangle`]
/// turns them back into per-mesh indices. Positions are checked when they are added: a NaN or
/// infinite coordinate, or an index past the vertex count, is a typed [`Error`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    positions: Vec<Vec3>,
    indices: Vec<[u32; 3]>,
    triangle_mesh: Vec<u32>,
    first_triangle: Vec<u32>,
    first_vertex: Vec<u32>,
}

impl Mesh {
    /// An empty mesh (no triangles: every ray misses).
    pub fn new() -> Self {
        Self::default()
    }

    /// A single indexed mesh (mesh id 0).
    pub fn from_indexed(positions: &[Vec3], indices: &[[u32; 3]]) -> Result<Self, Error> {
        let mut m = Self::new();
        m.push(positions, indices)?;
        Ok(m)
    }

    /// A single mesh from a triangle soup (three positions per triangle).
    pub fn from_triangles(triangles: &[[Vec3; 3]]) -> Result<Self, Error> {
        let positions: Vec<Vec3> = triangles.iter().flatten().copied().collect();
        let indices: Vec<[u32; 3]> =
            (0..triangles.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        Self::from_indexed(&positions, &indices)
    }

    /// Appends a mesh and returns its mesh id. Indices are local to `positions`.
    pub fn push(&mut self, positions: &[Vec3], indices: &[[u32; 3]]) -> Result<u32, Error> {
        let mesh = self.first_triangle.len() as u32;
        check_positions(mesh, positions)?;
        for (t, tri) in indices.iter().enumerate() {
            for &i in tri {
                if i as usize >= positions.len() {
                    return Err(Error::IndexOutOfRange {
                        mesh,
                        triangle: t as u32,
                        index: i,
                        vertex_count: positions.len() as u32,
                    });
                }
            }
        }
        let total = self.indices.len() + indices.len();
        if total > crate::tree::MAX_TRIANGLES {
            return Err(Error::TooManyTriangles(total));
        }
        let base = self.positions.len() as u32;
        self.first_triangle.push(self.indices.len() as u32);
        self.first_vertex.push(base);
        self.positions.extend_from_slice(positions);
        self.indices.extend(indices.iter().map(|t| [t[0] + base, t[1] + base, t[2] + base]));
        self.triangle_mesh.extend(std::iter::repeat_n(mesh, indices.len()));
        Ok(mesh)
    }

    /// Replaces the positions of mesh `mesh` (same vertex count), e.g. for animated geometry
    /// traced through [`crate::BvhAccel::update`].
    pub fn set_positions(&mut self, mesh: u32, positions: &[Vec3]) -> Result<(), Error> {
        let m = mesh as usize;
        let start = *self
            .first_vertex
            .get(m)
            .ok_or_else(|| Error::InvalidSettings(format!("mesh {mesh} does not exist")))?
            as usize;
        let end = self.first_vertex.get(m + 1).map_or(self.positions.len(), |&e| e as usize);
        if end - start != positions.len() {
            return Err(Error::BufferSize {
                len: positions.len(),
                width: (end - start) as u32,
                height: 1,
                expected: end - start,
            });
        }
        check_positions(mesh, positions)?;
        self.positions[start..end].copy_from_slice(positions);
        Ok(())
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn mesh_count(&self) -> usize {
        self.first_triangle.len()
    }

    /// All positions (global vertex numbering).
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// All triangles (global vertex numbering).
    pub fn indices(&self) -> &[[u32; 3]] {
        &self.indices
    }

    /// The mesh id of global triangle `triangle`.
    pub fn mesh_of(&self, triangle: u32) -> u32 {
        self.triangle_mesh[triangle as usize]
    }

    /// Global index of the first triangle of mesh `mesh`.
    pub fn first_triangle(&self, mesh: u32) -> u32 {
        self.first_triangle[mesh as usize]
    }

    /// The three corners of global triangle `triangle`.
    pub fn triangle(&self, triangle: u32) -> [Vec3; 3] {
        let [a, b, c] = self.indices[triangle as usize];
        [self.positions[a as usize], self.positions[b as usize], self.positions[c as usize]]
    }

    /// True for triangles with exactly zero area (repeated or collinear vertices, checked in
    /// f64): they are left out of every structure and never reported as hits.
    pub fn is_degenerate(&self, triangle: u32) -> bool {
        let [a, b, c] = self.triangle(triangle);
        crate::triangle::is_degenerate(a, b, c)
    }

    /// Bounding box `(min, max)` of all vertices used by triangles; `None` when empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut it = self.indices.iter().flatten().map(|&i| self.positions[i as usize]);
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }
}

fn check_positions(mesh: u32, positions: &[Vec3]) -> Result<(), Error> {
    match positions.iter().position(|p| !p.is_finite()) {
        Some(v) => {
            let p = positions[v];
            Err(Error::NonFiniteVertex { mesh, vertex: v as u32, x: p.x, y: p.y, z: p.z })
        }
        None => Ok(()),
    }
}
