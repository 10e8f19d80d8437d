//! The engine's tone mapping (`post::gpu::ToneMapPass` over its HDR targets) against the CPU
//! twin (`post::ToneMapper`) of the HDR frame it read back: the same display image,
//! on the first frame (exposure adapts at once) and after a frame of adaptation; and a frame
//! rendered without its images reads back nothing but what its passes need.

mod common;

use post::{ToneMapper, log_average};

/// Channels differing by more than one step of 8 bits, and the largest difference.
fn compare(gpu: &[u8], cpu: &[u8]) -> (usize, u8) {
    let off = gpu.iter().zip(cpu).filter(|(a, b)| a.abs_diff(**b) > 1).count();
    let max = gpu.iter().zip(cpu).map(|(a, b)| a.abs_diff(*b)).max().unwrap_or(0);
    (off, max)
}

#[test]
fn gpu_tone_mapping_matches_the_cpu_twin() {
    let Some(mut r) = common::generated(scene::Generated::CornellWindow, 96, 64) else { return };
    r.set_fixed_frame_time(Some(0.25));
    let s = r.settings().clone();
    let f1 = r.render_frame().expect("frame 1");
    let mut cpu = ToneMapper::default();
    cpu.adapt(log_average(&f1.hdr.pixels), 0.0, s.adaptation_per_s);
    let (off, max) = compare(&f1.ldr, &cpu.map(&f1.hdr.pixels, s.key));
    assert!(off == 0 && max <= 1, "frame 1: {off} channels off by more than 1 (max {max})");
    // A different view: the exposure moves a quarter second towards its new average.
    let mut cam = *r.camera();
    cam.forward = (cam.forward + glam::Vec3::new(0.4, -0.3, 0.0)).normalize();
    r.set_camera(cam).expect("camera");
    let f2 = r.render_frame().expect("frame 2");
    let a = cpu.adapt(log_average(&f2.hdr.pixels), 0.25, s.adaptation_per_s);
    let (off, max) = compare(&f2.ldr, &cpu.map(&f2.hdr.pixels, s.key));
    assert!(off == 0 && max <= 1, "frame 2 (adapted {a}): {off} channels off (max {max})");
    // The display image is not the HDR image clamped: exposure was applied.
    assert!(f2.ldr.iter().any(|&v| v > 30 && v < 250), "a mid-grey somewhere");
}

#[test]
fn a_frame_without_images_reads_back_only_what_its_passes_need() {
    let Some(mut r) = common::generated(scene::Generated::PlaneBox, 96, 64) else { return };
    r.advance_frame().expect("frame 1");
    let still = r.advance_frame().expect("frame 2");
    assert_eq!(still.transfers.read_back_bytes, 0, "a still frame reads nothing back");
    assert_eq!(still.transfers.cpu_waits, 0, "a still frame never waits for the GPU");
    // The images are read on demand: HDR (8 bytes a pixel) and display (4).
    let (hdr, ldr) = r.read_frame().expect("read");
    assert_eq!((hdr.pixels.len(), ldr.len()), (96 * 64, 96 * 64 * 4));
}

/// A moving camera's frame in the city (mirrors and glass in view) reads back only the
/// ray-casting texels that have a ray (a 16-byte count, then 64 bytes a texel), never the
/// whole quarter-resolution buffer, and uploads the traced radiance one entry per ray, not
/// per texel and slot.
#[test]
fn a_moving_frame_moves_only_the_texels_with_rays() {
    let settings = engine::Settings::preset(engine::Preset::Default, 96, 64);
    let Some(mut r) = common::renderer(scene::Generated::City.build(common::SEED), settings) else {
        return;
    };
    let warm = r.sky_volume_frames() + 2;
    for k in 0..warm + 3 {
        let mut cam = *r.camera();
        cam.position += cam.forward.cross(cam.up).normalize() * 0.02;
        r.set_camera(cam).expect("camera");
        let f = r.render_frame().expect("frame");
        if k < warm {
            continue;
        }
        assert!(f.ray_traced, "the city's view has mirrors and glass");
        assert_eq!(f.transfers.cpu_waits, 1, "one wait: the list with its count");
        let texels = 48 * 32;
        let read = f.transfers.read_back_bytes;
        assert!(read > 16 && (read - 16) % 64 == 0, "read back {read} bytes: not a ray list");
        let listed = (read - 16) / 64;
        assert!(listed < texels, "{listed} of {texels} texels listed: the view is not all glass");
        // At most two rays a listed texel; the uniforms are well under a kilobyte a pass.
        let up = f.transfers.uploaded_bytes;
        assert!(up <= listed * 2 * 16 + 4096, "uploaded {up} bytes for {listed} texels");
        assert!(up < texels * 2 * 16, "uploaded {up} bytes: as much as a slot per texel");
        eprintln!("read back {read} B ({listed} texels), uploaded {up} B");
    }
}

/// A caller's device (as a window makes one for its surface) renders the same frame as the
/// engine's own.
#[test]
fn a_callers_device_renders_the_same_frame() {
    let Some(mut own) = common::generated(scene::Generated::PlaneBox, 64, 36) else { return };
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let settings = own.settings().clone();
    let described = ctx.describe();
    let mut theirs = engine::Renderer::on_device(
        scene::Generated::PlaneBox.build(common::SEED),
        settings,
        ctx.device,
        ctx.queue,
        &ctx.adapter_info,
    )
    .expect("renderer on the caller's device");
    assert_eq!(theirs.adapter(), described);
    let (a, b) = (own.render_frame().expect("own"), theirs.render_frame().expect("theirs"));
    assert_eq!(a.ldr, b.ldr, "the same display image");
    assert_eq!(theirs.display_texture().format(), wgpu::TextureFormat::Rgba8Unorm);
}
