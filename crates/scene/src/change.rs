//! What changed between two states of a scene, for the frame scheduler's invalidation
//! (a sun that moved less than a threshold keeps the sky map and sky volume, moved geometry
//! invalidates shadows and the ray tracer's acceleration structure, ...).

use crate::{Camera, OcclusionQuad, PointLight, Scene};
use glam::{Affine3A, Vec3};
use std::fmt;
use std::hash::{Hash, Hasher};

/// A compact snapshot of the parts of a scene whose change invalidates cached work.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneState {
    /// Unit direction towards the sun, or `None` (no sun, or an unusable date/place).
    pub sun_direction: Option<Vec3>,
    pub sun_color: Vec3,
    pub sky: bool,
    /// Per mesh: its transform and a hash of its positions and indices.
    pub meshes: Vec<(Affine3A, u64)>,
    /// Hash of all materials' values.
    pub materials: u64,
    pub point_lights: Vec<PointLight>,
    pub occlusion_quads: Vec<OcclusionQuad>,
    pub camera: Camera,
}

fn hash_f32s<H: Hasher>(h: &mut H, v: impl IntoIterator<Item = f32>) {
    for x in v {
        x.to_bits().hash(h);
    }
}

impl Scene {
    /// Snapshot for change detection (hashes geometry: linear in the vertex count).
    pub fn state(&self) -> SceneState {
        let meshes = self
            .meshes
            .iter()
            .map(|m| {
                let mut h = std::collections::hash_map::DefaultHasher::new();
                hash_f32s(&mut h, m.positions.iter().flat_map(|p| p.to_array()));
                hash_f32s(&mut h, m.colors.iter().flat_map(|c| c.to_array()));
                for t in &m.indices {
                    t.hash(&mut h);
                }
                (m.transform, h.finish())
            })
            .collect();
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for m in &self.materials {
            m.name.hash(&mut h);
            hash_f32s(&mut h, [m.transparency, m.ior]);
            hash_f32s(&mut h, m.emission.to_array());
            hash_f32s(&mut h, m.base_color.extend(m.metallic).to_array());
            hash_f32s(&mut h, [m.roughness, m.normal_scale, m.occlusion_strength]);
            (
                m.albedo_texture,
                m.normal_texture,
                m.metallic_roughness_texture,
                m.occlusion_texture,
                m.emissive_texture,
                m.alpha_mask.map(|a| (a.texture, a.cutoff.to_bits())),
                m.double_sided,
            )
                .hash(&mut h);
        }
        SceneState {
            sun_direction: self.sun.as_ref().and_then(|s| s.direction().ok()),
            sun_color: self.sun.as_ref().map_or(Vec3::ZERO, |s| s.color),
            sky: self.sky,
            meshes,
            materials: h.finish(),
            point_lights: self.point_lights.clone(),
            occlusion_quads: self.occlusion_quads.clone(),
            camera: self.camera,
        }
    }
}

/// The differences between two [`SceneState`]s.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneChange {
    /// Angle the sun moved, degrees (0 if unchanged or absent in both).
    pub sun_moved_deg: f32,
    /// The sun appeared or disappeared.
    pub sun_toggled: bool,
    pub sun_color_changed: bool,
    pub sky_toggled: bool,
    /// Meshes (indices in the newer state) whose transform changed.
    pub meshes_moved: Vec<usize>,
    /// Meshes whose vertex data changed.
    pub meshes_edited: Vec<usize>,
    /// The number of meshes changed.
    pub meshes_added_or_removed: bool,
    pub materials_changed: bool,
    /// Point lights added, removed or modified.
    pub lights_changed: bool,
    pub occlusion_quads_changed: bool,
    pub camera_moved: bool,
}

impl SceneChange {
    /// Compares an older and a newer state.
    pub fn between(old: &SceneState, new: &SceneState) -> Self {
        let (sun_moved_deg, sun_toggled) = match (old.sun_direction, new.sun_direction) {
            (Some(a), Some(b)) => (a.dot(b).clamp(-1.0, 1.0).acos().to_degrees(), false),
            (None, None) => (0.0, false),
            _ => (0.0, true),
        };
        let mut meshes_moved = Vec::new();
        let mut meshes_edited = Vec::new();
        for (i, (a, b)) in old.meshes.iter().zip(&new.meshes).enumerate() {
            if a.0 != b.0 {
                meshes_moved.push(i);
            }
            if a.1 != b.1 {
                meshes_edited.push(i);
            }
        }
        Self {
            sun_moved_deg,
            sun_toggled,
            sun_color_changed: old.sun_color != new.sun_color,
            sky_toggled: old.sky != new.sky,
            meshes_moved,
            meshes_edited,
            meshes_added_or_removed: old.meshes.len() != new.meshes.len(),
            materials_changed: old.materials != new.materials,
            lights_changed: old.point_lights != new.point_lights,
            occlusion_quads_changed: old.occlusion_quads != new.occlusion_quads,
            camera_moved: old.camera != new.camera,
        }
    }

    /// Nothing changed at all.
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// Any mesh moved, was edited, added or removed.
    pub fn geometry_changed(&self) -> bool {
        !self.meshes_moved.is_empty()
            || !self.meshes_edited.is_empty()
            || self.meshes_added_or_removed
    }

    /// Whether work that depends on the sun's direction (sky map, sky volume, shadow maps) is
    /// stale, given how far the sun may move before it is redone.
    pub fn sun_invalidates(&self, threshold_deg: f32) -> bool {
        self.sun_toggled || self.sun_color_changed || self.sun_moved_deg > threshold_deg
    }

    /// Whether the sky volume must be recomputed (sun beyond the threshold, sky toggled, or
    /// its occluders changed).
    pub fn sky_volume_invalidated(&self, threshold_deg: f32) -> bool {
        self.sun_invalidates(threshold_deg) || self.sky_toggled || self.occlusion_quads_changed
    }

    /// One line per change, for a frame report.
    pub fn lines(&self) -> Vec<String> {
        let mut v = Vec::new();
        if self.sun_toggled {
            v.push("sun appeared or disappeared".to_owned());
        } else if self.sun_moved_deg > 0.0 {
            v.push(format!("sun moved by {:.3}°", self.sun_moved_deg));
        }
        if self.sun_color_changed {
            v.push("sun colour changed".to_owned());
        }
        if self.sky_toggled {
            v.push("sky switched on or off".to_owned());
        }
        if !self.meshes_moved.is_empty() {
            v.push(format!("geometry moved: {} meshes", self.meshes_moved.len()));
        }
        if !self.meshes_edited.is_empty() {
            v.push(format!("geometry edited: {} meshes", self.meshes_edited.len()));
        }
        if self.meshes_added_or_removed {
            v.push("meshes added or removed".to_owned());
        }
        if self.materials_changed {
            v.push("materials changed".to_owned());
        }
        if self.lights_changed {
            v.push("point lights changed".to_owned());
        }
        if self.occlusion_quads_changed {
            v.push("occlusion quads changed".to_owned());
        }
        if self.camera_moved {
            v.push("camera moved".to_owned());
        }
        v
    }
}

impl fmt::Display for SceneChange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let lines = self.lines();
        if lines.is_empty() { write!(f, "no change") } else { write!(f, "{}", lines.join("; ")) }
    }
}
