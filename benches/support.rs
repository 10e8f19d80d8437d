//! What the root benches share: an engine on the city (or another generated scene) at
//! 320x180, brought to its steady state, and a frame whose camera moved.

use engine::{Indirect, Preset, Renderer, Settings};

/// The benches' frame size (issue 54's "320x180 on the default adapter").
pub const SIZE: (u32, u32) = (320, 180);

/// A renderer of `scene` at [`SIZE`] and `preset` with `indirect`, settled (every amortised
/// pass complete), or `None` with the reason printed when no adapter exists.
pub fn settled(scene: scene::Generated, preset: Preset, indirect: Indirect) -> Option<Renderer> {
    let settings = Settings::preset(preset, SIZE.0, SIZE.1);
    let mut r = match Renderer::new(scene.build(1), settings) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("engine benches skipped: {e}");
            return None;
        }
    };
    r.set_indirect(indirect);
    r.settle().expect("settling frames");
    Some(r)
}

/// One frame after a camera step of 1 cm (alternating), so every per-frame pass reruns;
/// returns its wall time in ms.
pub fn moving_frame(r: &mut Renderer, base: scene::Camera, step: &mut u32) -> f64 {
    *step += 1;
    let mut cam = base;
    cam.position.x += (*step % 2) as f32 * 0.01;
    r.set_camera(cam).expect("camera");
    r.render_frame().expect("frame").wall_ms
}
