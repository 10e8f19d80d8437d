//! Cube shadow maps for point lights (thesis 4.2): every shadow-casting light's cube rendered
//! by `shadows`' resident pass into one depth cube array over the scene's buffers; the
//! lighting pass samples it with hardware comparison (`shaders/shadows/cube.inc.wgsl`).

use crate::EngineError;
use crate::gpu::{Gpu, SceneBuffers};
use bytemuck::{Pod, Zeroable};
use shadows::gpu::{CubeLight, CubeShadows};

/// Near plane of the cube maps (metres).
pub const CUBE_NEAR: f32 = 0.05;

/// A point light as `lighting.wgsl` reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuPointLight {
    /// Position, radius of influence.
    pub position: [f32; 4],
    /// Colour (intensity), index of its cube in the cube array (-1: no shadows).
    pub color: [f32; 4],
    /// Cube near and far planes, cube face size, unused.
    pub shadow: [f32; 4],
    /// A spot light's cone ([`scene::SpotCone::scale_offset`]): xyz the unit axis times the
    /// falloff's scale, w its offset, so that the falloff in unit direction `dir` from the
    /// light is `saturate(dot(xyz, dir) + w)²`; `(0, 0, 0, 1)` for a point light.
    pub cone: [f32; 4],
    /// An emitter's stand-in ([`scene::PointLight::emitter`]): x [`scene::PointLight::softening`],
    /// y the lobe (`LOBE_*` in `shading.inc.wgsl`: 0 the cone, 1 a one-sided cosine about the
    /// normal in `cone.xyz`, 2 two-sided); zero for a point or spot light.
    pub emitter: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuPointLight>() == 80);

/// How far in front of a one-sided emissive patch its stand-in sits (metres): clear of the
/// patch in its own cube, and a small change of the distance to what it lights.
pub const EMITTER_OFFSET: f32 = 0.01;

/// The lights the engine lights `scene` with: its point and spot lights, then at most
/// `budget` stand-ins for its emissive surfaces ([`scene::emitter_lights`], placed
/// [`EMITTER_OFFSET`] in front of their patches), with the share of the emitters' power the
/// budget left out.
pub fn scene_lights(scene: &scene::Scene, budget: u32) -> (Vec<scene::PointLight>, f32) {
    let mut lights = scene.point_lights.clone();
    if !scene.materials.iter().any(scene::Material::is_emissive) {
        return (lights, 0.0);
    }
    let emitters =
        scene::emitter_lights(scene, &scene.triangles(), budget as usize, EMITTER_OFFSET);
    lights.extend(emitters.lights);
    (lights, emitters.power_left_out)
}

/// Whether a light gets a cube: it casts shadows and its range is longer than the near plane.
fn casts(l: &scene::PointLight) -> bool {
    l.casts_shadows && l.radius.is_finite() && l.radius > CUBE_NEAR * 2.0
}

/// The lights as the lighting pass reads them: light `i`'s cube index is its rank among the
/// lights that cast, in order.
pub fn gpu_lights(lights: &[scene::PointLight], size: u32) -> Vec<GpuPointLight> {
    let mut cube = 0.0f32;
    lights
        .iter()
        .map(|l| {
            let index = if casts(l) {
                cube += 1.0;
                cube - 1.0
            } else {
                -1.0
            };
            GpuPointLight {
                position: l.position.extend(l.radius).to_array(),
                color: l.color.extend(index).to_array(),
                shadow: [CUBE_NEAR, l.radius, size as f32, 0.0],
                cone: match (&l.emitter, &l.spot) {
                    (Some(e), _) => e.normal.extend(0.0).to_array(),
                    (None, Some(c)) => {
                        let (scale, offset) = c.scale_offset();
                        (c.direction * scale).extend(offset).to_array()
                    }
                    (None, None) => [0.0, 0.0, 0.0, 1.0],
                },
                emitter: l.emitter.map_or([0.0; 4], |e| {
                    let lobe = if e.two_sided { 2.0 } else { 1.0 };
                    [l.softening(), lobe, 0.0, 0.0]
                }),
            }
        })
        .collect()
}

pub struct PointShadowPass {
    cubes: CubeShadows,
    lights: Vec<CubeLight>,
}

impl PointShadowPass {
    /// Room for a `size`² cube per shadow-casting light of `lights`.
    pub fn new(
        device: &wgpu::Device,
        lights: &[scene::PointLight],
        size: u32,
    ) -> Result<Self, EngineError> {
        let lights: Vec<CubeLight> = lights
            .iter()
            .filter(|l| casts(l))
            .map(|l| CubeLight { position: l.position, near: CUBE_NEAR, far: l.radius })
            .collect();
        let cubes =
            CubeShadows::new(device, SceneBuffers::SHADOW_LAYOUT, size, lights.len() as u32)
                .map_err(|e| EngineError::technique("shadows", e))?;
        Ok(Self { cubes, lights })
    }

    /// The cube array and its comparison sampler, for the lighting pass.
    pub fn bindings(&self) -> (&wgpu::TextureView, &wgpu::Sampler) {
        (self.cubes.view(), self.cubes.sampler())
    }

    /// Renders every shadow-casting light's cube.
    pub fn render(&self, gpu: &Gpu, scene: &SceneBuffers) -> Result<(), EngineError> {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        self.cubes
            .record(&gpu.queue, &mut enc, &scene.shadow_geometry(false), &self.lights)
            .map_err(|e| EngineError::technique("shadows", e))?;
        gpu.queue.submit([enc.finish()]);
        Ok(())
    }
}
