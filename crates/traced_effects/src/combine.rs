//! The combination of the traced radiance with a rasterised view (thesis 6.3.4-6.3.5): the
//! radiance traced at quarter resolution reaches each full-resolution mirror or glass pixel
//! through a depth-aware 3x3 gather (the thesis's "smart" blur, which keeps silhouettes from
//! bleeding): the texels of the 3x3 neighbourhood around the pixel's position on the quarter
//! grid that have a ray and lie at a similar view depth (within `5% + 5 cm`), weighted by a
//! tent of radius 1.5 texels in each axis. The pixel adds the gathered reflected radiance with
//! the RGB weight `mirror + transparency * F` and the refracted with `transparency * (1 - F)`,
//! `F` Schlick's Fresnel term of the glass at the pixel and `mirror` the smooth surface's
//! traced specular weight ([`scene::Material::mirror_weight`], at the material's base colour:
//! a base-colour texture does not tint the mirror).
//!
//! [`traced_radiance`] is the CPU twin of what `crate::gpu::Combine` adds on the GPU.

use crate::ray_casting::RayCast;
use crate::screen::{ScreenGBuffer, ScreenView};
use crate::trace::fresnel_schlick;
use glam::{IVec2, UVec2, Vec2, Vec3};

/// The radiance the combination adds to pixel `px` of the lit view: zero for a pixel that is
/// background, neither mirror nor glass, or finds no texel to gather. `rays` is the ray
/// casting buffer (`ScreenView::quarter` texels) and `traced` the radiance traced per texel
/// (reflected, refracted; zero for a ray not traced). `None` when an input does not fit the
/// view or `px` is outside it.
pub fn traced_radiance(
    view: &ScreenView,
    gbuffer: &ScreenGBuffer<'_>,
    materials: &[scene::Material],
    rays: &[RayCast],
    traced: &[[Vec3; 2]],
    px: UVec2,
) -> Option<Vec3> {
    let (qw, qh) = view.quarter();
    let texels = qw as usize * qh as usize;
    if !gbuffer.fits(view) || rays.len() != texels || traced.len() != texels {
        return None;
    }
    if px.x >= view.width || px.y >= view.height {
        return None;
    }
    let i = (px.y * view.width + px.x) as usize;
    let depth = gbuffer.depth[i];
    let Some(m) = materials.get(gbuffer.material[i] as usize) else { return Some(Vec3::ZERO) };
    if depth <= 0.0 || !is_traced(m) {
        return Some(Vec3::ZERO);
    }
    let p = view.world_position(px.as_vec2(), depth);
    let n = gbuffer.normal[i].normalize();
    let v = (view.eye - p).normalize();
    let f = fresnel_schlick(m.ior, n.dot(v));
    let qc = (px.as_vec2() + 0.5) * 0.5 - 0.5;
    // WGSL's `round` (ties to even).
    let centre = IVec2::new(qc.x.round_ties_even() as i32, qc.y.round_ties_even() as i32);
    let (mut sum_r, mut sum_t, mut wsum) = (Vec3::ZERO, Vec3::ZERO, 0.0);
    for dy in -1..=1 {
        for dx in -1..=1 {
            let q = centre + IVec2::new(dx, dy);
            if q.x < 0 || q.y < 0 || q.x >= qw as i32 || q.y >= qh as i32 {
                continue;
            }
            let k = (q.y * qw as i32 + q.x) as usize;
            let d = rays[k].origin[3];
            if d <= 0.0 || (d - depth).abs() > 0.05 * depth + 0.05 {
                continue;
            }
            let off = (q.as_vec2() - qc).abs();
            let w = (Vec2::splat(1.5) - off).max(Vec2::ZERO).element_product();
            sum_r += traced[k][0] * w;
            sum_t += traced[k][1] * w;
            wsum += w;
        }
    }
    if wsum <= 0.0 {
        return Some(Vec3::ZERO);
    }
    let (wr, wt) = (m.mirror_weight(n.dot(v)) + m.transparency * f, m.transparency * (1.0 - f));
    Some(wr * sum_r / wsum + wt * sum_t / wsum)
}

/// True when a pixel of material `m` has traced light: a smooth surface (its specular lobe
/// is a mirror ray) or a transparent one.
pub(crate) fn is_traced(m: &scene::Material) -> bool {
    m.brdf().is_smooth() || m.transparency > 0.0
}
