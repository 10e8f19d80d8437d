//! A scene's emissive surfaces as a few point lights, for renderers that light with point
//! lights and cube shadows (the engine): each light stands for a patch of emissive triangles
//! and sends its patch's radiant intensity along a cosine lobe about the patch's normal, with
//! the inverse square softened by the patch's area ([`EmitterShape`]).
//!
//! The patches: the emissive triangles (front side by winding, as the reference path tracer
//! reads them; both sides for a double-sided material; the emission times the emissive
//! texture's mean over the triangle) are grouped by material and by the
//! axis their normal is closest to (six groups per material, so that a closed emissive box
//! or sphere does not average its normals to nothing); then, while there are fewer patches
//! than the budget, the patch with the largest power times size whose bounding box is
//! longer than [`SPLIT_FRACTION`] of the scene's is cut in two at the median of its
//! triangles along its longest axis. Over budget, the most powerful patches are kept and the
//! share of the power left out is reported.
//!
//! A patch of area `A` (its area-weighted normals summed: the area it shows along its
//! normal), mean emitted radiance `L` and normal `n` has radiant intensity `L A cos` in the
//! direction at angle `theta` from `n`, which its light sends from its centroid (a one-sided
//! patch's from a little in front of it, clear of the patch in its own shadow map). The softened inverse
//! square `1 / (d² + A / pi)` makes the irradiance on the axis of a disk of area `A` exact
//! (`E = pi L R² / (d² + R²)`), where a point's `1 / d²` would grow without bound near the
//! patch; off the axis and near a large patch the lobe and the centroid's direction are the
//! approximation's price, which the `area_lights` component of the engine's ledger measures
//! against the reference. Under a 1 m square (the stand-in's irradiance over the square's,
//! integrated; `tests/emitters.rs`):
//!
//! | height | on the axis | half a side off | a side off |
//! |---|---|---|---|
//! | 0.25 m | 1.02 | 0.22 | 0.42 |
//! | 0.5 m | 1.03 | 0.58 | 0.57 |
//! | 1 m | 1.02 | 0.91 | 0.81 |
//! | 2 m | 1.01 | 1.00 | 0.97 |
//! | 4 m | 1.01 | 1.00 | 1.00 |
//!
//! So a patch is cut where it is large against the scene ([`SPLIT_FRACTION`]), which keeps
//! most receivers a few patch sizes away.

use crate::light::{EmitterShape, PointLight};
use crate::{Aabb, Scene, SceneTriangles};
use glam::Vec3;

/// A patch whose bounding box's diagonal is at most this share of the scene's is not cut.
pub const SPLIT_FRACTION: f32 = 1.0 / 8.0;

/// The emissive surfaces as point lights ([`emitter_lights`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EmitterLights {
    /// One light per patch, most powerful first.
    pub lights: Vec<PointLight>,
    /// The share of the emitters' power (luminance of `pi L A`) the lights leave out because
    /// the budget held fewer patches than the emitters' materials and sides made (0 when all
    /// are kept).
    pub power_left_out: f32,
}

/// One emissive triangle.
#[derive(Clone, Copy, Debug)]
struct Emitter {
    centroid: Vec3,
    corners: Aabb,
    /// The (front) normal times the area.
    area_normal: Vec3,
    radiance: Vec3,
}

impl Emitter {
    fn power(&self) -> f32 {
        luminance(self.radiance) * self.area_normal.length()
    }
}

fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// A group of emissive triangles that one light stands for.
#[derive(Clone, Debug)]
struct Patch {
    name: String,
    two_sided: bool,
    emitters: Vec<Emitter>,
}

impl Patch {
    fn power(&self) -> f32 {
        self.emitters.iter().map(Emitter::power).sum()
    }

    fn bounds(&self) -> Aabb {
        self.emitters.iter().fold(Aabb::EMPTY, |b, e| b.union(e.corners))
    }

    /// The two halves at the median of the centroids along the longest axis.
    fn split(mut self) -> (Patch, Patch) {
        let b = Aabb::from_points(self.emitters.iter().map(|e| e.centroid));
        let axis = b.size().max_position();
        self.emitters.sort_by(|a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
        let back = self.emitters.split_off(self.emitters.len() / 2);
        let other = Patch { emitters: back, ..self.clone() };
        (self, other)
    }

    /// The patch's light, `None` when its area-weighted normals cancel out.
    fn light(&self, radius: f32, offset: f32) -> Option<PointLight> {
        let area_normal: Vec3 = self.emitters.iter().map(|e| e.area_normal).sum();
        let area = area_normal.length();
        let normal = area_normal.try_normalize()?;
        let total: f32 = self.emitters.iter().map(|e| e.area_normal.length()).sum();
        let flux: Vec3 = self.emitters.iter().map(|e| e.radiance * e.area_normal.length()).sum();
        let centroid: Vec3 =
            self.emitters.iter().map(|e| e.centroid * e.area_normal.length()).sum::<Vec3>() / total;
        let radiance = flux / total;
        let shape = EmitterShape { normal, area, two_sided: self.two_sided };
        let offset = if self.two_sided { 0.0 } else { offset };
        Some(PointLight::emitter(&self.name, centroid + normal * offset, radiance, shape, radius))
    }
}

/// The emissive texture's mean over a triangle of texture coordinates `uv` (white without
/// one): a trilinear sample at its centre, at the level whose texel covers its area.
fn emissive_texel(scene: &Scene, m: &crate::Material, uv: [glam::Vec2; 3]) -> Vec3 {
    let Some(t) = m.emissive_texture.and_then(|id| scene.textures.get(id.index())) else {
        return Vec3::ONE;
    };
    let uv_area = 0.5 * (uv[1] - uv[0]).perp_dot(uv[2] - uv[0]).abs();
    let texels = uv_area * t.width() as f32 * t.height() as f32;
    let lod = if texels > 1.0 { 0.5 * texels.log2() } else { 0.0 };
    let texel = t.sample_trilinear((uv[0] + uv[1] + uv[2]) / 3.0, lod).truncate();
    if texel.is_finite() { texel.max(Vec3::ZERO) } else { Vec3::ONE }
}

/// The six axis directions a normal is binned by.
fn axis_bin(n: Vec3) -> usize {
    let a = n.abs();
    let axis = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    axis * 2 + usize::from(n[axis] < 0.0)
}

/// The emissive surfaces of `scene` (its triangles `triangles`, [`Scene::triangles`]) as at
/// most `budget` point lights whose range covers the scene, a one-sided patch's placed
/// `offset` in front of it (clear of the patch in the light's own shadow map), a two-sided
/// one's on it. See the module doc.
pub fn emitter_lights(
    scene: &Scene,
    triangles: &SceneTriangles,
    budget: usize,
    offset: f32,
) -> EmitterLights {
    let mut groups: Vec<((usize, usize), Patch)> = Vec::new();
    for (t, &material) in triangles.materials.iter().enumerate() {
        let Some(m) = scene.materials.get(material as usize) else { continue };
        if !m.is_emissive() {
            continue;
        }
        let [a, b, c] = triangles.triangle(t);
        let area_normal = 0.5 * (b - a).cross(c - a);
        if !area_normal.is_finite() || area_normal.length() <= 0.0 {
            continue;
        }
        let corners = Aabb::from_points([a, b, c]);
        let radiance = m.emission * emissive_texel(scene, m, triangles.corner_uvs(t));
        if radiance.max_element() <= 0.0 {
            continue;
        }
        let e = Emitter { centroid: (a + b + c) / 3.0, corners, area_normal, radiance };
        let key = (material as usize, axis_bin(area_normal));
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, p)) => p.emitters.push(e),
            None => {
                let p =
                    Patch { name: m.name.clone(), two_sided: m.double_sided, emitters: vec![e] };
                groups.push((key, p));
            }
        }
    }
    let mut patches: Vec<Patch> = groups.into_iter().map(|(_, p)| p).collect();
    let total: f32 = patches.iter().map(Patch::power).sum();
    let bounds = scene.bounds();
    let diagonal = if bounds.is_empty() { 0.0 } else { bounds.size().length() };
    let min_split = diagonal * SPLIT_FRACTION;
    while patches.len() < budget {
        let size = |p: &Patch| p.bounds().size().length();
        let candidate = patches
            .iter()
            .enumerate()
            .filter(|(_, p)| p.emitters.len() > 1 && size(p) > min_split)
            .max_by(|(_, a), (_, b)| (a.power() * size(a)).total_cmp(&(b.power() * size(b))));
        let Some((i, _)) = candidate else { break };
        let (a, b) = patches.swap_remove(i).split();
        patches.push(a);
        patches.push(b);
    }
    patches.sort_by(|a, b| b.power().total_cmp(&a.power()));
    patches.truncate(budget);
    let kept: f32 = patches.iter().map(Patch::power).sum();
    // Reach: the whole scene from anywhere in it.
    let radius = diagonal.max(offset * 4.0);
    let lights = patches.iter().filter_map(|p| p.light(radius, offset)).collect();
    let power_left_out = if total > 0.0 { (1.0 - kept / total).max(0.0) } else { 0.0 };
    EmitterLights { lights, power_left_out }
}
