//! G-buffer channel views: the lighting pass writes the channel's value, the display shows
//! it without exposure or tone curve, and switching back to the frame gives the frame again.

mod common;

use engine::{Channel, View};

fn srgb8(c: f32) -> f32 {
    scene::linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0
}

#[test]
fn channel_views_show_the_gbuffer_as_it_is() {
    let Some(mut r) = common::generated(scene::Generated::PlaneBox, 64, 36) else { return };
    r.set_fixed_frame_time(Some(0.0));
    let frame = r.render_frame().expect("frame");

    r.set_view(View::Channel(Channel::ShadingNormal));
    let normals = r.render_frame().expect("normal view");
    let mut covered = 0;
    let mut up = 0;
    for px in &normals.hdr.pixels {
        if px[..3] == [0.0; 3] {
            continue; // background
        }
        covered += 1;
        let n = [0, 1, 2].map(|k| 2.0 * px[k] - 1.0);
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 0.02, "normal view {px:?} is not a unit normal");
        up += usize::from(n[1] > 0.99);
    }
    assert!(covered > 100 && up > 50, "{covered} covered pixels, {up} facing up (the floor)");

    // Raw display: the LDR image is the sRGB encoding of the clamped values.
    r.set_view(View::Channel(Channel::BaseColor));
    let albedo = r.render_frame().expect("albedo view");
    assert_eq!(r.view(), View::Channel(Channel::BaseColor));
    for (px, ldr) in albedo.hdr.pixels.iter().zip(albedo.ldr.chunks(4)) {
        assert!(px[..3].iter().all(|c| (0.0..=1.0).contains(c)), "albedo {px:?}");
        for k in 0..3 {
            assert!((srgb8(px[k]) - ldr[k] as f32).abs() <= 1.0, "{px:?} shown as {ldr:?}");
        }
    }
    r.set_view(View::Channel(Channel::Depth));
    let depth = r.render_frame().expect("depth view");
    let grey = depth.hdr.pixels.iter().all(|p| p[0] == p[1] && p[1] == p[2] && p[0] < 1.0);
    assert!(grey, "depth is grey and below 1");

    r.set_view(View::Frame);
    let back = r.render_frame().expect("frame again");
    let (a, b) = (common::hdr_stats(&frame).0, common::hdr_stats(&back).0);
    assert!((a - b).abs() <= 1e-4 * a, "frame {a} vs after the views {b}");
    assert_eq!(frame.ldr, back.ldr, "the exposure was kept through the raw views");
}
