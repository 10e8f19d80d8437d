//! The sun mirrored by large planar specular surfaces (a glass curtain wall, a mirror) onto
//! the surfaces in front of them: light the thesis's engine never had and the reference
//! carries (its caustic photons), measured on the city's ledger as most of the east facade's
//! light across the street from the glass tower (`app/examples/specular_transport.rs`).
//!
//! Each reflector is a rectangle in a plane with the reflectance of its material's sharp
//! specular parts: `(1 - t) F(cos) + t F_glass(cos)` (the specular lobe, counted when the
//! material's roughness is below [`MAX_ROUGHNESS`], with `F` the BRDF's Schlick Fresnel at
//! the lobe's brightest channel; the glass part's Fresnel reflection; `t` the transparency). The lighting pass
//! (`shaders/engine/mirrored_sun.inc.wgsl`) lights a pixel in front of a reflector as by a
//! second sun from the mirrored direction, when the ray towards it meets the rectangle, scaled
//! by that reflectance and the real sun's visibility where the ray meets the reflector (the
//! view's cascades); it loops only over the reflectors that may light the view
//! ([`ReflectorSet::in_view`]). Not modelled: occluders between the pixel and the reflector, the
//! glossy lobe's spread (the mirrored sun is a point direction) and curved reflectors (the
//! statue). The traced G-buffer lit on the GPU (`engine::TracedShading::Gpu`) includes the same
//! snippet (with the overlapped maps' visibility at the reflector); the traced rays'
//! surfaces lit on the CPU get it from the CPU twin ([`Reflector::mirror`], in
//! `crate::trace`) with shadow rays, which also see occluders between a hit and the
//! reflector.
//!
//! On the city's ledger it brings the east facade across from the glass tower from a seventh
//! of the reference's light to the reference's, and lowers the whole frame's error
//! (`docs/measured.md` has the figures). The engine's presets turn it on
//! (`engine::Settings::mirrored_sun`).

use glam::Vec3;
use std::collections::HashMap;

/// Most reflectors the lighting pass loops over (the largest are kept).
pub const MAX_REFLECTORS: usize = 16;
/// Smallest reflector, m² (a pane or a window is not one; a wall of them is).
pub const MIN_AREA: f32 = 4.0;
/// Largest roughness whose specular lobe counts as mirroring the sun (about 4 degrees wide:
/// the thesis's Phong power 256 converted, `scene::PhongParams::to_metallic_roughness`).
pub const MAX_ROUGHNESS: f32 = 0.3;
/// Smallest normal-incidence reflectance that makes a surface a reflector: a glass pane's
/// 4 % (which grows to most of the light at grazing incidence) qualifies.
pub const MIN_REFLECTANCE: f32 = 0.03;

/// One reflector as the lighting shader reads it (`Reflector` in
/// `shaders/engine/mirrored_sun.inc.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Reflector {
    /// Centre of the rectangle; w: half its extent along `axis_u`.
    pub center: [f32; 4],
    /// Unit normal of its plane; w: half its extent along `normal x axis_u`.
    pub normal: [f32; 4],
    /// Unit axis in the plane; w: 1 when both sides reflect (glass), else 0.
    pub axis_u: [f32; 4],
    /// The specular lobe's normal-incidence reflectance `F0` (brightest channel; 0 for a
    /// lobe rougher than [`MAX_ROUGHNESS`]), the glass part (transparency `t`), its index of
    /// refraction, the lobe's share `1 - t`.
    pub params: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<Reflector>() == 64);

/// The lighting pass's uniform (`Reflectors` in `shaders/engine/mirrored_sun.inc.wgsl`):
/// the count, then [`MAX_REFLECTORS`] slots.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ReflectorSet {
    pub count: [u32; 4],
    pub items: [Reflector; MAX_REFLECTORS],
}

impl ReflectorSet {
    /// The first [`MAX_REFLECTORS`] of `reflectors`.
    pub fn new(reflectors: &[Reflector]) -> Self {
        let mut set = Self { count: [0; 4], items: [Reflector::default(); MAX_REFLECTORS] };
        let n = reflectors.len().min(MAX_REFLECTORS);
        set.items[..n].copy_from_slice(&reflectors[..n]);
        set.count[0] = n as u32;
        set
    }

    /// The first [`MAX_REFLECTORS`] of `reflectors` that may light a point of the view
    /// (`frustum`) inside `bounds` with the sun in unit direction `l`
    /// ([`Reflector::may_light`]): what a pixel's loop needs, the others giving nothing there.
    pub fn in_view(
        reflectors: &[Reflector],
        l: Vec3,
        bounds: &scene::Aabb,
        frustum: &scene::Frustum,
    ) -> Self {
        let mut set = Self::new(&[]);
        let lit = reflectors.iter().filter(|r| r.may_light(l, bounds, frustum));
        for (slot, r) in set.items.iter_mut().zip(lit) {
            *slot = *r;
            set.count[0] += 1;
        }
        set
    }
}

/// What a reflector sends to a point ([`Reflector::mirror`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mirrored {
    /// Unit direction from the point towards the mirrored sun.
    pub dir: Vec3,
    /// The reflector's reflectance for the sun.
    pub reflectance: f32,
    /// Where the light leaves the reflector, and the reflector's normal on the sun's side.
    pub at: Vec3,
    pub normal: Vec3,
}

impl Reflector {
    /// What this reflector sends of the sun in unit direction `l` to point `p`: `None` when
    /// `p` is behind it (or within 1 cm of its plane), the sun is behind a one-sided
    /// reflector, or the ray towards the mirrored sun misses the rectangle. The twin of
    /// `mirrored_sun` in `shaders/engine/mirrored_sun.inc.wgsl`.
    pub fn mirror(&self, p: Vec3, l: Vec3) -> Option<Mirrored> {
        let (c, n0, u) = (xyz(self.center), xyz(self.normal), xyz(self.axis_u));
        let (mut n, mut cos_l) = (n0, l.dot(n0));
        if cos_l < 0.0 && self.axis_u[3] > 0.5 {
            (n, cos_l) = (-n, -cos_l);
        }
        let height = (p - c).dot(n);
        if cos_l <= 0.0 || height <= 0.01 {
            return None;
        }
        let dir = l - 2.0 * cos_l * n;
        let at = p + dir * (height / cos_l);
        let d = at - c;
        let inside = d.dot(u).abs() <= self.center[3] && d.dot(n0.cross(u)).abs() <= self.normal[3];
        inside.then(|| Mirrored { dir, reflectance: self.reflectance(cos_l), at, normal: n })
    }

    /// False only when no point inside both `bounds` and `frustum` can get this reflector's
    /// light of the sun in unit direction `l` ([`Reflector::mirror`] is `None` there): the sun
    /// is behind it or along its plane, or the prism its rectangle sweeps along the mirrored
    /// light (to the far side of `bounds`) lies outside one of the frustum's planes. What
    /// the view's lighting loops over (`engine`: the reflectors of the frame).
    pub fn may_light(&self, l: Vec3, bounds: &scene::Aabb, frustum: &scene::Frustum) -> bool {
        let (c, n0, u) = (xyz(self.center), xyz(self.normal), xyz(self.axis_u));
        let (mut n, mut cos_l) = (n0, l.dot(n0));
        if cos_l < 0.0 && self.axis_u[3] > 0.5 {
            (n, cos_l) = (-n, -cos_l);
        }
        if cos_l.is_nan() || cos_l <= 0.0 || bounds.is_empty() {
            return false;
        }
        let (hu, hv) = (u * self.center[3], n0.cross(u) * self.normal[3]);
        // The light leaves along reflect(-l, n); every lit point of `bounds` is within the
        // box's diagonal of the rectangle along it.
        let out = (2.0 * cos_l * n - l) * (bounds.max - bounds.min).length();
        let corners = [c + hu + hv, c + hu - hv, c - hu + hv, c - hu - hv];
        let hull = corners.map(|k| [k, k + out]);
        let inside = |p: &glam::Vec4, k: &Vec3| p.truncate().dot(*k) + p.w >= 0.0;
        frustum.planes.iter().all(|p| hull.iter().flatten().any(|k| inside(p, k)))
    }

    /// Reflectance of the reflector's specular parts for the sun at incidence cosine `cos`
    /// (Fresnel-Schlick for the glass part, as the engine's shaders).
    pub fn reflectance(&self, cos: f32) -> f32 {
        let [f0, glass, ior, lobe] = self.params;
        let f = scene::brdf::fresnel_schlick(Vec3::splat(f0), cos).x;
        lobe * f + glass * crate::trace::fresnel_schlick(ior, cos)
    }
}

fn xyz(v: [f32; 4]) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

/// The specular parts of a material that mirror the sun ([`Reflector::params`]), or `None`
/// when together they reflect less than [`MIN_REFLECTANCE`] at normal incidence.
fn sharp_parts(m: &scene::Material) -> Option<[f32; 4]> {
    let lobe = (1.0 - m.transparency).max(0.0);
    let f0 = if m.roughness <= MAX_ROUGHNESS { m.brdf().f0().max_element() } else { 0.0 };
    let r0 = ((m.ior - 1.0) / (m.ior + 1.0)).powi(2);
    let total = lobe * f0 + m.transparency * r0;
    let parts = [f0, m.transparency, m.ior, lobe];
    (total >= MIN_REFLECTANCE && parts.iter().all(|v| v.is_finite())).then_some(parts)
}

/// Whether a material reflects on both sides: glass, or double-sided.
fn two_sided(m: &scene::Material) -> bool {
    m.double_sided || m.transparency > 0.0
}

/// Triangles of one material in one plane.
#[derive(Default)]
struct Group {
    normal: Vec3,
    area: f32,
    corners: Vec<Vec3>,
}

/// The scene's planar reflectors: its triangles of reflecting materials grouped by material
/// and plane (normals within about a degree, offsets within 2 cm), each group's bounding
/// rectangle in its plane, those of at least [`MIN_AREA`], the [`MAX_REFLECTORS`] largest
/// (largest first). A scene without any gives none.
pub fn planar_reflectors(scene: &scene::Scene) -> Vec<Reflector> {
    let parts: Vec<Option<[f32; 4]>> = scene.materials.iter().map(sharp_parts).collect();
    let tris = scene.triangles();
    let mut groups: HashMap<(u32, [i32; 4]), Group> = HashMap::new();
    for t in 0..tris.indices.len() {
        let material = tris.materials[t];
        if parts.get(material as usize).copied().flatten().is_none() {
            continue;
        }
        let [a, b, c] = tris.triangle(t);
        let cross = (b - a).cross(c - a);
        let (Some(n), area) = (cross.try_normalize(), 0.5 * cross.length()) else { continue };
        // A surface that reflects on both sides: one orientation per plane (the largest
        // component positive); a one-sided mirror keeps its winding's.
        let n = if two_sided(&scene.materials[material as usize]) && n[n.abs().max_position()] < 0.0
        {
            -n
        } else {
            n
        };
        let key = [
            (n.x * 64.0).round(),
            (n.y * 64.0).round(),
            (n.z * 64.0).round(),
            (n.dot(a) * 50.0).round(),
        ];
        let g = groups.entry((material, key.map(|k| k as i32))).or_default();
        g.normal += n * area;
        g.area += area;
        g.corners.extend([a, b, c]);
    }
    let mut out: Vec<(f32, Reflector)> = groups
        .into_iter()
        .filter(|(_, g)| g.area >= MIN_AREA)
        .filter_map(|((material, _), g)| {
            let normal = g.normal.try_normalize()?;
            let up = if normal.y.abs() < 0.9 { Vec3::Y } else { Vec3::X };
            let u = up.cross(normal).normalize();
            let v = normal.cross(u);
            let (mut lo, mut hi) =
                (glam::Vec2::splat(f32::INFINITY), glam::Vec2::splat(f32::NEG_INFINITY));
            let mut offset = 0.0;
            for p in &g.corners {
                let q = glam::Vec2::new(p.dot(u), p.dot(v));
                (lo, hi) = (lo.min(q), hi.max(q));
                offset += p.dot(normal);
            }
            let offset = offset / g.corners.len() as f32;
            let mid = 0.5 * (lo + hi);
            let center = u * mid.x + v * mid.y + normal * offset;
            let half = 0.5 * (hi - lo);
            let m = &scene.materials[material as usize];
            let reflector = Reflector {
                center: center.extend(half.x).to_array(),
                normal: normal.extend(half.y).to_array(),
                axis_u: u.extend(if two_sided(m) { 1.0 } else { 0.0 }).to_array(),
                params: parts[material as usize]?,
            };
            Some((g.area, reflector))
        })
        .collect();
    // Largest first; ties in a fixed order whatever the map's.
    out.sort_by(|a, b| {
        b.0.total_cmp(&a.0)
            .then(a.1.center.partial_cmp(&b.1.center).unwrap_or(std::cmp::Ordering::Equal))
    });
    out.truncate(MAX_REFLECTORS);
    out.into_iter().map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use scene::{Material, MeshData, Scene};

    /// A rectangle with corners `o`, `o + u`, `o + u + v`, `o + v`, wound to face `u x v`.
    fn rectangle(s: &mut Scene, o: Vec3, u: Vec3, v: Vec3, material: scene::MaterialId) {
        let positions = vec![o, o + u, o + u + v, o + v];
        let data =
            MeshData { positions, normals: None, uvs: None, indices: vec![0, 1, 2, 0, 2, 3] };
        s.meshes.push(scene::Mesh::build("rectangle", data, material).unwrap().0);
    }

    #[test]
    fn walls_of_reflecting_panes_become_one_rectangle_each() {
        let mut s = Scene::new("reflectors");
        let mirror = s.add_material(Material::mirror("mirror", 0.9));
        let glass = s.add_material(Material::glass("glass", 0.7, 1.5));
        let matte = s.add_material(Material::diffuse("matte", Vec3::ONE));
        // A 4 x 3 m mirror facing +x in two panes, a 6 x 2 m glass wall in the plane z = -5,
        // a small mirror (1 m²) and a big matte wall: one reflector each for the first two.
        rectangle(&mut s, Vec3::new(0.0, 0.0, 2.0), -Vec3::Z * 2.0, Vec3::Y * 3.0, mirror);
        rectangle(&mut s, Vec3::new(0.0, 0.0, 0.0), -Vec3::Z * 2.0, Vec3::Y * 3.0, mirror);
        rectangle(&mut s, Vec3::new(10.0, 1.0, -5.0), Vec3::X * 6.0, Vec3::Y * 2.0, glass);
        rectangle(&mut s, Vec3::new(20.0, 0.0, 0.0), Vec3::Y, Vec3::Z, mirror);
        rectangle(&mut s, Vec3::new(30.0, 0.0, 0.0), Vec3::Y * 9.0, Vec3::Z * 9.0, matte);
        let r = planar_reflectors(&s);
        assert_eq!(r.len(), 2, "{r:?}");
        // The mirror (12 m²) first: centre, extents, its winding's normal, one-sided.
        let close = |a: [f32; 4], b: [f32; 4]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5);
        assert!(close(r[0].center, [0.0, 1.5, 0.0, 2.0]), "{:?}", r[0]);
        assert!(close(r[0].normal, [1.0, 0.0, 0.0, 1.5]), "{:?}", r[0]);
        assert_eq!(r[0].axis_u[3], 0.0);
        assert!((r[0].reflectance(1.0) - 0.9).abs() < 1e-5, "a smooth metal of F0 0.9");
        // The glass: both sides, its Fresnel part and its lobe.
        assert!(close(r[1].center, [13.0, 2.0, -5.0, 3.0]), "{:?}", r[1]);
        assert_eq!(r[1].normal[2].abs(), 1.0);
        assert_eq!(r[1].axis_u[3], 1.0);
        // The smooth dielectric's share 0.3 and the glass's 0.7, both F0 = 0.04.
        assert!((r[1].reflectance(1.0) - (0.3 * 0.04 + 0.7 * 0.04)).abs() < 1e-5);
        assert!(r[1].reflectance(0.0) > r[1].reflectance(1.0), "Fresnel grows at grazing");
    }

    #[test]
    fn scenes_without_reflectors_have_none() {
        assert!(planar_reflectors(&Scene::new("empty")).is_empty());
        let plane_box = scene::Generated::PlaneBox.build(1);
        assert!(planar_reflectors(&plane_box).is_empty());
        // The city: its two glass towers' walls (and its mirror) but not its curved statue.
        let city = scene::Generated::City.build(1);
        let r = planar_reflectors(&city);
        assert!((8..=MAX_REFLECTORS).contains(&r.len()), "{} reflectors", r.len());
        assert!(r.iter().all(|r| r.center[3] > 0.0 && r.normal[3] > 0.0));
    }
}
