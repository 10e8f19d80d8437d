//! CPU/GPU parity of the WGSL lookup and brute-force fill, and naga validation of the exact
//! shader strings Rust uses.
#![cfg(feature = "gpu")]

use glam::{UVec3, Vec3};
use gpu_harness::{Binding, cast_vec, gpu_test_context};
use sky_volume::gpu::*;
use sky_volume::*;

fn validate_wgsl(src: &str) {
    gpu_harness::validate_wgsl(src).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn shaders_validate() {
    validate_wgsl(&lookup_shader());
    validate_wgsl(&fill_shader());
    // The clamp before packing is one number on both sides.
    let line = format!("const SKY_VOLUME_HALF_MAX: f32 = {HALF_MAX:?};");
    assert!(FILL_WGSL.contains(&line), "the fill should declare `{line}`");
}

/// The coefficients in a probe buffer (`pack_probe`'s words), 27 per point.
fn unpacked(bytes: &[u8]) -> Vec<f32> {
    let words: Vec<u32> = cast_vec(bytes);
    words.chunks_exact(PROBE_UVEC4S * 4).flat_map(|p| unpack_probe(p.try_into().unwrap())).collect()
}

/// Halves round a coefficient by at most 1 part in 2048 and keep its sign; beyond their
/// range they clamp.
#[test]
fn probes_pack_to_halves() {
    let p: [f32; 27] = std::array::from_fn(|k| (k as f32 - 13.0) * 0.37 + 0.011 * k as f32);
    let back = unpack_probe(&pack_probe(&p));
    for (a, b) in p.iter().zip(&back) {
        assert!((a - b).abs() <= a.abs() / 2048.0, "{a} -> {b}");
    }
    let words = pack_probe(&[1e9; 27]);
    assert_eq!(words[13] >> 16, 0, "the 28th half is zero");
    assert!(words[14..].iter().all(|&w| w == 0));
    assert!(unpack_probe(&words).iter().all(|&c| c == HALF_MAX));
    assert!(unpack_probe(&pack_probe(&[-1e9; 27])).iter().all(|&c| c == -HALF_MAX));
}

fn volume(method: FillMethod) -> (SkyVolume, AnalyticSky) {
    let grid =
        VolumeGrid::new(Vec3::new(-9.0, 0.0, -9.0), UVec3::new(7, 4, 6), Vec3::new(3.0, 2.5, 3.0));
    let mut quads = generated_city(&grid, 12, 4);
    quads.push(
        OcclusionQuad::horizontal(Vec3::new(2.0, 5.0, 1.0), 3.0, 2.0)
            .with_opacity(0.6, Vec3::new(0.3, 0.9, 0.4)),
    );
    let sky = AnalyticSky::new(Vec3::new(0.4, 0.5, -0.3));
    let mut v =
        SkyVolume::with_quads(grid, Settings::DEFAULT.with_samples(64).with_method(method), &quads)
            .unwrap();
    v.fill(&sky);
    (v, sky)
}

#[test]
fn fill_matches_cpu() {
    let Some(ctx) = gpu_test_context() else { return };
    let (v, sky) = volume(FillMethod::BruteForce);
    let inputs = v.gpu_fill_inputs(&sky);
    let n = v.grid().len();
    let out = ctx
        .run_compute(
            &fill_shader(),
            "fill",
            &[
                Binding::Uniform(bytemuck::bytes_of(&inputs.params)),
                Binding::Read(bytemuck::cast_slice(&inputs.samples)),
                Binding::Read(bytemuck::cast_slice(&inputs.sky)),
                Binding::Read(bytemuck::cast_slice(&inputs.quads)),
                Binding::Output((n * PROBE_UVEC4S * 16) as u64),
            ],
            [n.div_ceil(64) as u32, 1, 1],
        )
        .expect("dispatch");
    let gpu = unpacked(&out[4]);
    let cpu = unpacked(&v.gpu_probe_bytes());
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for (a, b) in gpu.iter().zip(&cpu) {
        num += ((a - b) as f64).powi(2);
        den += (*b as f64).powi(2);
    }
    let rel = (num / den).sqrt();
    assert!(rel < 1e-3, "GPU fill rel RMS {rel}");
}

#[test]
fn lookup_matches_cpu() {
    let Some(ctx) = gpu_test_context() else { return };
    let (v, _) = volume(FillMethod::CachedVisibility);
    let g = *v.grid();
    let lo = g.origin - Vec3::splat(2.0);
    let size = g.max_corner() - g.origin + Vec3::splat(4.0);
    let queries: Vec<Query> = (0..256u32)
        .map(|i| {
            let f = |k: u32| ((i * 7919 + k * 104_729) % 1000) as f32 / 1000.0;
            let n = Vec3::new(f(1) - 0.5, f(2) - 0.4, f(3) - 0.5).normalize_or(Vec3::Y);
            let p = lo + size * Vec3::new(f(4), f(5), f(6));
            Query {
                position: p.extend(1.0).to_array(),
                normal: n.extend(0.0).to_array(),
                albedo: [0.8, 0.5, 0.2, 1.0],
            }
        })
        .collect();
    let params = v.gpu_lookup_params();
    let out = ctx
        .run_compute(
            &lookup_shader(),
            "lookup",
            &[
                Binding::Uniform(bytemuck::bytes_of(&params)),
                Binding::Read(&v.gpu_probe_bytes()),
                Binding::Read(bytemuck::cast_slice(&queries)),
                Binding::Output((queries.len() * 16) as u64),
            ],
            [4, 1, 1],
        )
        .expect("dispatch");
    let gpu = cast_vec::<[f32; 4]>(&out[3]);
    for (q, got) in queries.iter().zip(&gpu) {
        let p = Vec3::from_slice(&q.position[..3]);
        let n = Vec3::from_slice(&q.normal[..3]);
        let want = v.diffuse(p, n, Vec3::new(0.8, 0.5, 0.2));
        let got = Vec3::from_slice(&got[..3]);
        // The probes are halves (1 part in 2048; here at most 8.2e-5), the CPU's lookup f32.
        assert!(
            (got - want).abs().max_element() <= 2.5e-4 * (1.0 + want.max_element()),
            "{p} {n}: {got} vs {want}"
        );
    }
}

/// The resident fill, recorded in two layer ranges into one encoder, gives the CPU's probes;
/// its lookup, bound once, gives the CPU's diffuse light; recording both again creates no GPU
/// object; a layer range past the volume is a typed error.
#[test]
fn resident_fill_and_lookup_match_cpu_and_allocate_nothing_per_record() {
    use wgpu::util::DeviceExt;
    let Some(ctx) = gpu_test_context() else { return };
    let (v, sky) = volume(FillMethod::BruteForce);
    let (device, queue) = (&ctx.device, &ctx.queue);
    let resident = ResidentSkyVolume::new(device, &v).unwrap();
    resident.set_sky(queue, &sky);
    let layers = v.grid().dims.y;
    let queries: Vec<Query> = (0..100u32)
        .map(|i| {
            let f = |k: u32| ((i * 7919 + k * 104_729) % 1000) as f32 / 1000.0;
            let n = Vec3::new(f(1) - 0.5, f(2) - 0.3, f(3) - 0.5).normalize_or(Vec3::Y);
            let p = v.grid().origin
                + (v.grid().max_corner() - v.grid().origin) * Vec3::new(f(4), f(5), f(6));
            Query {
                position: p.extend(1.0).to_array(),
                normal: n.extend(0.0).to_array(),
                albedo: [0.8, 0.5, 0.2, 1.0],
            }
        })
        .collect();
    let q = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&queries),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let out = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: queries.len() as u64 * 16,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let binding = resident.bind_lookup(device, &q, &out, queries.len() as u32);
    let mut live = None;
    for _ in 0..2 {
        let mut enc = device.create_command_encoder(&Default::default());
        resident.record_fill(&mut enc, 0..layers / 2).unwrap();
        resident.record_fill(&mut enc, layers / 2..layers).unwrap();
        resident.record_lookup(&mut enc, &binding);
        queue.submit([enc.finish()]);
        let now = gpu_harness::live_objects(device);
        assert!(live.is_none_or(|l| l == now), "{live:?} -> {now:?}");
        live = Some(now);
    }
    let gpu = resident.read_back(device, queue).unwrap();
    let cpu: Vec<f32> = cast_vec::<f32>(bytemuck::cast_slice(v.probes()));
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for (a, b) in gpu.iter().zip(&cpu) {
        num += ((a - b) as f64).powi(2);
        den += (*b as f64).powi(2);
    }
    assert!((num / den).sqrt() < 1e-3, "resident fill rel RMS {}", (num / den).sqrt());
    let light: Vec<[f32; 4]> =
        cast_vec(&gpu_harness::read_buffer(device, queue, &out, out.size()).unwrap());
    for (q, got) in queries.iter().zip(&light) {
        let (p, n) = (Vec3::from_slice(&q.position[..3]), Vec3::from_slice(&q.normal[..3]));
        let want = v.diffuse(p, n, Vec3::new(0.8, 0.5, 0.2));
        let got = Vec3::from_slice(&got[..3]);
        assert!(
            (got - want).abs().max_element() <= 1e-3 * (1.0 + want.max_element()),
            "{p}: {got} vs {want}"
        );
    }
    // The cached lookup into buffers of the caller's gives the same light, first 64 queries
    // only, and binds them once.
    let cached_out = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: out.size(),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut live = None;
    for _ in 0..2 {
        let mut enc = device.create_command_encoder(&Default::default());
        resident.record_lookup_into(device, &mut enc, (&q, &cached_out), 64);
        queue.submit([enc.finish()]);
        let now = gpu_harness::live_objects(device);
        assert!(live.is_none_or(|l| l == now), "{live:?} -> {now:?}");
        live = Some(now);
    }
    let cached: Vec<[f32; 4]> =
        cast_vec(&gpu_harness::read_buffer(device, queue, &cached_out, out.size()).unwrap());
    assert_eq!(cached[..64], light[..64]);
    assert!(cached[64..].iter().all(|v| *v == [0.0; 4]), "only the first 64 are looked up");
    let mut enc = device.create_command_encoder(&Default::default());
    let e = resident.record_fill(&mut enc, 0..layers + 1).unwrap_err();
    assert!(matches!(e, SkyVolumeError::LayerOutOfRange { .. }), "{e}");
}

/// Uploading layer by layer at the offsets `gpu_layer_bytes` gives writes the whole buffer;
/// a range past the volume is clamped.
#[test]
fn layer_bytes_tile_the_probe_buffer() {
    let (v, _) = volume(FillMethod::CachedVisibility);
    let all = v.gpu_probe_bytes();
    assert_eq!(all.len(), v.grid().len() * PROBE_UVEC4S * 16);
    let mut tiled = vec![0u8; all.len()];
    for y in 0..v.grid().dims.y {
        let (offset, bytes) = v.gpu_layer_bytes(y..y + 1);
        tiled[offset as usize..offset as usize + bytes.len()].copy_from_slice(&bytes);
    }
    assert_eq!(tiled, all);
    assert!(v.gpu_layer_bytes(v.grid().dims.y..v.grid().dims.y + 3).1.is_empty());
    let words: Vec<u32> = cast_vec(&all);
    assert!(words.chunks_exact(PROBE_UVEC4S * 4).all(|p| p[13] >> 16 == 0 && p[14..] == [0, 0]));
    let cpu: Vec<f32> = cast_vec(bytemuck::cast_slice(v.probes()));
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for (a, b) in unpacked(&all).iter().zip(&cpu) {
        num += ((a - b) as f64).powi(2);
        den += (*b as f64).powi(2);
    }
    assert!((num / den).sqrt() < 5e-4, "halves' rel RMS {}", (num / den).sqrt());
}
