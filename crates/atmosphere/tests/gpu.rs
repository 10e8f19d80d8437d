//! GPU path: naga validation of the exact shader source and CPU/GPU parity of the sky map.
#![cfg(feature = "gpu")]

use atmosphere::gpu::{SKYMAP_ENTRY, SKYMAP_WGSL, SkyMapGpuInputs, sky_map_from_gpu};
use atmosphere::{Atmosphere, Sky, SkyMapSettings, SkySettings};
use glam::Vec3;
use gpu_harness::{Binding, cast_vec, gpu_test_context};

#[test]
fn shader_validates_with_naga() {
    let module = naga::front::wgsl::parse_str(SKYMAP_WGSL).expect("parses");
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .expect("validates");
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

#[test]
fn crate_gpu_entry_point_matches_cpu() {
    use atmosphere::gpu::GpuSkyMapper;
    let Some(ctx) = gpu_test_context() else { return };
    let sky = Sky::new(Atmosphere::EARTH, SkySettings::low()).unwrap();
    let settings = SkyMapSettings { size: 32, ..SkyMapSettings::default() };
    let sun = Vec3::new(-0.2, 0.3, 0.9).normalize();
    let mapper = GpuSkyMapper::new(&ctx.device).unwrap();
    let gpu = mapper.compute_blocking(&ctx.device, &ctx.queue, &sky, &settings, sun).unwrap();
    let cpu = SkyMapGpuInputs::cpu_equivalent(&sky, &settings, sun).unwrap();
    gpu.validate().unwrap();
    assert!(rel_rms(gpu.texels(), cpu.texels()) < 1e-3);
}
