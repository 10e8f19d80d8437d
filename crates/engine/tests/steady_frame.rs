//! A steady frame creates no bind groups: every pass keeps the groups it made while the
//! resources it binds stay the same (`gpu_harness::BindGroupCache`), so a moving camera costs
//! recording and uniforms, not objects. Alone in its test binary because the count it reads
//! (`gpu_harness::bind_groups_created`) is the whole process's.

mod common;

use engine::{Indirect, Preset, Settings};

/// Bind groups created by `frames` frames of `r` with the camera moving 2 cm sideways each.
fn created_while_moving(r: &mut engine::Renderer, frames: usize) -> u64 {
    let before = gpu_harness::bind_groups_created();
    for _ in 0..frames {
        let mut cam = *r.camera();
        cam.position += cam.forward.cross(cam.up).normalize() * 0.02;
        r.set_camera(cam).expect("camera");
        r.render_frame().expect("frame");
    }
    gpu_harness::bind_groups_created() - before
}

#[test]
fn a_moving_camera_creates_no_bind_groups_once_warm() {
    for (scene, indirect) in
        [(scene::Generated::City, Indirect::Rsm), (scene::Generated::CornellWindow, Indirect::Lpv)]
    {
        let mut settings = Settings::preset(Preset::Default, 64, 36);
        settings.indirect = indirect;
        let Some(mut r) = common::renderer(scene.build(common::SEED), settings) else { return };
        let warm = r.sky_volume_frames() as usize + 2;
        let first = created_while_moving(&mut r, warm);
        assert!(first > 0, "{scene:?}: the first frames make the bind groups");
        let steady = created_while_moving(&mut r, 3);
        assert_eq!(steady, 0, "{scene:?} with {indirect:?}: bind groups made in 3 steady frames");
    }
}
