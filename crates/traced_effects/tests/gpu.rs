//! The GPU passes (`traced_effects::gpu`, feature `gpu`; lavapipe in CI) against their CPU
//! twins on small synthetic G-buffers: the ray casting buffer, its list and the batch read
//! back; the scatter of the uploaded radiance and the combination's gather, drawn over the
//! mirror draws alone; the snippets a renderer includes; a steady second frame creating no
//! bind group; and every shader validated by naga, its structs the size of Rust's.
//!
//! The tests take one lock: the bind-group count is the whole process's.
#![cfg(feature = "gpu")]

use glam::{Mat4, UVec2, Vec3, Vec4};
use gpu_harness::{Binding, GpuContext, cast_vec, gpu_test_context, read_buffer};
use scene::gpu::{GpuMaterial, GpuScene};
use std::sync::{Mutex, MutexGuard};
use traced_effects::combine::traced_radiance;
use traced_effects::gpu::{
    COMBINE_WGSL, Combine, CombineInputs, FRESNEL_INC_WGSL, GBufferViews, RAYCAST_WGSL, RayCasting,
    SCATTER_WGSL, SCREEN_INC_WGSL, TRACED_ADD, TRACED_REFLECTIONS, TRACED_REFRACTIONS, TracedView,
};
use traced_effects::ray_casting::{ListedRay, RayCast, RayKinds, batch, cast_rays};
use traced_effects::screen::{ScreenGBuffer, ScreenView};
use traced_effects::trace::fresnel_schlick;

static LOCK: Mutex<()> = Mutex::new(());

fn lock() -> MutexGuard<'static, ()> {
    LOCK.lock().unwrap_or_else(|e| e.into_inner())
}

/// Diffuse, mirror, glass, a mixed part, and glass of index below 1 (total internal
/// reflection at grazing angles).
fn materials() -> Vec<scene::Material> {
    use scene::Material;
    vec![
        Material::diffuse("diffuse", Vec3::splat(0.5)),
        Material::mirror("mirror", 0.8),
        Material::glass("glass", 0.9, 1.5),
        Material { transparency: 0.4, ior: 1.33, ..Material::mirror("half mirror", 0.5) },
        Material { transparency: 1.0, ior: 0.75, ..Material::default() },
    ]
}

/// A small seeded generator (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// A synthetic G-buffer: each pixel background, diffuse, mirror, glass, mixed or
/// under-1-index glass, with a normal mostly towards the camera (a few away from it), so
/// that some blocks have no candidate and some several.
struct Synthetic {
    view: ScreenView,
    normal: Vec<Vec3>,
    material: Vec<u32>,
    depth: Vec<f32>,
}

impl Synthetic {
    fn new((w, h): (u32, u32), seed: u64) -> Self {
        let camera = scene::Camera::look_at(
            Vec3::new(0.0, 1.0, 5.0),
            Vec3::new(0.2, 0.9, 0.0),
            60.0,
            w as f32 / h as f32,
        );
        let view =
            ScreenView::new(camera.view_projection(), camera.position, camera.forward, (w, h));
        let mut rng = Rng(seed);
        let n = (w * h) as usize;
        let (mut normal, mut material, mut depth) = (vec![], vec![], vec![]);
        for _ in 0..n {
            // Background a fifth of the time, diffuse a third, else one of the four others.
            let r = rng.next();
            let kind = if r < 0.2 {
                5
            } else if r < 0.53 {
                0
            } else {
                1 + ((r - 0.53) * 8.5) as u32
            };
            let d = 2.0 + 6.0 * rng.next();
            let facing = if rng.next() < 0.1 { -1.0 } else { 1.0 };
            let tilt = Vec3::new(rng.next() - 0.5, rng.next() - 0.5, 0.0) * 1.5;
            normal.push((Vec3::Z * facing + tilt) * (0.5 + rng.next()));
            material.push(kind.min(4));
            depth.push(if kind == 5 { 0.0 } else { d });
        }
        // The first block has every kind of candidate: diffuse first, then a mirror (the one
        // chosen), glass and the mixed part.
        for (k, m) in [0, 1, 2, 3].into_iter().enumerate().filter(|_| w > 1 && h > 1) {
            let i = ((k as u32 >> 1) * w + (k as u32 & 1)) as usize;
            (material[i], depth[i]) = (m, 3.0 + k as f32);
        }
        Self { view, normal, material, depth }
    }

    fn cpu(&self) -> ScreenGBuffer<'_> {
        ScreenGBuffer { normal: &self.normal, material: &self.material, depth: &self.depth }
    }
}

/// A texture of `format` (`bytes` per texel) holding `data`.
fn texture(
    ctx: &GpuContext,
    (w, h): (u32, u32),
    format: wgpu::TextureFormat,
    bytes: u32,
    data: &[u8],
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    let usage = usage | wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::TEXTURE_BINDING;
    let t = gpu_harness::texture_2d(&ctx.device, "test texture", (w, h), format, usage);
    let layout = wgpu::TexelCopyBufferLayout {
        offset: 0,
        bytes_per_row: Some(w * bytes),
        rows_per_image: Some(h),
    };
    let size = wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 };
    ctx.queue.write_texture(t.as_image_copy(), data, layout, size);
    t
}

/// The G-buffer's textures on the GPU (32-bit floats) and the material table.
struct Uploaded {
    views: [wgpu::TextureView; 3],
    materials: wgpu::Buffer,
}

impl Uploaded {
    fn new(ctx: &GpuContext, g: &Synthetic, materials: &[scene::Material]) -> Self {
        let size = (g.view.width, g.view.height);
        let rgba = wgpu::TextureFormat::Rgba32Float;
        let usage = wgpu::TextureUsages::empty();
        let normal: Vec<Vec4> = g.normal.iter().map(|n| n.extend(0.0)).collect();
        let geometry: Vec<Vec4> =
            g.material.iter().map(|&m| Vec4::new(0.0, 0.0, 1.0, m as f32)).collect();
        let view = |t: wgpu::Texture| t.create_view(&Default::default());
        let table: Vec<GpuMaterial> = materials.iter().map(GpuMaterial::new).collect();
        Self {
            views: [
                view(texture(ctx, size, rgba, 16, bytemuck::cast_slice(&normal), usage)),
                view(texture(ctx, size, rgba, 16, bytemuck::cast_slice(&geometry), usage)),
                view(texture(
                    ctx,
                    size,
                    wgpu::TextureFormat::R32Float,
                    4,
                    bytemuck::cast_slice(&g.depth),
                    usage,
                )),
            ],
            materials: gpu_harness::storage_buffer(
                &ctx.device,
                "materials",
                bytemuck::cast_slice(&table),
            ),
        }
    }

    fn gbuffer(&self) -> GBufferViews<'_> {
        let [normal, geometry, depth] = &self.views;
        GBufferViews { normal, geometry, depth }
    }
}

fn close(a: f32, b: f32, tol: f32) -> bool {
    (a - b).abs() <= tol * (1.0 + b.abs())
}

fn close4(a: [f32; 4], b: [f32; 4], xyz: bool, w: bool) -> bool {
    (!xyz || (0..3).all(|i| close(a[i], b[i], 1e-4))) && (!w || close(a[3], b[3], 1e-5))
}

/// The GPU's ray casting buffer equals the CPU's: the chosen pixel of each block, its origin
/// and depth, both directions where they have weight, and the weights (zero for a kind
/// switched off and under total internal reflection); the listed texels read back give the
/// CPU's batch.
#[test]
fn ray_casting_buffer_matches_its_cpu_twin() {
    let _lock = lock();
    let Some(ctx) = gpu_test_context() else { return };
    let materials = materials();
    let kinds = [
        RayKinds::ALL,
        RayKinds { reflections: true, refractions: false },
        RayKinds { reflections: false, refractions: true },
    ];
    let (mut with_ray, mut without, mut reflected_inside) = (0, 0, 0);
    for (size, seed) in [((7, 5), 1), ((9, 3), 2), ((1, 1), 3), ((16, 12), 4)] {
        let g = Synthetic::new(size, seed);
        let up = Uploaded::new(&ctx, &g, &materials);
        let pass = RayCasting::new(&ctx.device, size).expect("the pass");
        for kinds in kinds {
            let cpu = cast_rays(&g.view, &g.cpu(), &materials, kinds).expect("fits");
            let view = TracedView::new(&g.view, kinds, true);
            let listed = pass
                .run(&ctx.device, &ctx.queue, &view, &up.gbuffer(), &up.materials)
                .expect("runs");
            let bytes = pass.buffer().size();
            let gpu: Vec<RayCast> =
                cast_vec(&read_buffer(&ctx.device, &ctx.queue, pass.buffer(), bytes).unwrap());
            assert_eq!(gpu.len(), cpu.len(), "{size:?}");
            with_ray += cpu.iter().filter(|t| t.has_ray()).count();
            without += cpu.iter().filter(|t| !t.has_ray()).count();
            for (i, (a, b)) in gpu.iter().zip(&cpu).enumerate() {
                let at = format!("{size:?} {kinds:?} texel {i}: {a:?} against {b:?}");
                assert!(close4(a.origin, b.origin, true, true), "{at}");
                assert!(close4(a.reflect, b.reflect, b.reflect[3] > 0.0, true), "{at}");
                assert!(close4(a.refract, b.refract, b.refract[3] > 0.0, true), "{at}");
            }
            let all: Vec<ListedRay> = (0..cpu.len())
                .filter(|&i| cpu[i].has_ray())
                .map(|i| ListedRay { ray: cpu[i], texel: [i as u32, 0, 0, 0] })
                .collect();
            let expected = batch(cpu.len(), &all);
            assert_eq!(listed.batch.slots, expected.slots, "{size:?} {kinds:?}");
            for (a, b) in listed.batch.rays.iter().zip(&expected.rays) {
                assert!((a.origin - b.origin).length() < 1e-3 && (a.dir - b.dir).length() < 1e-3);
            }
            assert_eq!(listed.transferred.reads, 1);
        }
        // The first block chose its mirror (the second pixel), over diffuse, glass and mixed.
        let cpu = cast_rays(&g.view, &g.cpu(), &materials, RayKinds::ALL).unwrap();
        // The mirror's weight is its Schlick reflectance, F0 0.8 (within 0.01 of it at the
        // near-normal views here); glass under total internal reflection reflects 0.9 and more.
        let is_mirror = |t: &RayCast| (t.reflect[3] - 0.8).abs() < 0.01;
        // Glass without a refraction ray and not the mirror: total internal reflection.
        reflected_inside +=
            cpu.iter().filter(|t| t.has_ray() && t.refract[3] == 0.0 && !is_mirror(t)).count();
        if size.0 > 1 && size.1 > 1 {
            assert_eq!(cpu[0].origin[3], 4.0);
            assert!(is_mirror(&cpu[0]) && cpu[0].refract[3] == 0.0, "{:?}", cpu[0]);
        }
    }
    assert!(with_ray > 20 && without > 5, "{with_ray} texels with a ray, {without} without");
    assert!(reflected_inside > 0, "no texel under total internal reflection");
}

/// A mirror quad in z = 0 (x up to 0.5) with a diffuse one in front of its left part, with
/// the table of [`materials`] (which the synthetic G-buffers index): the scene the
/// combination draws over.
fn quads() -> scene::Scene {
    let mut s = scene::Scene::new("quads");
    s.materials = materials();
    let (diffuse, mirror) = (scene::MaterialId(0), scene::MaterialId(1));
    let quad = |x0: f32, x1: f32, z: f32, m| {
        let data = scene::MeshData {
            positions: vec![
                Vec3::new(x0, -20.0, z),
                Vec3::new(x1, -20.0, z),
                Vec3::new(x1, 20.0, z),
                Vec3::new(x0, 20.0, z),
            ],
            normals: Some(vec![Vec3::Z; 4]),
            uvs: None,
            indices: vec![0, 1, 2, 0, 2, 3],
        };
        scene::Mesh::build("quad", data, m).expect("a quad").0
    };
    s.meshes = vec![quad(-20.0, 0.5, 0.0, mirror), quad(-20.0, -1.5, 0.5, diffuse)];
    s
}

/// The z-buffer of `scene`'s draws (the reflective ones alone when `reflective`), drawn with
/// the combination's own vertex shader, and read back.
fn zbuffer(
    ctx: &GpuContext,
    gpu: &GpuScene,
    view: &TracedView,
    reflective: bool,
) -> (wgpu::Texture, Vec<f32>) {
    let device = &ctx.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("depth"),
        source: wgpu::ShaderSource::Wgsl(COMBINE_WGSL.into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("depth"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_reflective"),
            compilation_options: Default::default(),
            buffers: &[Some(GpuScene::vertex_layout(true))],
        },
        primitive: Default::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: None,
        multiview_mask: None,
        cache: None,
    });
    let uniform = gpu_harness::uniform_buffer(device, "view", bytemuck::bytes_of(view));
    let layout = pipeline.get_bind_group_layout(0);
    let group = gpu_harness::bind_group(device, "depth", &layout, &[uniform.as_entire_binding()]);
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let size = (view.size[0], view.size[1]);
    let z = gpu_harness::texture_2d(device, "z", size, wgpu::TextureFormat::Depth32Float, usage);
    let zview = z.create_view(&Default::default());
    let mut enc = device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("depth"),
            color_attachments: &[],
            depth_stencil_attachment: Some(gpu_harness::depth_attachment(
                &zview,
                wgpu::LoadOp::Clear(1.0),
            )),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.set_vertex_buffer(0, gpu.vertices.slice(..));
        pass.set_index_buffer(gpu.indices.slice(..), wgpu::IndexFormat::Uint32);
        for d in gpu.draws.iter().filter(|d| !reflective || gpu.reflective(d)) {
            pass.draw_indexed(d.first_index..d.first_index + d.index_count, 0, 0..1);
        }
    }
    ctx.queue.submit([enc.finish()]);
    let depth = wgpu::TextureAspect::DepthOnly;
    let bytes = gpu_harness::read_texture(device, &ctx.queue, &z, 0, depth, 4).unwrap();
    (z, cast_vec(&bytes))
}

/// One frame of both passes over the `quads` scene and a synthetic G-buffer.
struct Frame {
    g: Synthetic,
    up: Uploaded,
    gpu: GpuScene,
    lit: (wgpu::Texture, wgpu::TextureView),
    lit_data: Vec<Vec4>,
    output: (wgpu::Texture, wgpu::TextureView),
    zbuffer: wgpu::TextureView,
    /// Per pixel, whether the mirror draw is its visible surface.
    mirror: Vec<bool>,
    raycast: RayCasting,
    combine: Combine,
}

impl Frame {
    fn new(ctx: &GpuContext, size: (u32, u32), materials: &[scene::Material]) -> Self {
        let g = Synthetic::new(size, 7);
        let scene = quads();
        let gpu = GpuScene::new(&ctx.device, &ctx.queue, &scene);
        let view = TracedView::new(&g.view, RayKinds::ALL, true);
        let (z, all) = zbuffer(ctx, &gpu, &view, false);
        let (_, mirror_only) = zbuffer(ctx, &gpu, &view, true);
        let mirror = all.iter().zip(&mirror_only).map(|(&a, &m)| m < 1.0 && m == a).collect();
        let mut rng = Rng(11);
        let lit_data: Vec<Vec4> = (0..size.0 * size.1)
            .map(|_| Vec4::new(rng.next(), rng.next(), rng.next(), 0.5))
            .collect();
        let rgba = wgpu::TextureFormat::Rgba32Float;
        let lit = texture(
            ctx,
            size,
            rgba,
            16,
            bytemuck::cast_slice(&lit_data),
            wgpu::TextureUsages::COPY_SRC,
        );
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let zeros = vec![0u8; (size.0 * size.1 * 16) as usize];
        let output = texture(ctx, size, rgba, 16, &zeros, usage);
        let with_view = |t: wgpu::Texture| {
            let v = t.create_view(&Default::default());
            (t, v)
        };
        Self {
            up: Uploaded::new(ctx, &g, materials),
            raycast: RayCasting::new(&ctx.device, size).unwrap(),
            combine: Combine::new(&ctx.device, size, rgba).unwrap(),
            g,
            gpu,
            lit: with_view(lit),
            lit_data,
            output: with_view(output),
            zbuffer: z.create_view(&Default::default()),
            mirror,
        }
    }

    /// Casts the rays, uploads `radiance(i)` for ray `i`, records the combination for `view`
    /// and returns the batch's traced radiance per texel and the output image.
    fn run(
        &self,
        ctx: &GpuContext,
        view: &TracedView,
        radiance: impl Fn(usize) -> Vec3,
    ) -> (Vec<[Vec3; 2]>, Vec<Vec4>) {
        let (device, queue) = (&ctx.device, &ctx.queue);
        let listed = self.raycast.run(device, queue, view, &self.up.gbuffer(), &self.up.materials);
        let b = listed.expect("ray casting").batch;
        let traced: Vec<Vec3> = (0..b.rays.len()).map(radiance).collect();
        let mut per_texel = vec![[Vec3::ZERO; 2]; b.texels];
        for (&(texel, refract), r) in b.slots.iter().zip(&traced) {
            per_texel[texel as usize][usize::from(refract)] = *r;
        }
        let mut enc = device.create_command_encoder(&Default::default());
        let up = self.combine.upload(queue, &mut enc, &b, &traced);
        assert_eq!(up.uploaded, 16 * traced.len() as u64 + 16 * u64::from(!traced.is_empty()));
        let inputs = CombineInputs {
            gbuffer: self.up.gbuffer(),
            lit: (&self.lit.0, &self.lit.1),
            output: (&self.output.0, &self.output.1),
            zbuffer: &self.zbuffer,
            scene: &self.gpu,
            rays: &self.raycast,
        };
        self.combine.record(device, queue, &mut enc, view, &inputs).expect("combination");
        queue.submit([enc.finish()]);
        let all = wgpu::TextureAspect::All;
        let bytes = gpu_harness::read_texture(device, queue, &self.output.0, 0, all, 16).unwrap();
        (per_texel, cast_vec(&bytes))
    }
}

/// The combination adds, where the mirror draw is the visible surface, what the CPU twin
/// gathers from the uploaded radiance (placed per texel by the scatter) with the pixel's
/// Fresnel weights; everywhere else, and with `TRACED_ADD` off everywhere, the output is the
/// lit view.
#[test]
fn combination_gathers_as_its_cpu_twin_over_the_mirror_draws() {
    let _lock = lock();
    let Some(ctx) = gpu_test_context() else { return };
    let materials = materials();
    let size = (11, 9);
    let f = Frame::new(&ctx, size, &materials);
    assert!(f.mirror.iter().any(|&m| m) && f.mirror.iter().any(|&m| !m), "both kinds of pixel");
    let radiance = |i: usize| Vec3::new(1.0 + i as f32 * 0.1, 2.0, 0.5 + (i % 3) as f32);
    let view = TracedView::new(&f.g.view, RayKinds::ALL, true);
    let (traced, out) = f.run(&ctx, &view, radiance);
    let cpu_rays = cast_rays(&f.g.view, &f.g.cpu(), &materials, RayKinds::ALL).unwrap();
    let mut gathered = 0;
    for y in 0..size.1 {
        for x in 0..size.0 {
            let i = (y * size.0 + x) as usize;
            let lit = f.lit_data[i];
            let px = UVec2::new(x, y);
            let added = traced_radiance(&f.g.view, &f.g.cpu(), &materials, &cpu_rays, &traced, px);
            let added = added.expect("inside");
            let expected = if f.mirror[i] { lit.truncate() + added } else { lit.truncate() };
            gathered += usize::from(f.mirror[i] && added != Vec3::ZERO);
            let got = out[i].truncate();
            let ok = (0..3).all(|c| close(got[c], expected[c], 1e-4));
            assert!(ok, "pixel {px}: {got} against {expected} (lit {lit}, mirror {})", f.mirror[i]);
        }
    }
    assert!(gathered > 5, "{gathered} pixels gathered traced radiance");
    let off = TracedView::new(&f.g.view, RayKinds::ALL, false);
    assert_eq!(off.flags(), TRACED_REFLECTIONS | TRACED_REFRACTIONS);
    let (_, out) = f.run(&ctx, &off, radiance);
    assert_eq!(out, f.lit_data, "without TRACED_ADD the output is the lit view");
}

/// A second frame of both passes with the camera moved creates no bind group.
#[test]
fn a_steady_frame_creates_no_bind_group() {
    let _lock = lock();
    let Some(ctx) = gpu_test_context() else { return };
    let materials = materials();
    let f = Frame::new(&ctx, (8, 6), &materials);
    let view = TracedView::new(&f.g.view, RayKinds::ALL, true);
    f.run(&ctx, &view, |_| Vec3::ONE);
    let before = gpu_harness::bind_groups_created();
    let moved = ScreenView::new(
        Mat4::from_translation(Vec3::X * 0.01) * f.g.view.view_proj,
        f.g.view.eye,
        f.g.view.forward,
        (8, 6),
    );
    f.run(&ctx, &TracedView::new(&moved, RayKinds::ALL, true), |_| Vec3::splat(2.0));
    assert_eq!(gpu_harness::bind_groups_created() - before, 0);
}

/// A view or target of another size than the pass's is an error, not a GPU fault.
#[test]
fn inputs_of_another_size_are_a_typed_error() {
    let _lock = lock();
    let Some(ctx) = gpu_test_context() else { return };
    let g = Synthetic::new((6, 4), 5);
    let up = Uploaded::new(&ctx, &g, &materials());
    let pass = RayCasting::new(&ctx.device, (8, 4)).unwrap();
    let view = TracedView::new(&g.view, RayKinds::ALL, true);
    let e = pass.run(&ctx.device, &ctx.queue, &view, &up.gbuffer(), &up.materials);
    assert!(matches!(e, Err(traced_effects::TraceError::Mismatch(_))));
}

/// The snippets a renderer includes compute what their CPU twins do.
#[test]
fn fresnel_and_position_snippets_match_their_cpu_twins() {
    let _lock = lock();
    let Some(ctx) = gpu_test_context() else { return };
    let kernel = format!(
        "{FRESNEL_INC_WGSL}\n{SCREEN_INC_WGSL}\n
        struct View {{ inv: mat4x4<f32>, eye: vec4<f32>, fwd: vec4<f32>, size: vec4<f32> }}
        @group(0) @binding(0) var<uniform> v: View;
        @group(0) @binding(1) var<storage, read> queries: array<vec4<f32>>;
        @group(0) @binding(2) var<storage, read_write> out: array<vec4<f32>>;
        @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
            if id.x >= arrayLength(&out) {{ return; }}
            let q = queries[id.x];
            let p = pixel_world_position(v.inv, v.eye.xyz, v.fwd.xyz, v.size.xy, q.xy, q.z);
            out[id.x] = vec4<f32>(p, fresnel_schlick(q.w, 1.0 + q.z * 0.1));
        }}"
    );
    gpu_harness::validate_wgsl(&kernel).expect("validates");
    let g = Synthetic::new((13, 7), 9);
    let v = g.view;
    let mut uniform: Vec<f32> = v.inv_view_proj.to_cols_array().to_vec();
    uniform.extend(v.eye.extend(0.0).to_array());
    uniform.extend(v.forward.extend(0.0).to_array());
    uniform.extend([v.width as f32, v.height as f32, 0.0, 0.0]);
    let mut rng = Rng(3);
    let queries: Vec<Vec4> = (0..100)
        .map(|_| {
            Vec4::new(
                rng.next() * 13.0,
                rng.next() * 7.0,
                0.5 + rng.next() * 20.0,
                rng.next() * 2.4 - 1.2,
            )
        })
        .collect();
    let bindings = [
        Binding::Uniform(bytemuck::cast_slice(&uniform)),
        Binding::Read(bytemuck::cast_slice(&queries)),
        Binding::Output(16 * queries.len() as u64),
    ];
    let out = ctx.run_compute(&kernel, "main", &bindings, [2, 1, 1]).expect("runs");
    let out: Vec<Vec4> = cast_vec(&out[2]);
    for (q, o) in queries.iter().zip(&out) {
        let p = v.world_position(q.truncate().truncate(), q.z);
        let f = fresnel_schlick(1.0 + q.z * 0.1, q.w);
        assert!((o.truncate() - p).length() < 1e-4 * (1.0 + p.length()), "{o} against {p}");
        assert!((o.w - f).abs() < 1e-5, "{} against {f}", o.w);
    }
}

/// Every shader parses and validates with naga, and the structs Rust writes have the sizes
/// WGSL lays their twins out with.
#[test]
fn shaders_validate_and_structs_match_their_wgsl_twins() {
    for (name, source) in
        [("raycast", RAYCAST_WGSL), ("combine", COMBINE_WGSL), ("scatter", SCATTER_WGSL)]
    {
        gpu_harness::validate_wgsl(source).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    let size = |name| gpu_harness::wgsl_struct_size(RAYCAST_WGSL, name).unwrap();
    use std::mem::size_of;
    assert_eq!(size("TracedView"), size_of::<TracedView>());
    assert_eq!(size("RayCast"), size_of::<RayCast>());
    assert_eq!(size("ListedRay"), size_of::<ListedRay>());
    assert_eq!(size("Material"), size_of::<GpuMaterial>());
    for (name, value) in [
        ("TRACED_REFLECTIONS", TRACED_REFLECTIONS),
        ("TRACED_REFRACTIONS", TRACED_REFRACTIONS),
        ("TRACED_ADD", TRACED_ADD),
    ] {
        let line = format!("const {name}: u32 = {value}u;");
        assert!(RAYCAST_WGSL.contains(&line), "{line}");
    }
}
