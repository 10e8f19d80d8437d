//! The ray casting buffer (thesis 6.2.6, Table 6.1): at quarter resolution (one texel per 2x2
//! block of pixels), the first pixel of the block with a smooth or transparent material (its
//! specular lobe traced, [`scene::Material`]) writes its world position and view depth, and
//! its reflection and refraction directions with their weights (reflection: the largest
//! channel of [`scene::Material::mirror_weight`] `+ transparency * F`; refraction:
//! `transparency * (1 - F)`, `F` Schlick's Fresnel term of the glass; 0 under total internal reflection or where that kind
//! of ray is switched off). Texels without such a pixel have no ray.
//!
//! [`cast_rays`] computes the buffer on the CPU; `crate::gpu::RayCasting` writes it on the
//! GPU, lists the texels that have a ray ([`ListedRay`]) and reads the list back, which
//! [`batch`] turns into the rays to trace ([`RayBatch`], in texel order).

use crate::screen::{ScreenGBuffer, ScreenView};
use crate::trace::{TraceRay, fresnel_schlick};
use bytemuck::{Pod, Zeroable};
use glam::{UVec2, Vec3};

/// One texel of the ray casting buffer (`RayCast` in `shaders/traced_effects/common.inc.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct RayCast {
    /// World-space origin; w: the pixel's view depth (0: no ray).
    pub origin: [f32; 4],
    /// Unit reflection direction; w: its weight.
    pub reflect: [f32; 4],
    /// Unit refraction direction; w: its weight.
    pub refract: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<RayCast>() == 48);

impl RayCast {
    /// Whether the texel has a ray (a mirror or glass pixel wrote it).
    pub fn has_ray(&self) -> bool {
        self.origin[3] > 0.0
    }
}

/// A texel that has a ray, as the GPU lists them (`ListedRay` in
/// `shaders/traced_effects/raycast.wgsl`): its [`RayCast`] and its index.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ListedRay {
    pub ray: RayCast,
    /// The texel's index (`y * quarter width + x`), then padding.
    pub texel: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<ListedRay>() == 64);

/// Which kinds of rays the buffer gets (a switched-off kind gets no weight, so it is not
/// traced).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayKinds {
    pub reflections: bool,
    pub refractions: bool,
}

impl RayKinds {
    /// Reflection and refraction rays.
    pub const ALL: Self = Self { reflections: true, refractions: true };
}

/// The rays to trace: for every texel with a ray, its reflection and refraction ray (those
/// with a weight).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RayBatch {
    /// Texels in the ray casting buffer.
    pub texels: usize,
    /// Per ray: its texel's index and whether it is the refraction ray.
    pub slots: Vec<(u32, bool)>,
    pub rays: Vec<TraceRay>,
}

impl RayBatch {
    /// Per ray, its entry in a traced-radiance buffer of two entries per texel (reflected,
    /// refracted): `2 texel + 1` for a refraction ray.
    pub fn slot_indices(&self) -> impl Iterator<Item = u32> + '_ {
        self.slots.iter().map(|&(texel, refract)| texel * 2 + u32::from(refract))
    }
}

/// The rays of the `listed` texels (of `texels` in the buffer) that have any (weights above
/// zero, finite unit directions), offset off their surface, in the texels' order: the GPU
/// appends in no set order, and the texels' order makes the batch deterministic and keeps
/// neighbouring rays together for the tracer's packets (one pass over the buffer's texels, not
/// a sort of the entries). Entries outside the buffer are left out.
pub fn batch(texels: usize, listed: &[ListedRay]) -> RayBatch {
    let mut at = vec![u32::MAX; texels];
    for (j, l) in listed.iter().enumerate() {
        if let Some(slot) = at.get_mut(l.texel[0] as usize) {
            *slot = j as u32;
        }
    }
    let mut b = RayBatch { texels, ..Default::default() };
    for (i, &j) in at.iter().enumerate().filter(|&(_, &j)| j != u32::MAX) {
        let t = listed[j as usize].ray;
        if !t.has_ray() {
            continue;
        }
        let o = Vec3::from_slice(&t.origin[..3]);
        let eps = 1e-3 * (1.0 + o.abs().max_element()) + 1e-4 * t.origin[3];
        for (dir, refract) in [(t.reflect, false), (t.refract, true)] {
            let d = Vec3::from_slice(&dir[..3]);
            if dir[3] > 0.0 && d.is_finite() && d.length_squared() > 0.5 {
                b.slots.push((i as u32, refract));
                b.rays.push(TraceRay { origin: o + d * eps, dir: d });
            }
        }
    }
    b
}

/// The ray casting buffer of a G-buffer on the CPU, texel `y * quarter width + x` (the GPU
/// path's twin, `shaders/traced_effects/raycast.wgsl`). A material index outside
/// `materials` is neither mirror nor glass. `None` when the G-buffer does not fit the view.
pub fn cast_rays(
    view: &ScreenView,
    gbuffer: &ScreenGBuffer<'_>,
    materials: &[scene::Material],
    kinds: RayKinds,
) -> Option<Vec<RayCast>> {
    if !gbuffer.fits(view) {
        return None;
    }
    let (qw, qh) = view.quarter();
    let texel = |q: UVec2| -> RayCast {
        // The first of the block's pixels with a mirror or glass part.
        let found = (0..4u32).find_map(|k| {
            let px = UVec2::new(q.x * 2 + (k & 1), q.y * 2 + (k >> 1));
            if px.x >= view.width || px.y >= view.height {
                return None;
            }
            let i = (px.y * view.width + px.x) as usize;
            let m = materials.get(gbuffer.material[i] as usize)?;
            let depth = gbuffer.depth[i];
            (depth > 0.0 && crate::combine::is_traced(m)).then_some((px, i, m, depth))
        });
        let Some((px, i, m, depth)) = found else { return RayCast::default() };
        let p = view.world_position(px.as_vec2(), depth);
        let n = gbuffer.normal[i].normalize();
        let v = (view.eye - p).normalize();
        let f = fresnel_schlick(m.ior, n.dot(v));
        let r = (-v).reflect(n);
        let mut t = (-v).refract(n, 1.0 / m.ior.max(1e-3));
        let mut wt = m.transparency * (1.0 - f);
        if t.dot(t) < 1e-12 {
            (t, wt) = (Vec3::ZERO, 0.0);
        }
        let mirror = m.mirror_weight(n.dot(v)).max_element();
        let wr = if kinds.reflections { mirror + m.transparency * f } else { 0.0 };
        let wt = if kinds.refractions { wt } else { 0.0 };
        RayCast {
            origin: p.extend(depth).to_array(),
            reflect: r.extend(wr).to_array(),
            refract: (t + Vec3::splat(1e-20)).normalize().extend(wt).to_array(),
        }
    };
    Some((0..qh).flat_map(|y| (0..qw).map(move |x| UVec2::new(x, y))).map(texel).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn listed(texel: u32, reflect: f32, refract: f32) -> ListedRay {
        ListedRay {
            ray: RayCast {
                origin: [texel as f32, 0.0, 0.0, 2.0],
                reflect: [0.0, 1.0, 0.0, reflect],
                refract: [0.0, 0.0, -1.0, refract],
            },
            texel: [texel, 0, 0, 0],
        }
    }

    /// The GPU's list in any order gives the same batch, in the texels' order; rays without
    /// weight and texels outside the buffer are left out.
    #[test]
    fn batch_is_in_texel_order_whatever_the_list_order() {
        let list = [
            listed(7, 1.0, 0.0),
            listed(2, 0.5, 0.5),
            listed(99, 1.0, 1.0),
            listed(4, 0.0, 0.0),
            listed(0, 0.0, 1.0),
        ];
        let b = batch(10, &list);
        assert_eq!(b.texels, 10);
        assert_eq!(b.slots, vec![(0, true), (2, false), (2, true), (7, false)]);
        assert_eq!(b.slot_indices().collect::<Vec<_>>(), vec![1, 4, 5, 14]);
        let mut reversed = list;
        reversed.reverse();
        let r = batch(10, &reversed);
        assert_eq!(r.slots, b.slots);
        let origins = |b: &RayBatch| b.rays.iter().map(|r| r.origin.x).collect::<Vec<_>>();
        assert_eq!(origins(&r), origins(&b));
        assert!(
            b.rays.iter().zip(&b.slots).all(|(r, &(i, _))| (r.origin.x - i as f32).abs() < 0.1)
        );
    }
}
