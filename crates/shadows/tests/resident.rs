//! The resident passes: the cascade and cube lookups against their CPU twins and the
//! geometry, several passes recorded into one encoder and submitted once, and passes reused
//! across frames allocating nothing (runs on lavapipe in CI).
#![cfg(feature = "gpu")]

use glam::Vec3;
use gpu_harness::{Binding, GpuContext, gpu_test_context};
use proptest::prelude::*;
use shadows::gpu::{
    CSM_EVAL_WGSL, CUBE_INC_WGSL, CascadeShadows, CsmCascade, CubeLight, CubeShadows, DepthPass,
    DrawRange, Geometry, GpuMesh, GpuVplReduction, ReflectiveShadowMap, VertexLayout,
};
use shadows::plane_box::PlaneBox;
use shadows::*;
use wgpu::util::DeviceExt;

/// World-space triangles as a position + normal vertex buffer and an index buffer.
struct Buffers {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    draws: Vec<DrawRange>,
}

impl Buffers {
    fn new(device: &wgpu::Device, tris: &[[Vec3; 3]]) -> Self {
        let mut v = Vec::new();
        for t in tris {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or(Vec3::Y);
            for p in t {
                v.extend([*p, n]);
            }
        }
        let idx: Vec<u32> = (0..tris.len() as u32 * 3).collect();
        let init = |contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents,
                usage,
            })
        };
        // Two draws, to exercise the per-draw slots.
        let half = (tris.len() as u32 / 2) * 3;
        Self {
            vertices: init(bytemuck::cast_slice(&v), wgpu::BufferUsages::VERTEX),
            indices: init(bytemuck::cast_slice(&idx), wgpu::BufferUsages::INDEX),
            draws: vec![
                DrawRange { indices: 0..half, base_vertex: 0 },
                DrawRange { indices: half..idx.len() as u32, base_vertex: 0 },
            ],
        }
    }

    fn geometry(&self) -> Geometry<'_> {
        Geometry::opaque(&self.vertices, &self.indices, wgpu::IndexFormat::Uint32, &self.draws)
    }
}

/// The plane_box cascades for a camera looking at the box from `eye`, with their filters.
fn cascades(eye: Vec3, resolution: u32) -> (CascadedShadowMap, Vec<Pcss>, Vec<CsmCascade>) {
    let scene = PlaneBox::DEFAULT;
    let fwd = (Vec3::new(1.0, 0.5, 1.0) - eye).normalize();
    let cam =
        shadows::Camera::look_to(eye.as_dvec3(), fwd, Vec3::Y, 1.0, 16.0 / 9.0, 0.1, 60.0).unwrap();
    let settings = CsmSettings { cascades: 3, resolution, ..CsmSettings::DEFAULT };
    let csm = CascadedShadowMap::fit(&cam, scene.to_sun, &settings).unwrap();
    let pcss: Vec<Pcss> = csm
        .cascades
        .iter()
        .map(|c| Pcss::directional(&c.view, scene.sun_angular_radius * 4.0, &PcssSettings::DEFAULT))
        .collect::<Result<_, _>>()
        .unwrap();
    let blocks = csm.cascades.iter().zip(&pcss).map(|(c, p)| CsmCascade::new(c, p)).collect();
    (csm, pcss, blocks)
}

fn submit(ctx: &GpuContext, record: impl FnOnce(&mut wgpu::CommandEncoder)) {
    let mut enc = ctx.device.create_command_encoder(&Default::default());
    record(&mut enc);
    ctx.queue.submit([enc.finish()]);
}

/// `csm.inc.wgsl` and `csm_visibility` agree on receivers all over the plane and the box top,
/// through all three cascades, over the maps the resident pass rendered; and the lookup sees
/// the box's shadow (some receivers shadowed, some lit).
/// `entry` of `shaders/shadows/csm_eval.wgsl` over `queries` (position, view depth, normal)
/// with the cascades' blocks, maps and taps: one visibility per query.
fn eval_on_gpu(
    ctx: &GpuContext,
    entry: &str,
    (blocks, maps, pcss): (&[CsmCascade], &[DepthMap], &Pcss),
    queries: &[[f32; 8]],
) -> Vec<f32> {
    let depths: Vec<f32> = maps.iter().flat_map(|m| m.as_slice().iter().copied()).collect();
    let out = ctx
        .run_compute(
            CSM_EVAL_WGSL,
            entry,
            &[
                Binding::Read(bytemuck::cast_slice(blocks)),
                Binding::Read(bytemuck::cast_slice(&depths)),
                Binding::Read(bytemuck::cast_slice(pcss.taps())),
                Binding::Read(bytemuck::cast_slice(queries)),
                Binding::Output(queries.len() as u64 * 4),
            ],
            [(queries.len() as u32).div_ceil(64), 1, 1],
        )
        .unwrap();
    gpu_harness::cast_vec(&out[4])
}

#[test]
fn csm_lookup_cpu_gpu_parity() {
    let Some(ctx) = gpu_test_context() else { return };
    let scene = PlaneBox::DEFAULT;
    let buffers = Buffers::new(&ctx.device, &scene.triangles());
    let eye = Vec3::new(-6.0, 4.0, -5.0);
    let (csm, pcss, blocks) = cascades(eye, 256);
    let pass = CascadeShadows::new(&ctx.device, VertexLayout::POSITION_NORMAL, 256, 3).unwrap();
    submit(&ctx, |enc| {
        pass.record(&ctx.queue, enc, &buffers.geometry(), &blocks, pcss[0].taps()).unwrap();
    });
    let maps: Vec<DepthMap> =
        (0..3).map(|c| pass.read_back(&ctx.device, &ctx.queue, c).unwrap()).collect();
    let fwd = csm.cascades[0].sphere_center - eye.as_dvec3();
    let fwd = fwd.normalize().as_vec3();
    let mut queries: Vec<[f32; 8]> = Vec::new();
    for i in 0..48 * 48 {
        let (u, v) = ((i % 48) as f32 / 47.0, (i / 48) as f32 / 47.0);
        let (p, n) = if i % 7 == 0 {
            (Vec3::new(-0.45 + 0.9 * u, 3.0, -0.45 + 0.9 * v), Vec3::Y)
        } else {
            let (lo, hi) = (scene.region_min, scene.region_max);
            (Vec3::new(lo.x + (hi.x - lo.x) * u, 0.0, lo.y + (hi.y - lo.y) * v), Vec3::Y)
        };
        let depth = (p - eye).dot(fwd).max(0.2);
        queries.push([p.x, p.y, p.z, depth, n.x, n.y, n.z, 0.0]);
    }
    type Lookup = fn(&[CsmCascade], &[Pcss], &[DepthMap], Vec3, Vec3, f32) -> f32;
    let lookups: [(&str, Lookup); 2] =
        [("main", csm_visibility), ("main_hard", shadows::csm_visibility_hard)];
    for (entry, cpu_lookup) in lookups {
        let gpu = eval_on_gpu(&ctx, entry, (&blocks, &maps, &pcss[0]), &queries);
        let (mut differ, mut shadowed, mut lit) = (0, 0, 0);
        for (q, g) in queries.iter().zip(gpu) {
            let p = Vec3::new(q[0], q[1], q[2]);
            let cpu = cpu_lookup(&blocks, &pcss, &maps, p, Vec3::new(q[4], q[5], q[6]), q[3]);
            differ += ((cpu - g).abs() > 1e-5) as usize;
            shadowed += (cpu < 0.1) as usize;
            lit += (cpu > 0.9) as usize;
        }
        let n = queries.len();
        // Equal up to rare comparison ties flipped by FMA contraction on the GPU.
        assert!(differ * 100 < n, "{entry}: {differ} of {n} visibilities differ");
        assert!(shadowed > n / 50 && lit > n / 2, "{entry}: shadowed {shadowed}, lit {lit} of {n}");
    }
    // The box's shadow falls where the CPU reference says: a point just behind the box
    // (away from the sun) is shadowed, one in front of it lit.
    let behind = Vec3::new(0.0, 0.0, 0.0) - scene.to_sun.with_y(0.0).normalize() * 1.5;
    let front = Vec3::new(0.0, 0.0, 0.0) + scene.to_sun.with_y(0.0).normalize() * 1.5;
    let vis = |p: Vec3| csm_visibility(&blocks, &pcss, &maps, p, Vec3::Y, (p - eye).dot(fwd));
    assert!(vis(behind) < 0.1 && vis(front) > 0.9, "{} {}", vis(behind), vis(front));
}

/// `osm.inc.wgsl` and `osm_visibility` agree over overlapped maps the resident cascade pass
/// rendered (the maps are cascade blocks): each point reads the smallest map that holds it,
/// points outside the small one read a larger one, the box's shadow is seen, and a point
/// outside every map is lit.
#[test]
fn osm_lookup_cpu_gpu_parity() {
    let Some(ctx) = gpu_test_context() else { return };
    let scene = PlaneBox::DEFAULT;
    let buffers = Buffers::new(&ctx.device, &scene.triangles());
    let settings = OsmSettings {
        maps: 2,
        resolution: 256,
        base_radius: 1.5,
        growth: 4.0,
        caster_extension: 20.0,
    };
    let osm = OverlappedShadowMaps::fit(glam::DVec3::new(0.5, 1.0, 0.5), scene.to_sun, &settings)
        .unwrap();
    let pcss: Vec<Pcss> = osm
        .maps
        .iter()
        .map(|v| Pcss::directional(v, scene.sun_angular_radius * 4.0, &PcssSettings::DEFAULT))
        .collect::<Result<_, _>>()
        .unwrap();
    let blocks: Vec<CsmCascade> =
        osm.maps.iter().zip(&pcss).map(|(v, p)| CsmCascade::of_view(v, f32::INFINITY, p)).collect();
    let pass = CascadeShadows::new(&ctx.device, VertexLayout::POSITION_NORMAL, 256, 2).unwrap();
    submit(&ctx, |enc| {
        pass.record(&ctx.queue, enc, &buffers.geometry(), &blocks, pcss[0].taps()).unwrap();
    });
    let maps: Vec<DepthMap> =
        (0..2).map(|c| pass.read_back(&ctx.device, &ctx.queue, c).unwrap()).collect();
    let (lo, hi) = (scene.region_min, scene.region_max);
    let mut queries: Vec<[f32; 8]> = Vec::new();
    for i in 0..40 * 40 {
        let (u, v) = ((i % 40) as f32 / 39.0, (i / 40) as f32 / 39.0);
        let p = Vec3::new(lo.x + (hi.x - lo.x) * u, 0.0, lo.y + (hi.y - lo.y) * v);
        queries.push([p.x, p.y, p.z, 0.0, 0.0, 1.0, 0.0, 0.0]);
    }
    let gpu = eval_on_gpu(&ctx, "main_osm", (&blocks, &maps, &pcss[0]), &queries);
    let (mut differ, mut outer, mut shadowed) = (0, 0, 0);
    for (q, g) in queries.iter().zip(gpu) {
        let p = Vec3::new(q[0], q[1], q[2]);
        let cpu = osm_visibility(&blocks, &pcss, &maps, p, Vec3::Y);
        differ += ((cpu - g).abs() > 1e-5) as usize;
        outer += (osm.select(p.as_dvec3(), 0.0) == Some(1)) as usize;
        shadowed += (cpu < 0.1) as usize;
    }
    let n = queries.len();
    assert!(differ * 100 < n, "{differ} of {n} visibilities differ");
    assert!(outer > n / 10, "{outer} of {n} points read the larger map");
    assert!(shadowed > n / 100, "the box's shadow: {shadowed} of {n}");
    let far = Vec3::new(500.0, 0.0, 500.0);
    assert_eq!(osm_visibility(&blocks, &pcss, &maps, far, Vec3::Y), 1.0, "outside every map: lit");
}

const CUBE_EVAL: &str = "
@group(0) @binding(0) var maps: texture_depth_cube_array;
@group(0) @binding(1) var cmp: sampler_comparison;
@group(0) @binding(2) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> out: array<f32>;
struct Light { position: vec4<f32>, range: vec4<f32> }
@group(0) @binding(4) var<uniform> light: Light;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&points) { return; }
    let p = points[id.x].xyz;
    out[id.x] = cube_visibility(maps, cmp, i32(light.range.w), light.position.xyz,
        light.range.x, light.range.y, light.range.z, p, vec3<f32>(0.0, 1.0, 0.0));
}";

/// `cube.inc.wgsl` against the geometry: a light above a floor with a square occluder between
/// them; floor points under the occluder's umbra are shadowed, points well outside it lit,
/// for the second light of the array (the cube index matters).
#[test]
fn cube_lookup_sees_the_occluder() {
    let Some(ctx) = gpu_test_context() else { return };
    let d = &ctx.device;
    let quad = |y: f32, h: f32| {
        let c =
            [Vec3::new(-h, y, -h), Vec3::new(h, y, -h), Vec3::new(h, y, h), Vec3::new(-h, y, h)];
        [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
    };
    let tris: Vec<[Vec3; 3]> = quad(0.0, 20.0).into_iter().chain(quad(2.0, 1.0)).collect();
    let buffers = Buffers::new(d, &tris);
    let lights = [
        CubeLight { position: Vec3::new(9.0, 3.0, 9.0), near: 0.05, far: 30.0 },
        CubeLight { position: Vec3::new(0.0, 4.0, 0.0), near: 0.05, far: 30.0 },
    ];
    let pass = CubeShadows::new(d, VertexLayout::POSITION_NORMAL, 128, 2).unwrap();
    submit(&ctx, |enc| pass.record(&ctx.queue, enc, &buffers.geometry(), &lights).unwrap());
    // Occluder half-size 1 at height 2, light at 4: umbra on the floor within |x|,|z| < 2.
    let points: Vec<[f32; 4]> = (0..40 * 40)
        .map(|i| {
            [-8.0 + 16.0 * (i % 40) as f32 / 39.0, 0.0, -8.0 + 16.0 * (i / 40) as f32 / 39.0, 0.0]
        })
        .collect();
    let l = lights[1];
    let uniform = [l.position.extend(0.0).to_array(), [l.near, l.far, 128.0, 1.0]];
    let src = format!("{CUBE_INC_WGSL}\n{CUBE_EVAL}");
    let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: None,
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let init = |contents: &[u8], usage| {
        d.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: None, contents, usage })
    };
    let pts = init(bytemuck::cast_slice(&points), wgpu::BufferUsages::STORAGE);
    let out = init(
        &vec![0u8; points.len() * 4],
        wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    );
    let uni = init(bytemuck::cast_slice(&uniform), wgpu::BufferUsages::UNIFORM);
    let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(pass.view()),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(pass.sampler()),
            },
            wgpu::BindGroupEntry { binding: 2, resource: pts.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 3, resource: out.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 4, resource: uni.as_entire_binding() },
        ],
    });
    let staging = d.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: points.len() as u64 * 4,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    submit(&ctx, |enc| {
        {
            let mut c = enc.begin_compute_pass(&Default::default());
            c.set_pipeline(&pipeline);
            c.set_bind_group(0, &group, &[]);
            c.dispatch_workgroups((points.len() as u32).div_ceil(64), 1, 1);
        }
        enc.copy_buffer_to_buffer(&out, 0, &staging, 0, points.len() as u64 * 4);
    });
    let vis: Vec<f32> = bytemuck::cast_slice(&ctx.read_buffer(&staging).unwrap()).to_vec();
    let (mut checked_in, mut checked_out) = (0, 0);
    for (p, v) in points.iter().zip(&vis) {
        let m = p[0].abs().max(p[2].abs());
        if m < 1.6 {
            assert!(*v < 0.05, "({}, {}) under the occluder: visibility {v}", p[0], p[2]);
            checked_in += 1;
        } else if m > 2.6 {
            assert!(*v > 0.95, "({}, {}) outside the umbra: visibility {v}", p[0], p[2]);
            checked_out += 1;
        }
    }
    assert!(checked_in > 20 && checked_out > 500);
}

proptest! {
    /// `cube_shadow_depth` is the depth the face matrices produce for any point in range.
    #[test]
    fn cube_shadow_depth_matches_face_matrices(
        d in prop::array::uniform3(-1.0f32..1.0), t in 0.3f32..40.0,
    ) {
        let d = Vec3::from_array(d);
        prop_assume!(d.length() > 0.1);
        let (light, near, far) = (Vec3::new(3.0, -2.0, 7.0), 0.1f32, 50.0f32);
        let off = d.normalize() * t;
        let m = cube_face_view_proj(light, near, far).unwrap()[cube_face_of(off)];
        let clip = m * (light + off).extend(1.0);
        let want = clip.z / clip.w;
        prop_assert!((cube_shadow_depth(off, near, far) - want).abs() < 2e-5);
    }
}

/// Live buffers, textures, texture views, bind groups, buffer and texture bytes once the
/// device is idle (the queue's staging buffers for `write_buffer` are gone by then).
fn counts(d: &wgpu::Device) -> [isize; 6] {
    d.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let c = d.get_internal_counters().hal;
    [
        c.buffers.read(),
        c.textures.read(),
        c.texture_views.read(),
        c.bind_groups.read(),
        c.buffer_memory.read(),
        c.texture_memory.read(),
    ]
}

/// Textures, texture views, bind groups and samplers alive now (no staging among them).
fn views_and_groups(d: &wgpu::Device) -> [isize; 4] {
    let c = d.get_internal_counters().hal;
    [c.textures.read(), c.texture_views.read(), c.bind_groups.read(), c.samplers.read()]
}

/// Cascades, cubes and the RSM recorded into one encoder and submitted once give the maps
/// the one-call passes give; recording them again for a moved camera and light creates no
/// buffer, texture, view or bind group.
#[test]
fn passes_share_one_encoder_and_allocate_nothing_when_reused() {
    let Some(ctx) = gpu_test_context() else { return };
    let d = &ctx.device;
    let scene = PlaneBox::DEFAULT;
    let tris = scene.triangles();
    let buffers = Buffers::new(d, &tris);
    let csm = CascadeShadows::new(d, VertexLayout::POSITION_NORMAL, 128, 3).unwrap();
    let cubes = CubeShadows::new(d, VertexLayout::POSITION_NORMAL, 64, 2).unwrap();
    let rsm = ReflectiveShadowMap::new(d, VertexLayout::POSITION_NORMAL, 64, 2).unwrap();
    let view = scene.shadow_view(64);
    let albedo = [Vec3::new(0.5, 0.4, 0.3), Vec3::splat(0.7)];
    let frame = |k: f32| {
        let (_, pcss, blocks) = cascades(Vec3::new(-6.0 + k, 4.0, -5.0), 128);
        let lights = [CubeLight { position: Vec3::new(2.0 + k, 5.0, 1.0), near: 0.05, far: 20.0 }];
        submit(&ctx, |enc| {
            let before = views_and_groups(d);
            csm.record(&ctx.queue, enc, &buffers.geometry(), &blocks, pcss[0].taps()).unwrap();
            cubes.record(&ctx.queue, enc, &buffers.geometry(), &lights).unwrap();
            rsm.record(&ctx.queue, enc, &buffers.geometry(), &albedo, &view, Vec3::ONE).unwrap();
            // Nothing made for the frame, not even a view that dies with the command buffer.
            assert_eq!(before, views_and_groups(d), "recording created textures, views or groups");
        });
        (blocks, lights)
    };
    frame(0.0);
    let before = counts(d);
    let (blocks, lights) = frame(0.5);
    frame(1.0);
    let after = counts(d);
    assert_eq!(before, after, "buffers, textures, views, bind groups, bytes: reuse allocated");
    // Frame 0.5's content, against the one-call passes.
    let (blocks2, lights2) = frame(0.5);
    assert_eq!((&blocks, lights), (&blocks2, lights2));
    let (pos, idx): (Vec<Vec3>, Vec<u32>) =
        (tris.iter().flatten().copied().collect(), (0..tris.len() as u32 * 3).collect());
    let mesh = GpuMesh {
        positions: &pos,
        normals: &[],
        indices: &idx,
        model: glam::Mat4::IDENTITY,
        albedo: Vec3::ONE,
    };
    let one = DepthPass::new(d).unwrap();
    for (c, b) in blocks.iter().enumerate() {
        let vp = glam::Mat4::from_cols_array_2d(&b.view_proj);
        let want = one.render(d, &ctx.queue, &[mesh], vp, 128, 128).unwrap();
        let got = csm.read_back(d, &ctx.queue, c as u32).unwrap();
        assert_eq!(want.as_slice(), got.as_slice(), "cascade {c}");
    }
    let l = lights[0];
    let want = one.render_cube(d, &ctx.queue, &[mesh], l.position, l.near, l.far, 64).unwrap();
    let got = cubes.read_back(d, &ctx.queue, 0).unwrap();
    for f in 0..6 {
        assert_eq!(want[f].as_slice(), got[f].as_slice(), "cube face {f}");
    }
    let (map, _) = rsm.read_back(d, &ctx.queue).unwrap();
    map.validate().unwrap();
    let covered = map.normal.iter().filter(|n| **n != Vec3::ZERO).count();
    assert!(covered > 64 * 64 / 2, "the RSM sees the plane ({covered} texels)");
    // Its VPLs reduced on the GPU are the CPU's `extract_vpls` of the map read back, and
    // reducing again makes nothing.
    for block in [1, 4, 5] {
        let reduction = GpuVplReduction::new(d, &rsm, block).unwrap();
        submit(&ctx, |enc| reduction.record(enc));
        let got = reduction.read(d).unwrap();
        let before = counts(d);
        submit(&ctx, |enc| reduction.record(enc));
        assert_eq!(reduction.read(d).unwrap(), got);
        assert_eq!(before, counts(d), "a reduction creates nothing");
        let want = map.extract_vpls(block).unwrap();
        assert_eq!(got.len(), want.len(), "block {block}: VPL count");
        let scale = want.iter().fold(0.0f32, |m, v| m.max(v.flux.max_element())).max(1e-30);
        for (g, w) in got.iter().zip(&want) {
            let close = |a: Vec3, b: Vec3, tol: f32| (a - b).abs().max_element() <= tol;
            assert!(close(g.flux, w.flux, 1e-5 * scale), "block {block}: {g:?} vs {w:?}");
            assert!(close(g.position, w.position, 1e-4), "block {block}: {g:?} vs {w:?}");
            assert!(close(g.normal, w.normal, 1e-5), "block {block}: {g:?} vs {w:?}");
        }
    }
    assert!(GpuVplReduction::new(d, &rsm, 0).is_err(), "block 0 is a typed error");
    // More cascades or lights than the pass was made for is an error, not a panic.
    let (_, pcss, mut blocks) = cascades(Vec3::new(-6.0, 4.0, -5.0), 128);
    blocks.push(blocks[0]);
    let mut enc = d.create_command_encoder(&Default::default());
    assert!(matches!(
        csm.record(&ctx.queue, &mut enc, &buffers.geometry(), &blocks, pcss[0].taps()),
        Err(ShadowError::InvalidParameter { .. })
    ));
    assert!(matches!(
        cubes.record(&ctx.queue, &mut enc, &buffers.geometry(), &[l, l, l]),
        Err(ShadowError::InvalidParameter { .. })
    ));
}

/// `record_moved` renders exactly the cascades whose snapped view changed, and the maps it
/// leaves are those of a full render: for a camera nudged by less than the far cascades'
/// texels only the near ones move; an unmoved camera renders nothing.
#[test]
fn record_moved_renders_only_the_moved_cascades_and_matches_a_full_render() {
    let Some(ctx) = gpu_test_context() else { return };
    let d = &ctx.device;
    let buffers = Buffers::new(d, &PlaneBox::DEFAULT.triangles());
    let at = |dx: f32| cascades(Vec3::new(-6.0 + dx, 4.0, -5.0), 128);
    let (_, pcss, start) = at(0.0);
    let moved = |b: &[CsmCascade]| b.iter().zip(&start).filter(|(x, y)| x != y).count() as u32;
    // The smallest nudge that moves some cascades but not all (stabilised cascades' texels
    // grow with their distance).
    let dx = (1..200)
        .map(|k| k as f32 * 2e-3)
        .find(|&dx| (1..3).contains(&moved(&at(dx).2)))
        .expect("a nudge that moves only the near cascades");
    let (_, pcss2, nudged) = at(dx);
    let pass = CascadeShadows::new(d, VertexLayout::POSITION_NORMAL, 128, 3).unwrap();
    let record = |blocks: &[CsmCascade], taps: &[glam::Vec2]| {
        let mut rendered = 0;
        submit(&ctx, |enc| {
            let r = pass.record_moved(&ctx.queue, enc, &buffers.geometry(), blocks, taps);
            rendered = r.unwrap().rendered;
        });
        rendered
    };
    assert_eq!(record(&start, pcss[0].taps()), 3, "a new pass renders every map");
    assert_eq!(record(&start, pcss[0].taps()), 0, "an unmoved view renders nothing");
    assert_eq!(record(&nudged, pcss2[0].taps()), moved(&nudged));
    let full = CascadeShadows::new(d, VertexLayout::POSITION_NORMAL, 128, 3).unwrap();
    submit(&ctx, |enc| {
        full.record(&ctx.queue, enc, &buffers.geometry(), &nudged, pcss2[0].taps()).unwrap();
    });
    for c in 0..3 {
        let (a, b) = (pass.read_back(d, &ctx.queue, c), full.read_back(d, &ctx.queue, c));
        assert_eq!(a.unwrap().as_slice(), b.unwrap().as_slice(), "cascade {c}");
    }
}
