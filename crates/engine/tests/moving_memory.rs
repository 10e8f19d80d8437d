//! Frames of a moving camera and sun leave resident memory where it was once the renderer is
//! warm. Alone in its test binary because resident memory (`VmRSS`) is the whole process's.
//!
//! Issue 57 §1: on Mesa 22.3's lavapipe the soak grew by about 5 MiB per frame while every
//! wgpu object count stayed flat. The driver inlines uniform values that a shader's branches
//! depend on, compiling the shader anew every time its pipeline is bound and keeping every
//! copy; the lighting shader's branches on its frame uniform were such, and it was bound
//! every frame (`shaders/engine/lighting.wgsl`'s `load_frame` now hides the uniform from that
//! inlining, as it does for its reflectors and sky-volume uniforms: with the frame's alone
//! hidden, fs_lighting still recompiled here through those). No wgpu object is created
//! there, so a creation count cannot see it: resident memory is the measure. 16 frames grew
//! 74-80 MiB before (city, default preset, 64x36); the bound is 1 MiB a frame.

mod common;

use engine::{Preset, Settings};
use scene::SunPosition;

/// Resident memory of this process, KiB (`None` where `/proc` has no `VmRSS`).
fn resident_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// `frames` frames with the camera moving 2 cm sideways and the sun moving a little in each.
fn move_and_render(r: &mut engine::Renderer, frames: usize) {
    for _ in 0..frames {
        let mut cam = *r.camera();
        cam.position += cam.forward.cross(cam.up).normalize() * 0.02;
        r.set_camera(cam).expect("camera");
        let mut sun = r.scene().sun;
        if let Some(s) = sun.as_mut() {
            s.position = match s.position {
                SunPosition::Direction(d) => SunPosition::Direction(d + glam::Vec3::Y * 0.002),
                SunPosition::Time { date, utc_hours, latitude_deg, longitude_deg } => {
                    let utc_hours = utc_hours + 0.01;
                    SunPosition::Time { date, utc_hours, latitude_deg, longitude_deg }
                }
            };
        }
        r.set_sun(sun).expect("sun");
        r.advance_frame().expect("frame");
    }
}

#[test]
fn moving_frames_do_not_grow_resident_memory_once_warm() {
    const FRAMES: usize = 16;
    let settings = Settings::preset(Preset::Default, 64, 36);
    let Some(mut r) = common::renderer(scene::Generated::City.build(common::SEED), settings) else {
        return;
    };
    let warm = r.sky_volume_frames() as usize + 4;
    move_and_render(&mut r, warm);
    let Some(before) = resident_kib() else {
        eprintln!("no VmRSS in /proc/self/status: resident memory not checked");
        return;
    };
    move_and_render(&mut r, FRAMES);
    let after = resident_kib().expect("VmRSS");
    let grown_kib = after as i64 - before as i64;
    eprintln!(
        "{} ({}): resident memory {before} KiB after {warm} warm-up frames, {after} KiB after \
         {FRAMES} more ({grown_kib:+} KiB)",
        r.adapter(),
        if r.is_software() { "software" } else { "hardware" },
    );
    assert!(
        grown_kib < 1024 * FRAMES as i64,
        "resident memory grew {grown_kib} KiB over {FRAMES} moving frames after the warm-up \
         (more than 1 MiB a frame): a pass creating per frame, or a driver recompiling a \
         shader per bind (issue 57 §1)"
    );
}
