//! GPU path: naga validation of the exact shader source and CPU/GPU parity of the sky map.
#![cfg(feature = "gpu")]

use atmosphere::gpu::{SKYMAP_ENTRY, SKYMAP_WGSL, SkyMapGpuInputs, sky_map_from_gpu};
use atmosphere::{Atmosphere, Sky, SkyMapSettings, SkySettings};
use glam::Vec3;
use gpu_harness::{Binding, cast_vec, gpu_test_context};

#[test]
fn shaders_validate_with_naga() {
    for source in [SKYMAP_WGSL.to_owned(), atmosphere::gpu::skymap_sample_eval_shader()] {
        gpu_harness::validate_wgsl(&source).unwrap_or_else(|e| panic!("{e}"));
    }
}

fn rel_rms(a: &[Vec3], r: &[Vec3]) -> f64 {
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for (x, y) in a.iter().zip(r) {
        for k in 0..3 {
            num += ((x[k] - y[k]) as f64).powi(2);
            den += (y[k] as f64).powi(2);
        }
    }
    (num / den).sqrt()
}

#[test]
fn gpu_sky_map_matches_cpu() {
    let Some(ctx) = gpu_test_context() else { return };
    for (settings, sun_y) in [
        (SkySettings::default(), 0.5f32),
        (SkySettings::low(), 0.05),
        (SkySettings::default().single_scattering(), -0.1),
    ] {
        let sky = Sky::new(Atmosphere::EARTH, settings).unwrap();
        let map_settings =
            SkyMapSettings { size: 48, altitude_km: 0.3, ..SkyMapSettings::default() };
        let sun = Vec3::new(0.6, sun_y, -0.4).normalize();
        let inputs = SkyMapGpuInputs::new(&sky, &map_settings, sun).unwrap();
        let out = ctx
            .run_compute(
                SKYMAP_WGSL,
                SKYMAP_ENTRY,
                &[
                    Binding::Uniform(bytemuck::bytes_of(&inputs.params)),
                    Binding::Read(bytemuck::cast_slice(&inputs.transmittance)),
                    Binding::Read(bytemuck::cast_slice(&inputs.multiple_scattering)),
                    Binding::Output(inputs.output_bytes),
                ],
                inputs.workgroups,
            )
            .expect("dispatch");
        let rgb: Vec<f32> = cast_vec(&out[3]);
        let gpu = sky_map_from_gpu(&map_settings, sun, &rgb).unwrap();
        let cpu = SkyMapGpuInputs::cpu_equivalent(&sky, &map_settings, sun).unwrap();
        let err = rel_rms(gpu.texels(), cpu.texels());
        assert!(err < 1e-3, "sun y {sun_y}: GPU vs CPU rel RMS {err}");
        assert!(cpu.texels().iter().any(|t| t.max_element() > 0.0));
    }
}

/// The resident pass: the same map as the CPU path for two suns in a row, and recording
/// again creates no GPU object.
#[test]
fn resident_sky_map_matches_cpu_and_allocates_nothing_per_record() {
    use atmosphere::gpu::ResidentSkyMap;
    let Some(ctx) = gpu_test_context() else { return };
    let sky = Sky::new(Atmosphere::EARTH, SkySettings::low()).unwrap();
    let settings = SkyMapSettings { size: 32, ..SkyMapSettings::default() };
    let map = ResidentSkyMap::new(&ctx.device, &sky, &settings).unwrap();
    assert_eq!(map.size(), 32);
    let mut before = None;
    for sun in [Vec3::new(-0.2, 0.3, 0.9), Vec3::new(0.7, 0.05, -0.2)] {
        let sun = sun.normalize();
        let mut enc = ctx.device.create_command_encoder(&Default::default());
        map.record(&ctx.queue, &mut enc, sun).unwrap();
        ctx.queue.submit([enc.finish()]);
        let live = gpu_harness::live_objects(&ctx.device);
        assert!(before.is_none_or(|b| b == live), "{before:?} -> {live:?}");
        before = Some(live);
        let gpu = map.read_back(&ctx.device, &ctx.queue, sun).unwrap();
        let cpu = SkyMapGpuInputs::cpu_equivalent(&sky, &settings, sun).unwrap();
        gpu.validate().unwrap();
        let err = rel_rms(gpu.texels(), cpu.texels());
        assert!(err < 1e-3, "sun {sun}: {err}");
    }
    let mut enc = ctx.device.create_command_encoder(&Default::default());
    assert!(map.record(&ctx.queue, &mut enc, Vec3::ZERO).is_err(), "a zero sun is refused");
}

/// The consumers' snippet samples a map as `SkyMap::sample` does, below the horizon and
/// at the zenith included.
#[test]
fn the_sample_snippet_matches_the_cpu_sample() {
    use atmosphere::gpu::skymap_sample_eval_shader;
    let Some(ctx) = gpu_test_context() else { return };
    let sky = Sky::new(Atmosphere::EARTH, SkySettings::low()).unwrap();
    let settings = SkyMapSettings { size: 24, ..SkyMapSettings::default() };
    let map =
        atmosphere::SkyMap::new(&sky, settings, Vec3::new(0.3, 0.4, -0.8).normalize()).unwrap();
    let mut dirs: Vec<Vec3> = vec![Vec3::Y, Vec3::X, Vec3::new(0.3, -0.9, 0.1), Vec3::NEG_Y];
    let mut rng = 12345u64;
    let mut next = || {
        rng = rng.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((rng >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
    };
    dirs.extend((0..500).map(|_| Vec3::new(next(), next(), next())));
    let rgb: Vec<f32> = map.texels().iter().flat_map(|t| t.to_array()).collect();
    let d4: Vec<[f32; 4]> = dirs.iter().map(|d| d.extend(0.0).to_array()).collect();
    let params = [settings.size, dirs.len() as u32, 0, 0];
    let out = ctx
        .run_compute(
            &skymap_sample_eval_shader(),
            "main",
            &[
                Binding::Uniform(bytemuck::cast_slice(&params)),
                Binding::Read(bytemuck::cast_slice(&rgb)),
                Binding::Read(bytemuck::cast_slice(&d4)),
                Binding::Output(dirs.len() as u64 * 16),
            ],
            [(dirs.len() as u32).div_ceil(64), 1, 1],
        )
        .expect("dispatch");
    let gpu: Vec<[f32; 4]> = cast_vec(&out[3]);
    let gpu: Vec<Vec3> = gpu.iter().map(|v| Vec3::new(v[0], v[1], v[2])).collect();
    let cpu: Vec<Vec3> = dirs.iter().map(|&d| map.sample(d)).collect();
    let err = rel_rms(&gpu, &cpu);
    assert!(err < 1e-5, "snippet vs SkyMap::sample: rel RMS {err}");
    for (g, c) in gpu.iter().zip(&cpu) {
        assert!((*g - *c).abs().max_element() <= 1e-4 * c.max_element().max(1e-3), "{g} vs {c}");
    }
}
