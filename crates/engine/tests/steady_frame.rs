//! A steady frame creates no bind groups: every pass keeps the groups it made while the
//! resources it binds stay the same (`gpu_harness::BindGroupCache`), so a moving camera costs
//! recording and uniforms, not objects. Alone in its test binary because the count it reads
//! (`gpu_harness::bind_groups_created`) is the whole process's.

mod common;

use engine::{Indirect, Preset, Settings, TracedShading};

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

/// (scene, indirect light, sky bounce VPLs, traced hits lit on the GPU): every one-bounce
/// technique, and the two paths that light extra queries with the sky volume.
const CASES: [(scene::Generated, Indirect, u32, TracedShading); 4] = [
    (scene::Generated::City, Indirect::Rsm, 0, TracedShading::Cpu),
    (scene::Generated::CornellWindow, Indirect::Lpv, 0, TracedShading::Cpu),
    (scene::Generated::City, Indirect::Lpv, 8, TracedShading::Gpu),
    (scene::Generated::CornellWindow, Indirect::Cache, 0, TracedShading::Cpu),
];

#[test]
fn a_moving_camera_creates_no_bind_groups_once_warm() {
    for (scene, indirect, sky_bounce, traced_shading) in CASES {
        let mut settings = Settings::preset(Preset::Default, 64, 36);
        settings.indirect = indirect;
        settings.sky_bounce = sky_bounce;
        settings.traced_shading = traced_shading;
        let Some(mut r) = common::renderer(scene.build(common::SEED), settings) else { return };
        let warm = r.sky_volume_frames() as usize + 2;
        let first = created_while_moving(&mut r, warm);
        assert!(first > 0, "{scene:?}: the first frames make the bind groups");
        let steady = created_while_moving(&mut r, 3);
        let case = format!("{scene:?}, {indirect:?}, sky bounce {sky_bounce}, {traced_shading:?}");
        assert_eq!(steady, 0, "{case}: bind groups made in 3 steady frames");
    }
}
