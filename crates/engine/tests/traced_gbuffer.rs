//! The traced G-buffer lit on the GPU (`TracedShading::Gpu`, thesis 6.3) against the CPU's
//! shading of the same hits (`TracedShading::Cpu`, shadow rays): a mirror floor reflects a
//! sunlit wall with an awning's shadow on it, and the reflections component comes out the
//! same within the difference between overlapped shadow maps and shadow rays. Only the GPU
//! mode runs the overlapped shadow maps and the traced lighting; the CPU mode skips both
//! with the setting as the reason.

mod common;

use common::quad;
use engine::{Component, Preset, Settings, TracedShading, pass};
use frame_scheduler::Outcome;
use glam::Vec3;
use scene::{Camera, Material, Scene, Sun};

const W: u32 = 96;
const H: u32 = 64;

fn scene(awning: bool) -> Scene {
    let mut s = Scene::new("mirror floor");
    let mirror = s.add_material(Material::mirror("mirror", 0.8));
    let white = s.add_material(Material::diffuse("wall", Vec3::splat(0.7)));
    // The floor (facing up) and the wall behind it (facing the camera).
    s.meshes.push(quad(Vec3::new(-5.0, 0.0, 3.0), Vec3::X * 10.0, Vec3::NEG_Z * 10.0, mirror));
    s.meshes.push(quad(Vec3::new(-5.0, 0.0, -7.0), Vec3::X * 10.0, Vec3::Y * 5.0, white));
    if awning {
        // An awning over the wall: its shadow covers the wall from about 1 m to 3 m.
        s.meshes.push(quad(Vec3::new(-5.0, 3.0, -7.0), Vec3::X * 10.0, Vec3::Z * 1.5, white));
    }
    s.sun = Some(Sun::from_direction(Vec3::new(0.3, 0.8, 0.6).normalize()));
    s.camera = Camera::look_at(
        Vec3::new(0.0, 2.0, 4.0),
        Vec3::new(0.0, 0.0, -3.0),
        50.0,
        W as f32 / H as f32,
    );
    s
}

/// The reflections component in `shading` mode. The mirror floor is also a planar reflector
/// that mirrors the sun onto the wall; `mirrored_sun` turns that on. The GPU mode's mirrored
/// sun does not test occluders between a hit and the reflector (the CPU's shadow rays do),
/// and the awning is one for the wall above it, so the parity of the two modes' sun is
/// measured without it.
fn reflections_with(
    shading: TracedShading,
    awning: bool,
    mirrored_sun: bool,
) -> Option<(Vec<Vec3>, engine::Frame)> {
    let settings = Settings {
        traced_shading: shading,
        mirrored_sun,
        // One sample: the second frame reuses the first (no jittered still samples).
        still_samples: 1,
        ..Settings::preset(Preset::Default, W, H)
    };
    let mut r = common::renderer(scene(awning), settings)?;
    r.set_component(Some(Component::Reflections));
    r.render_frame().expect("first frame");
    let frame = r.render_frame().expect("frame");
    Some((frame.hdr.rgb().collect(), frame))
}

fn reflections(shading: TracedShading, awning: bool) -> Option<(Vec<Vec3>, engine::Frame)> {
    reflections_with(shading, awning, false)
}

fn luminance(c: Vec3) -> f64 {
    (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) as f64
}

#[test]
fn the_gpu_lights_the_traced_gbuffer_as_the_cpu_shades_it() {
    let Some((cpu, cpu_frame)) = reflections(TracedShading::Cpu, true) else { return };
    let Some((gpu, gpu_frame)) = reflections(TracedShading::Gpu, true) else { return };
    for p in [pass::OSM, pass::TRACED_LIGHTING] {
        assert_eq!(
            common::outcome(&cpu_frame, p),
            Outcome::Skipped,
            "{}",
            common::describe(&cpu_frame, p)
        );
        assert!(
            cpu_frame.report.pass(p).unwrap().reason.to_string().contains("lit on the GPU"),
            "{}",
            common::describe(&cpu_frame, p)
        );
    }
    // Lit in the first frame, reused in the second (nothing moved).
    assert_eq!(common::outcome(&gpu_frame, pass::TRACED_LIGHTING), Outcome::Reused);
    let mean = |img: &[Vec3]| img.iter().map(|&c| luminance(c)).sum::<f64>() / img.len() as f64;
    let (a, b) = (mean(&cpu), mean(&gpu));
    assert!(a > 0.01, "the mirror reflects the sunlit wall: {a}");
    assert!((b / a - 1.0).abs() < 0.1, "mean luminance of the reflections: CPU {a}, GPU {b}");
    let (num, den) = cpu.iter().zip(&gpu).fold((0.0, 0.0), |(n, d), (&c, &g)| {
        (n + (luminance(g) - luminance(c)).powi(2), d + luminance(c).powi(2))
    });
    let rel = (num / den).sqrt();
    assert!(rel < 0.25, "per-pixel rel RMS between the two shadings: {rel}");
    // Both see the awning's shadow: without it the reflected wall is brighter.
    for shading in TracedShading::ALL {
        let with = mean(&reflections(shading, true).expect("renderer").0);
        let without = mean(&reflections(shading, false).expect("renderer").0);
        assert!(without > 1.05 * with, "{shading}: {with} with the awning, {without} without");
    }
    // The mirrored sun: without occluders between the wall and the floor, the same in both
    // modes, and it adds to the wall's light.
    let mirrored = |shading| mean(&reflections_with(shading, false, true).expect("renderer").0);
    let (a, b) = (mirrored(TracedShading::Cpu), mirrored(TracedShading::Gpu));
    let plain = mean(&reflections(TracedShading::Cpu, false).expect("renderer").0);
    assert!(a > 1.2 * plain, "the mirrored sun lights the wall: {a} against {plain}");
    assert!((b / a - 1.0).abs() < 0.05, "with the mirrored sun: CPU {a}, GPU {b}");
}
