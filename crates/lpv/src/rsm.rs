//! A reflective shadow map's texels as the LPV's inputs on the CPU: every covered texel a
//! [`Vpl`] and, for the geometry volume, a [`Surfel`]. This is the CPU twin of the GPU path's
//! injection straight from an RSM's textures (`shaders/lpv/inject_rsm.wgsl`, used by
//! `gpu::ResidentLpv`, feature `gpu`): a renderer that reads its RSM back and updates the
//! [`Lpv`] on the CPU feeds [`Lpv::update`] with [`rsm_vpls`] and [`rsm_surfels`] and gets
//! the volumes the GPU path computes from the same texels (to rounding; `tests/gpu.rs`
//! checks it).
//!
//! The texels come as plain slices of the same length (row-major, any size): world
//! positions, normals (a zero normal is an empty texel; others need not be unit) and, for
//! VPLs, the flux each texel reflects (`albedo * E * texel_area`).
//!
//! [`Lpv`]: crate::Lpv
//! [`Lpv::update`]: crate::Lpv::update

use crate::LpvError;
use crate::vpl::{Surfel, Vpl};
use glam::Vec3;

/// The smallest `|n.l|` a surfel's area is divided by ([`surfel_area`]): a texel seen at a
/// grazing angle stands for `texel_area / |n.l|` of surface, which this bound keeps finite
/// (at most 5 texel areas). `inject_rsm.wgsl` uses the same literal (`max(abs(dot(n,
/// rsm.to_light.xyz)), 0.2)`); a test checks that the shader source still says so.
pub const SURFEL_MIN_COS: f32 = 0.2;

/// The surface one RSM texel covers: `texel_area / max(|n.to_light|, SURFEL_MIN_COS)`, the
/// texel's area across the light spread over a surface tilted away from it. `normal` is used
/// as given (the shader normalises first; an RSM's normals are unit up to their format's
/// rounding).
pub fn surfel_area(normal: Vec3, texel_area: f32, to_light: Vec3) -> f32 {
    texel_area / normal.dot(to_light).abs().max(SURFEL_MIN_COS)
}

/// Whether a texel holds a surface (a non-zero normal; the RSM clears empty texels to 0).
fn covered(normal: Vec3) -> bool {
    normal.length_squared() > 0.0
}

/// One VPL per covered texel (position, normal, flux as they are; [`Lpv::update`] skips
/// VPLs that emit nothing). Slices of different lengths are [`LpvError::PlaneLengths`].
///
/// [`Lpv::update`]: crate::Lpv::update
pub fn rsm_vpls(position: &[Vec3], normal: &[Vec3], flux: &[Vec3]) -> Result<Vec<Vpl>, LpvError> {
    same_lengths(position, normal, Some(flux))?;
    Ok(position
        .iter()
        .zip(normal)
        .zip(flux)
        .filter(|((_, n), _)| covered(**n))
        .map(|((&p, &n), &f)| Vpl::new(p, n, f))
        .collect())
}

/// One surfel per covered texel, of area [`surfel_area`] for texels `texel_area` across (in
/// world units², perpendicular to the light) and the unit direction `to_light` towards the
/// light. Slices of different lengths are [`LpvError::PlaneLengths`].
pub fn rsm_surfels(
    position: &[Vec3],
    normal: &[Vec3],
    texel_area: f32,
    to_light: Vec3,
) -> Result<Vec<Surfel>, LpvError> {
    same_lengths(position, normal, None)?;
    Ok(position
        .iter()
        .zip(normal)
        .filter(|(_, n)| covered(**n))
        .map(|(&p, &n)| Surfel::new(p, n, surfel_area(n, texel_area, to_light)))
        .collect())
}

/// The planes' lengths agree (`flux` only where the caller takes one).
fn same_lengths(position: &[Vec3], normal: &[Vec3], flux: Option<&[Vec3]>) -> Result<(), LpvError> {
    let flux_len = flux.map_or(position.len(), <[Vec3]>::len);
    if position.len() == normal.len() && flux_len == position.len() {
        return Ok(());
    }
    Err(LpvError::PlaneLengths {
        position: position.len(),
        normal: normal.len(),
        flux: flux.map_or(0, <[Vec3]>::len),
    })
}
