//! The scene on the GPU (`scene::gpu`, feature `gpu`; runs on lavapipe in CI): what is
//! uploaded is the scene, the material struct and the G-buffer's camera have one size in Rust
//! and WGSL, and the G-buffer pass draws what a small scene shows.
#![cfg(feature = "gpu")]

mod common;

use glam::{Vec2, Vec3, Vec4};
use gpu_harness::gpu_test_context;
use scene::gpu::{
    GBUFFER_WGSL, GBuffer, GBufferCamera, GBufferPass, GpuMaterial, GpuScene, MATERIAL_INC_WGSL,
};
use scene::{AlphaMask, Camera, Material, MaterialId, Mesh, MeshData, Scene, Texture};

/// A GPU context for one test at a time: the G-buffer test counts the bind groups the
/// process creates across a frame (`gpu_harness::bind_groups_created`, a process-wide
/// count), which the other tests here would add to if they ran beside it.
fn serial_gpu() -> (std::sync::MutexGuard<'static, ()>, Option<gpu_harness::GpuContext>) {
    static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let guard = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    (guard, gpu_test_context())
}

#[test]
fn material_struct_has_the_size_of_its_wgsl_twin() {
    let size = gpu_harness::wgsl_struct_size(MATERIAL_INC_WGSL, "Material");
    assert_eq!(size, Ok(std::mem::size_of::<GpuMaterial>()));
}

/// The material table as the GPU holds it.
fn materials(ctx: &gpu_harness::GpuContext, gpu: &GpuScene) -> Vec<GpuMaterial> {
    let bytes = gpu.materials.size();
    gpu_harness::cast_vec(
        &gpu_harness::read_buffer(&ctx.device, &ctx.queue, &gpu.materials, bytes).unwrap(),
    )
}

#[test]
fn uploaded_buffers_hold_the_scene_and_each_material_gets_one_group() {
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let city = scene::Generated::City.build(1);
    let groups_before = gpu_harness::bind_groups_created();
    let gpu = GpuScene::new(&ctx.device, &ctx.queue, &city);
    assert_eq!(gpu.material_groups.len(), city.materials.len());
    assert!(gpu_harness::bind_groups_created() - groups_before >= city.materials.len() as u64);
    let table = materials(&ctx, &gpu);
    assert_eq!(table, city.materials.iter().map(GpuMaterial::new).collect::<Vec<_>>());
    assert_eq!(gpu.triangle_count, city.stats().triangles);
    let drawn: u32 = gpu.draws.iter().map(|d| d.index_count).sum();
    assert_eq!(drawn as usize, 3 * city.stats().triangles);
    assert_eq!(gpu.indices.size() as usize, 4 * drawn as usize);
}

#[test]
fn an_empty_scene_binds_one_zeroed_material() {
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let gpu = GpuScene::new(&ctx.device, &ctx.queue, &scene::Scene::new("empty"));
    assert_eq!(materials(&ctx, &gpu), vec![GpuMaterial::default()]);
    assert!(gpu.draws.is_empty() && gpu.triangle_count == 0);
}

#[test]
fn gbuffer_shader_validates_and_its_camera_has_the_size_of_its_wgsl_twin() {
    gpu_harness::validate_wgsl(GBUFFER_WGSL).unwrap_or_else(|e| panic!("gbuffer: {e}"));
    let size = gpu_harness::wgsl_struct_size(GBUFFER_WGSL, "GBufferCamera");
    assert_eq!(size, Ok(std::mem::size_of::<GBufferCamera>()));
}

/// A quad in the plane `z` over `[x0, x1] x [y0, y1]`, texture u along x, with vertex
/// normals `normal`.
fn quad(
    name: &str,
    z: f32,
    (x0, x1): (f32, f32),
    (y0, y1): (f32, f32),
    normal: Vec3,
    m: u32,
) -> Mesh {
    let positions = vec![
        Vec3::new(x0, y0, z),
        Vec3::new(x1, y0, z),
        Vec3::new(x1, y1, z),
        Vec3::new(x0, y1, z),
    ];
    let uvs = vec![Vec2::new(0.0, 1.0), Vec2::new(1.0, 1.0), Vec2::new(1.0, 0.0), Vec2::ZERO];
    let data = MeshData {
        positions,
        normals: Some(vec![normal; 4]),
        uvs: Some(uvs),
        indices: vec![0, 1, 2, 0, 2, 3],
    };
    Mesh::build(name, data, MaterialId(m)).expect("a quad").0
}

/// Seen from `(0, 0, 4)` looking down -z: a blue glossy quad 6 m away (material 0), a red
/// one 4 m away on the left whose vertex normals face away from the camera (material 1), and
/// a green alpha-tested one 3 m away on the right whose mask cuts its right half (material
/// 2), in front of the blue quad.
fn three_quads() -> Scene {
    let mut scene = Scene::new("three quads");
    let mask = [1.0, 1.0, 0.0, 0.0].map(|a| Vec4::new(1.0, 1.0, 1.0, a)).to_vec();
    let mask = scene.add_texture(Texture::from_linear("mask", 4, 1, mask).expect("a mask"));
    let blue = Material::glossy("blue", Vec3::new(0.1, 0.2, 0.9), 0.5, 64.0);
    let red = Material::diffuse("red", Vec3::new(0.8, 0.1, 0.1));
    let green = Material {
        alpha_mask: Some(AlphaMask { texture: mask, cutoff: 0.5 }),
        ..Material::diffuse("leaf", Vec3::new(0.1, 0.7, 0.2))
    };
    for m in [blue, red, green] {
        scene.add_material(m);
    }
    scene.meshes.push(quad("back", -2.0, (-2.0, 2.0), (-2.0, 2.0), Vec3::Z, 0));
    scene.meshes.push(quad("left", 0.0, (-1.0, 0.0), (-1.0, 1.0), Vec3::NEG_Z, 1));
    scene.meshes.push(quad("leaf", 1.0, (0.0, 1.0), (-1.0, 1.0), Vec3::Z, 2));
    scene.camera = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, 60.0, 1.0);
    scene.validate().expect("a valid scene");
    scene
}

/// Texel `(x, y)` of G-buffer target `t` (0 albedo .. 3 depth, 4 surface) as four floats.
struct Targets {
    size: u32,
    texels: Vec<Vec<Vec4>>,
}

impl Targets {
    /// One frame of `scene` from its camera into a `size` x `size` G-buffer, read back.
    fn render(ctx: &gpu_harness::GpuContext, scene: &Scene, size: u32) -> Self {
        let cam = scene.camera;
        let gpu = GpuScene::new(&ctx.device, &ctx.queue, scene);
        let gbuffer = GBuffer::new(&ctx.device, size, size);
        let pass = GBufferPass::new(&ctx.device, &gpu).expect("the G-buffer pipelines");
        let camera = GBufferCamera::new(cam.view_projection(), cam.position, cam.forward, 1.0);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        pass.record(&ctx.queue, &mut encoder, &gbuffer, &gpu, &camera);
        ctx.queue.submit([encoder.finish()]);
        Self::read(ctx, &gbuffer)
    }

    fn read(ctx: &gpu_harness::GpuContext, g: &GBuffer) -> Self {
        let read = |t: usize, bytes| {
            let aspect = wgpu::TextureAspect::All;
            gpu_harness::read_texture(&ctx.device, &ctx.queue, &g.textures[t], 0, aspect, bytes)
                .expect("the target reads back")
        };
        let unorm: Vec<Vec4> = read(0, 4)
            .chunks(4)
            .map(|c| Vec4::from_array(std::array::from_fn(|i| c[i] as f32 / 255.0)))
            .collect();
        let half = |t| -> Vec<Vec4> {
            let h: Vec<half::f16> = gpu_harness::cast_vec(&read(t, 8));
            h.chunks(4).map(|c| Vec4::from_array(std::array::from_fn(|i| c[i].to_f32()))).collect()
        };
        let depth: Vec<f32> = gpu_harness::cast_vec(&read(3, 4));
        let depth = depth.into_iter().map(|d| Vec4::new(d, 0.0, 0.0, 0.0)).collect();
        // The `surface` target: the emissive texel's square roots and the occlusion, packed.
        let packed: Vec<u32> = gpu_harness::cast_vec(&read(5, 4));
        let surface = packed
            .into_iter()
            .map(|p| {
                let b = p.to_le_bytes().map(|c| c as f32 / 255.0);
                Vec4::new(b[0] * b[0], b[1] * b[1], b[2] * b[2], b[3])
            })
            .collect();
        Self { size: g.width, texels: vec![unorm, half(1), half(2), depth, surface] }
    }

    /// The emissive texture's value (rgb) and the occlusion (w) at the pixel of `p`.
    fn surface_at(&self, camera: &Camera, p: Vec3) -> Vec4 {
        self.texels[4][self.index(camera, p)]
    }

    fn index(&self, camera: &Camera, p: Vec3) -> usize {
        let ndc = camera.view_projection().project_point3(p);
        let px = ((ndc.x + 1.0) * 0.5 * self.size as f32) as usize;
        let py = ((1.0 - ndc.y) * 0.5 * self.size as f32) as usize;
        py * self.size as usize + px
    }

    /// The four targets at the pixel that world point `p` projects to.
    fn at(&self, camera: &Camera, p: Vec3) -> [Vec4; 4] {
        let i = self.index(camera, p);
        std::array::from_fn(|t| self.texels[t][i])
    }
}

fn near(a: Vec4, b: Vec4, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol
}

#[test]
fn gbuffer_pass_draws_depth_normals_materials_and_alpha_cut_outs() {
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let scene = three_quads();
    let cam = scene.camera;
    let gpu = GpuScene::new(&ctx.device, &ctx.queue, &scene);
    let gbuffer = GBuffer::new(&ctx.device, 32, 32);
    let pass = GBufferPass::new(&ctx.device, &gpu).expect("the G-buffer pipelines");
    let camera = GBufferCamera::new(cam.view_projection(), cam.position, cam.forward, 1.0);
    let frame = || {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let bytes = pass.record(&ctx.queue, &mut encoder, &gbuffer, &gpu, &camera);
        ctx.queue.submit([encoder.finish()]);
        assert_eq!(bytes, std::mem::size_of::<GBufferCamera>() as u64);
    };
    frame();
    let t = Targets::read(&ctx, &gbuffer);
    // Base colour + metallic; the roughness beside the normal.
    let rgb = |m: &Material| m.base_color.extend(m.metallic);
    let toward_camera = Vec4::new(0.0, 0.0, 1.0, 0.0);
    let tol = 1.0 / 255.0 + 1e-3;

    // The red quad, 4 m along the view axis; its normals face the viewer, not the vertices'.
    let [albedo, normal, geometry, depth] = t.at(&cam, Vec3::new(-0.5, 0.0, 0.0));
    assert!(near(albedo, rgb(&scene.materials[1]), tol), "red albedo {albedo}");
    let red_roughness = scene.materials[1].roughness;
    assert!(near(normal, toward_camera.with_w(red_roughness), 1e-3), "red normal {normal}");
    assert!(near(geometry, toward_camera.with_w(1.0), 1e-3), "red geometry {geometry}");
    assert!((depth.x - 4.0).abs() < 1e-4, "red depth {}", depth.x);

    // The leaf's kept half, 3 m away: material 2.
    let [albedo, _, geometry, depth] = t.at(&cam, Vec3::new(0.25, 0.0, 1.0));
    assert!(near(albedo, rgb(&scene.materials[2]), tol), "leaf albedo {albedo}");
    assert!(near(geometry, toward_camera.with_w(2.0), 1e-3), "leaf geometry {geometry}");
    assert!((depth.x - 3.0).abs() < 1e-4, "leaf depth {}", depth.x);

    // Through the leaf's cut half: the blue quad 6 m away, its roughness kept (a flat quad's
    // normal does not vary over a pixel, so specular anti-aliasing does not widen it).
    for p in [Vec3::new(0.85, 0.0, 1.0), Vec3::new(-1.8, -1.8, -2.0)] {
        let [albedo, normal, geometry, depth] = t.at(&cam, p);
        assert!(near(albedo, rgb(&scene.materials[0]), tol), "blue albedo {albedo} at {p}");
        let blue_roughness = scene.materials[0].roughness;
        let want = toward_camera.with_w(blue_roughness);
        assert!(near(normal, want, 1e-3), "blue normal {normal} at {p}");
        assert!(near(geometry, toward_camera.with_w(0.0), 1e-3), "blue geometry {geometry}");
        assert!((depth.x - 6.0).abs() < 1e-4, "blue depth {} at {p}", depth.x);
    }

    // Nothing drawn in the corners: depth 0, everything cleared.
    let corner = t.texels.iter().map(|texels| texels[0]).collect::<Vec<_>>();
    assert!(corner.iter().all(|&v| v == Vec4::ZERO), "background {corner:?}");
    let zbuffer = gpu_harness::read_texture(
        &ctx.device,
        &ctx.queue,
        &gbuffer.textures[4],
        0,
        wgpu::TextureAspect::DepthOnly,
        4,
    )
    .expect("the z-buffer reads back");
    let z: Vec<f32> = gpu_harness::cast_vec(&zbuffer);
    assert_eq!(z[0], 1.0, "the background keeps the cleared depth");
    assert!(z.iter().any(|&z| z > 0.0 && z < 1.0));

    // A second frame makes nothing: no bind group, no buffer, no texture or view.
    let (objects, groups) =
        (gpu_harness::live_objects(&ctx.device), gpu_harness::bind_groups_created());
    frame();
    assert_eq!(gpu_harness::live_objects(&ctx.device), objects);
    assert_eq!(gpu_harness::bind_groups_created(), groups);
    assert_eq!(Targets::read(&ctx, &gbuffer).texels, t.texels, "the same frame again");
}

/// The BRDF's WGSL twin (`scene::gpu::BRDF_INC_WGSL`) returns what `scene::brdf` returns, lobe
/// by lobe, and the same specular anti-aliasing roughness, on seeded random materials and directions (some below the horizon, some at
/// roughness 0).
#[test]
fn wgsl_brdf_equals_the_cpu_brdf() {
    use rand::{Rng, SeedableRng};
    use scene::gpu::BRDF_INC_WGSL;
    gpu_harness::validate_wgsl(BRDF_INC_WGSL).unwrap_or_else(|e| panic!("brdf: {e}"));
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5353);
    let dir = |rng: &mut rand_pcg::Pcg64, up: f32| {
        let z: f32 = rng.random_range(up..1.0);
        let phi: f32 = rng.random_range(0.0..std::f32::consts::TAU);
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(s * phi.cos(), s * phi.sin(), z)
    };
    let count = 1024usize;
    let mut inputs: Vec<[f32; 4]> = Vec::new();
    let mut cases = Vec::new();
    for i in 0..count {
        let c = Vec3::new(rng.random(), rng.random(), rng.random());
        let metallic: f32 = if i % 3 == 0 { 1.0 } else { rng.random() };
        let roughness: f32 = if i % 17 == 0 { 0.0 } else { rng.random() };
        let n = dir(&mut rng, -1.0);
        let (t, b) = n.any_orthonormal_pair();
        let local = |l: Vec3| t * l.x + b * l.y + n * l.z;
        let wo = local(dir(&mut rng, -0.1));
        let variance: f32 = if i % 5 == 0 { 0.0 } else { rng.random_range(0.0..0.2) };
        let wi = local(dir(&mut rng, -0.1));
        inputs.extend(
            [c.extend(metallic), n.extend(roughness), wo.extend(variance), wi.extend(0.0)]
                .map(|v| v.to_array()),
        );
        cases.push((scene::Brdf::new(c, metallic, roughness), n, wo, wi, variance));
    }
    let kernel = format!(
        "{BRDF_INC_WGSL}
        @group(0) @binding(0) var<storage, read> cases: array<vec4<f32>>;
        @group(0) @binding(1) var<storage, read_write> lobes: array<vec4<f32>>;
        @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
            let i = id.x;
            if i >= arrayLength(&cases) / 4u {{ return; }}
            let m = cases[4u * i];
            let n = cases[4u * i + 1u];
            let wo = cases[4u * i + 2u].xyz;
            let variance = cases[4u * i + 2u].w;
            let wi = cases[4u * i + 3u].xyz;
            lobes[3u * i] = vec4<f32>(brdf_eval_diffuse(m.xyz, m.w, n.xyz, wo, wi), 0.0);
            lobes[3u * i + 1u] = vec4<f32>(brdf_eval_specular(m.xyz, m.w, n.w, n.xyz, wo, wi),
                brdf_filtered_roughness(n.w, variance));
            lobes[3u * i + 2u] = vec4<f32>(brdf_eval(m.xyz, m.w, n.w, n.xyz, wo, wi),
                brdf_specular_reflectance(brdf_f0(m.xyz, m.w), dot(n.xyz, wo)).x);
        }}"
    );
    let out = ctx
        .run_compute(
            &kernel,
            "main",
            &[
                gpu_harness::Binding::Read(bytemuck::cast_slice(&inputs)),
                gpu_harness::Binding::Output((count * 3 * 16) as u64),
            ],
            [count.div_ceil(64) as u32, 1, 1],
        )
        .expect("dispatch");
    let gpu: Vec<[f32; 4]> = gpu_harness::cast_vec(&out[1]);
    let mut worst = 0.0f32;
    for (i, (b, n, wo, wi, variance)) in cases.iter().enumerate() {
        let spec_refl = scene::brdf::specular_reflectance(b.f0(), n.dot(*wo)).x;
        let cpu = [
            b.eval_diffuse(*n, *wo, *wi).extend(0.0),
            b.eval_specular(*n, *wo, *wi)
                .extend(scene::brdf::filtered_roughness(b.roughness, *variance)),
            b.eval(*n, *wo, *wi).extend(spec_refl),
        ];
        for (k, c) in cpu.iter().enumerate() {
            let g = Vec4::from_array(gpu[3 * i + k]);
            let err = (g - *c).abs().max_element() / c.abs().max_element().max(1.0);
            worst = worst.max(err);
            assert!(err < 2e-4, "case {i} lobe {k} ({b:?}): GPU {g} vs CPU {c}");
        }
    }
    eprintln!("worst relative difference GPU vs CPU: {worst:e}");
}

/// The G-buffer applies the normal map in the mesh's tangent frame (MikkTSpace, +Y of the
/// map up the image) and the metallic-roughness texture's blue and green channels: two quads
/// facing the camera, one whose map leans 45 degrees along +U (+x), one along +Y of the map
/// (up the image: +y, the quad's V runs down it) with a metallic-roughness texture. Without
/// the maps both normals would be +z and the factors unchanged.
#[test]
fn gbuffer_applies_normal_maps_and_metallic_roughness_textures() {
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let mut scene = Scene::new("mapped quads");
    let mut one = |name: &str, v: Vec4| {
        scene.add_texture(Texture::from_linear(name, 1, 1, vec![v]).expect("a 1x1 texture"))
    };
    let stored = |m: Vec3| ((m + Vec3::ONE) * 0.5).extend(1.0);
    let along_u = one("along u", stored(Vec3::new(s, 0.0, s)));
    let up = one("up", stored(Vec3::new(0.0, s, s)));
    let mr = one("mr", Vec4::new(0.0, 0.5, 0.25, 1.0));
    let base = Material::metallic_roughness("m", Vec3::splat(0.5), 0.8, 0.6);
    scene.add_material(Material { normal_texture: Some(along_u), ..base.clone() });
    scene.add_material(Material {
        normal_texture: Some(up),
        metallic_roughness_texture: Some(mr),
        ..base
    });
    scene.meshes.push(quad("left", 0.0, (-1.0, 0.0), (-1.0, 1.0), Vec3::Z, 0));
    scene.meshes.push(quad("right", 0.0, (0.0, 1.0), (-1.0, 1.0), Vec3::Z, 1));
    scene.camera = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, 60.0, 1.0);
    scene.validate().expect("a valid scene");
    let cam = scene.camera;
    let t = Targets::render(&ctx, &scene, 32);
    // Half floats and an RGBA8 metallic: 2e-3 and one step of 1/255.
    let [_, normal, _, _] = t.at(&cam, Vec3::new(-0.5, 0.0, 0.0));
    assert!(near(normal, Vec4::new(s, 0.0, s, 0.6), 2e-3), "along +U: {normal}");
    let [albedo, normal, _, _] = t.at(&cam, Vec3::new(0.5, 0.0, 0.0));
    assert!(near(normal, Vec4::new(0.0, s, s, 0.3), 2e-3), "up the image: {normal}");
    assert!((albedo.w - 0.2).abs() <= 1.0 / 255.0 + 1e-3, "metallic 0.8 x 0.25: {}", albedo.w);
}

/// The normal map's WGSL twin (`material_perturbed_normal`) equals `scene::perturbed_normal`
/// on seeded random frames, texels (some degenerate: a zero texel) and scales.
#[test]
fn wgsl_perturbed_normal_equals_the_cpu_one() {
    use rand::{Rng, SeedableRng};
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5354);
    let count = 512usize;
    let mut inputs: Vec<[f32; 4]> = Vec::new();
    let mut cases = Vec::new();
    for i in 0..count {
        let n = Vec3::new(rng.random_range(-1.0..1.0), rng.random(), rng.random_range(-1.0..1.0))
            .normalize_or(Vec3::Y);
        let t = n.any_orthonormal_vector().extend(if i % 2 == 0 { 1.0 } else { -1.0 });
        let texel = if i % 31 == 0 {
            Vec3::splat(0.5)
        } else {
            Vec3::new(rng.random(), rng.random(), rng.random_range(0.5..1.0))
        };
        let scale: f32 = rng.random_range(0.0..2.0);
        inputs.extend([n.extend(scale), t, texel.extend(0.0)].map(|v| v.to_array()));
        cases.push(scene::perturbed_normal(n, t, texel, scale));
    }
    let kernel = format!(
        "{MATERIAL_INC_WGSL}
        @group(0) @binding(0) var<storage, read> cases: array<vec4<f32>>;
        @group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;
        @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
            let i = id.x;
            if i >= arrayLength(&cases) / 3u {{ return; }}
            let n = cases[3u * i];
            out[i] = vec4<f32>(material_perturbed_normal(n.xyz, cases[3u * i + 1u],
                cases[3u * i + 2u].xyz, n.w), 0.0);
        }}"
    );
    let out = ctx
        .run_compute(
            &kernel,
            "main",
            &[
                gpu_harness::Binding::Read(bytemuck::cast_slice(&inputs)),
                gpu_harness::Binding::Output((count * 16) as u64),
            ],
            [count.div_ceil(64) as u32, 1, 1],
        )
        .expect("dispatch");
    let gpu: Vec<[f32; 4]> = gpu_harness::cast_vec(&out[1]);
    for (i, cpu) in cases.iter().enumerate() {
        let g = Vec4::from_array(gpu[i]).truncate();
        assert!((g - *cpu).length() < 1e-5, "case {i}: GPU {g} vs CPU {cpu}");
    }
}

/// The filtered diffuse cosine's WGSL twins (`brdf_filtered_cosine`, `brdf_normal_coherence`,
/// `brdf_diffuse_cos_filtered`) equal `scene::brdf`'s on seeded random cosines, coherences
/// (some 1, some tiny), texels and directions (some below the horizon).
#[test]
fn wgsl_filtered_diffuse_equals_the_cpu_one() {
    use rand::{Rng, SeedableRng};
    use scene::brdf::{filtered_cosine, normal_coherence};
    use scene::gpu::BRDF_INC_WGSL;
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5355);
    let count = 512usize;
    let mut inputs: Vec<[f32; 4]> = Vec::new();
    let mut cases = Vec::new();
    for i in 0..count {
        let c: f32 = rng.random_range(-1.0..1.0);
        let r: f32 = match i % 7 {
            0 => 1.0,
            1 => 0.01,
            _ => rng.random(),
        };
        let texel = Vec3::new(rng.random(), rng.random(), rng.random());
        let b = scene::Brdf::new(
            Vec3::new(rng.random(), rng.random(), rng.random()),
            rng.random(),
            0.5,
        );
        let n = Vec3::Z;
        let wo = Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-0.2..1.0),
        )
        .normalize_or(Vec3::Z);
        let wi = Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-0.5..1.0),
        )
        .normalize_or(Vec3::Z);
        inputs.extend(
            [
                Vec4::new(c, r, 0.0, 0.0),
                texel.extend(0.0),
                b.base_color.extend(b.metallic),
                wo.extend(0.0),
                wi.extend(0.0),
            ]
            .map(|v| v.to_array()),
        );
        let lobe = b.eval_diffuse_cos_filtered(n, wo, wi, r);
        cases.push((filtered_cosine(c, r), normal_coherence(texel), lobe));
    }
    let kernel = format!(
        "{BRDF_INC_WGSL}
        @group(0) @binding(0) var<storage, read> cases: array<vec4<f32>>;
        @group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;
        @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
            let i = id.x;
            if i >= arrayLength(&cases) / 5u {{ return; }}
            let a = cases[5u * i];
            let m = cases[5u * i + 2u];
            out[2u * i] = vec4<f32>(brdf_filtered_cosine(a.x, a.y),
                brdf_normal_coherence(cases[5u * i + 1u].xyz), 0.0, 0.0);
            out[2u * i + 1u] = vec4<f32>(brdf_diffuse_cos_filtered(m.xyz, m.w, vec3<f32>(0.0, 0.0, 1.0),
                cases[5u * i + 3u].xyz, cases[5u * i + 4u].xyz, a.y), 0.0);
        }}"
    );
    let out = ctx
        .run_compute(
            &kernel,
            "main",
            &[
                gpu_harness::Binding::Read(bytemuck::cast_slice(&inputs)),
                gpu_harness::Binding::Output((count * 32) as u64),
            ],
            [count.div_ceil(64) as u32, 1, 1],
        )
        .expect("dispatch");
    let gpu: Vec<[f32; 4]> = gpu_harness::cast_vec(&out[1]);
    for (i, (cos, coherence, lobe)) in cases.iter().enumerate() {
        let (a, l) = (gpu[2 * i], Vec4::from_array(gpu[2 * i + 1]).truncate());
        assert!((a[0] - cos).abs() < 1e-5, "case {i}: cosine GPU {} vs CPU {cos}", a[0]);
        assert!(
            (a[1] - coherence).abs() < 1e-5,
            "case {i}: coherence GPU {} vs CPU {coherence}",
            a[1]
        );
        assert!(
            (l - *lobe).length() < 1e-5 * (1.0 + lobe.length()),
            "case {i}: lobe GPU {l} vs CPU {lobe}"
        );
    }
}

/// The G-buffer reads a texture with its own wrap modes and magnification filter, as the CPU
/// reads it (`Texture::sample_bilinear`): a 4 x 2 texture of distinct colours, mirrored along
/// u, clamped along v and magnified with the nearest texel, on a quad whose coordinates run
/// from -1 to 2; checked at texel centres of every copy. With the default sampler (repeat,
/// linear) the mirrored copies would read the texels in the wrong order.
#[test]
fn gbuffer_reads_textures_with_their_wrap_modes_and_filter() {
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let colours: Vec<Vec4> =
        (0..8).map(|i| Vec4::new((i % 4) as f32 / 3.0, (i / 4) as f32, 0.5, 1.0)).collect();
    let mut tex = Texture::from_linear("tiles", 4, 2, colours).expect("a 4x2 texture");
    tex.wrap = [scene::Wrap::Mirror, scene::Wrap::Clamp];
    tex.magnify = scene::Filter::Nearest;
    let mut scene = Scene::new("wrapped quad");
    let id = scene.add_texture(tex.clone());
    scene.add_material(Material {
        albedo_texture: Some(id),
        ..Material::diffuse("tiles", Vec3::ONE)
    });
    // World [-1, 1]^2 at z = 0; u = 1.5 x + 0.5 runs -1..2 left to right, v likewise top down.
    let positions = vec![
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(-1.0, 1.0, 0.0),
    ];
    let uv_of = |p: Vec3| Vec2::new(1.5 * p.x + 0.5, 0.5 - 1.5 * p.y);
    let uvs = positions.iter().map(|&p| uv_of(p)).collect();
    let data = MeshData {
        positions,
        normals: Some(vec![Vec3::Z; 4]),
        uvs: Some(uvs),
        indices: vec![0, 1, 2, 0, 2, 3],
    };
    scene.meshes.push(Mesh::build("quad", data, MaterialId(0)).expect("a quad").0);
    scene.camera = Camera::look_at(Vec3::new(0.0, 0.0, 2.5), Vec3::ZERO, 60.0, 1.0);
    scene.validate().expect("a valid scene");
    let cam = scene.camera;
    let t = Targets::render(&ctx, &scene, 64);
    // Texel centres in u of the copies before, at and after [0, 1] (u in -1..2), and in v
    // inside and below the clamped range.
    for u in [-0.875, -0.375, 0.125, 0.625, 1.125, 1.625] {
        for v in [0.25, 0.75, 1.5] {
            let p = Vec3::new((u - 0.5) / 1.5, (0.5 - v) / 1.5, 0.0);
            let [base, ..] = t.at(&cam, p);
            let want = tex.sample_bilinear(Vec2::new(u, v), 0);
            let tol = 1.0 / 255.0 + 2e-3;
            assert!(
                near(base.with_w(0.0), want.with_w(0.0), tol),
                "uv ({u}, {v}): GPU {base} vs CPU {want}"
            );
        }
    }
}

/// `tests/data/surface_attributes.gltf` in the G-buffer, seen from above the front: the red
/// vertices make the white quad's base colour red, the occlusion texture's right half holds
/// 0.5 in the `surface` target (its left half 1), the emissive texture's left half 0 and its
/// right half the decoded texel (the lighting multiplies the material's emission). Without
/// the features: a white base colour, an occlusion of 1, a uniform (white) emissive value.
#[test]
fn gbuffer_applies_vertex_colours_occlusion_and_emissive_textures() {
    use common::surface_attributes::{self as file, COLOURED, GLOWING, OCCLUDED};
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let mut scene = scene::load_gltf(file::PATH).expect("load surface_attributes.gltf");
    scene.camera = Camera::look_at(Vec3::new(0.0, 5.0, 3.0), Vec3::ZERO, 60.0, 1.0);
    let cam = scene.camera;
    let t = Targets::render(&ctx, &scene, 128);
    let tol = 1.5 / 255.0;
    let mid = |r: (f32, f32)| (r.0 + r.1) * 0.5;
    let [base, ..] = t.at(&cam, Vec3::new(mid(COLOURED), 0.0, 0.0));
    assert!(near(base.with_w(0.0), Vec4::X, tol), "COLOR_0 red times white: {base}");
    let untouched = t.surface_at(&cam, Vec3::new(mid(COLOURED), 0.0, 0.0));
    assert!(near(untouched, Vec4::ONE, tol), "no textures: white, occlusion 1: {untouched}");
    let (left, right) =
        (Vec3::new(OCCLUDED.0 + 0.5, 0.0, 0.0), Vec3::new(OCCLUDED.1 - 0.5, 0.0, 0.0));
    let (l, r) = (t.surface_at(&cam, left), t.surface_at(&cam, right));
    assert!((l.w - 1.0).abs() <= tol, "ao 1 keeps the ambient light: {l}");
    assert!((r.w - file::RIGHT_OCCLUSION).abs() <= tol, "ao 0 at strength 0.5: {r}");
    let [lb, ..] = t.at(&cam, left);
    let [rb, ..] = t.at(&cam, right);
    assert!(near(lb, rb, tol) && (lb.x - 0.8).abs() <= tol, "occlusion leaves the base: {lb} {rb}");
    let (left, right) =
        (Vec3::new(GLOWING.0 + 0.5, 0.0, 0.0), Vec3::new(GLOWING.1 - 0.5, 0.0, 0.0));
    let (l, r) = (t.surface_at(&cam, left), t.surface_at(&cam, right));
    assert!(l.truncate().max_element() <= tol, "the black texel: {l}");
    let want = file::right_emission() / 2.0; // the texel, without the factor x strength 2
    assert!((r.truncate() - want).abs().max_element() < 4e-3, "{r} against {want}");
}

/// `material_surface_factors` (WGSL) equals `scene::surface_factors` on seeded random
/// factors, vertex colours and texels.
#[test]
fn wgsl_surface_factors_equal_the_cpu_ones() {
    use rand::{Rng, SeedableRng};
    let (_serial, Some(ctx)) = serial_gpu() else { return };
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5355);
    let count = 256usize;
    let mut v4 =
        |lo: f32, hi: f32| Vec4::from_array(std::array::from_fn(|_| rng.random_range(lo..hi)));
    let mut inputs: Vec<[f32; 4]> = Vec::new();
    let mut cases = Vec::new();
    for _ in 0..count {
        let (base, params, emission, color) =
            (v4(0.0, 1.0), v4(0.0, 1.0), v4(0.0, 8.0), v4(0.0, 1.0));
        // Texels a little outside [0, 1] too: both clamp.
        let texels = [v4(-0.1, 1.1), v4(-0.1, 1.1), v4(-0.1, 1.1), v4(-0.1, 1.1)];
        inputs.extend([base, params, emission, color].map(|v| v.to_array()));
        inputs.extend(texels.map(|v| v.to_array()));
        let [b, mr, ao, e] = texels;
        cases.push(scene::surface_factors(
            base,
            params.x,
            params.y,
            emission.truncate(),
            color.truncate(),
            b,
            mr,
            ao,
            e,
        ));
    }
    let kernel = format!(
        "{MATERIAL_INC_WGSL}
        @group(0) @binding(0) var<storage, read> cases: array<vec4<f32>>;
        @group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;
        @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
            let i = id.x;
            if i >= arrayLength(&cases) / 8u {{ return; }}
            let c = 8u * i;
            let p = cases[c + 1u];
            let f = material_surface_factors(cases[c], p.x, p.y, cases[c + 2u].xyz,
                cases[c + 3u].xyz, cases[c + 4u], cases[c + 5u], cases[c + 6u], cases[c + 7u]);
            out[3u * i] = vec4<f32>(f.base_color, f.metallic);
            out[3u * i + 1u] = vec4<f32>(f.roughness, f.occlusion, 0.0, 0.0);
            out[3u * i + 2u] = vec4<f32>(f.emission, 0.0);
        }}"
    );
    let out = ctx
        .run_compute(
            &kernel,
            "main",
            &[
                gpu_harness::Binding::Read(bytemuck::cast_slice(&inputs)),
                gpu_harness::Binding::Output((count * 48) as u64),
            ],
            [count.div_ceil(64) as u32, 1, 1],
        )
        .expect("dispatch");
    let gpu: Vec<[f32; 4]> = gpu_harness::cast_vec(&out[1]);
    for (i, cpu) in cases.iter().enumerate() {
        let [a, b, e] = [0, 1, 2].map(|k| Vec4::from_array(gpu[3 * i + k]));
        let want_a = cpu.base_color.extend(cpu.metallic);
        let want_b = Vec4::new(cpu.roughness, cpu.occlusion, 0.0, 0.0);
        let ok = near(a, want_a, 1e-5)
            && near(b, want_b, 1e-5)
            && near(e.with_w(0.0), cpu.emission.extend(0.0), 1e-4);
        assert!(ok, "case {i}: GPU {a} {b} {e} vs CPU {cpu:?}");
    }
}
