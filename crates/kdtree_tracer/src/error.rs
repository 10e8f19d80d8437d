//! Typed errors for everything that takes user data.

use thiserror::Error;

/// What can go wrong when building or querying an acceleration structure.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum Error {
    /// A vertex position has a NaN or infinite coordinate.
    #[error("mesh {mesh}: vertex {vertex} is not finite ({x}, {y}, {z})")]
    NonFiniteVertex { mesh: u32, vertex: u32, x: f32, y: f32, z: f32 },
    /// A triangle refers to a vertex that does not exist.
    #[error("mesh {mesh}: triangle {triangle} uses vertex {index} but the mesh has {vertex_count}")]
    IndexOutOfRange { mesh: u32, triangle: u32, index: u32, vertex_count: u32 },
    /// More triangles than the compact layout can address.
    #[error("too many triangles: {0} (at most {max})", max = crate::tree::MAX_TRIANGLES)]
    TooManyTriangles(usize),
    /// A settings value is out of its valid range.
    #[error("invalid settings: {0}")]
    InvalidSettings(String),
    /// An image-shaped buffer does not match its stated size.
    #[error("buffer has {len} entries but {width}x{height} needs {expected}")]
    BufferSize { len: usize, width: u32, height: u32, expected: usize },
    /// `validate()` found a broken invariant.
    #[error("invalid structure: {0}")]
    Invalid(String),
}
