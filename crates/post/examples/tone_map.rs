//! Use `post` in your renderer: keep one `ToneMapper` for the life of the view, and each frame
//! hand it the HDR frame and the seconds since the last one; it returns the sRGB RGBA8 image
//! to show. Here a synthetic 64x32 frame (a bright sky over a darker ground) is shown for a
//! few frames, then the sun sets (the frame gets 50 times darker) and the eye adapts.
//!
//! `cargo run -p serein-post --example tone_map`

use post::{Exposure, ToneMapper, log_average};

fn frame(brightness: f32) -> Vec<[f32; 4]> {
    (0..64 * 32)
        .map(|i| {
            let sky = i / 64 < 16;
            let c = if sky { [3.0, 3.5, 5.0] } else { [0.3, 0.25, 0.2] };
            [c[0] * brightness, c[1] * brightness, c[2] * brightness, 1.0]
        })
        .collect()
}

fn main() {
    let mut eye = ToneMapper::default();
    let mut exposure = Exposure { dt: 0.0, rate: 1.5, key: 0.18, reset: true, raw: false };
    for k in 0..40 {
        let hdr = frame(if k < 10 { 1.0 } else { 0.02 });
        let ldr = eye.tone_map(&hdr, &exposure);
        if k % 5 == 0 || k == 10 {
            // The first sky pixel and the first ground pixel, as displayed (sRGB 0..255).
            let (sky, ground) = (&ldr[0..3], &ldr[(16 * 64) * 4..(16 * 64) * 4 + 3]);
            println!(
                "frame {k:2}: scene log-average {:.4}, eye adapted to {:.4}, sky {sky:?}, ground {ground:?}",
                log_average(&hdr),
                eye.adapted().unwrap_or(0.0)
            );
        }
        // Every later frame adapts gradually: 60 frames per second.
        exposure = Exposure { dt: 1.0 / 60.0, reset: false, ..exposure };
    }
}
