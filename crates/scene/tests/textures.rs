//! Textures: sRGB decoding, mip chains of any size (1x1, non-power-of-two), mean preservation,
//! bilinear / trilinear sampling.

mod common;

use glam::{Vec2, Vec4};
use proptest::prelude::*;
use scene::{ColorSpace, Texture, Wrap, linear_to_srgb, srgb_to_linear};

#[test]
fn srgb_decoding_matches_the_standard() {
    assert_eq!(srgb_to_linear(0.0), 0.0);
    assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
    assert!((srgb_to_linear(128.0 / 255.0) - 0.215_860_5).abs() < 1e-6);
    assert!((srgb_to_linear(10.0 / 255.0) - 10.0 / 255.0 / 12.92).abs() < 1e-7);
    for i in 0..=255 {
        let c = i as f32 / 255.0;
        assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-5);
    }
    // Alpha is never gamma-decoded; Linear textures are kept as they are.
    let t = Texture::from_rgba8("t", 1, 1, &[128, 128, 128, 128], ColorSpace::Srgb).unwrap();
    assert!((t.levels[0].texels[0].w - 128.0 / 255.0).abs() < 1e-6);
    let t = Texture::from_rgba8("t", 1, 1, &[128, 128, 128, 128], ColorSpace::Linear).unwrap();
    assert!((t.levels[0].texels[0].x - 128.0 / 255.0).abs() < 1e-6);
}

#[test]
fn one_by_one_texture_has_one_level_and_samples_its_colour_everywhere() {
    let c = Vec4::new(0.2, 0.4, 0.6, 1.0);
    let t = Texture::solid("c", c).unwrap();
    t.validate().unwrap();
    assert_eq!(t.levels.len(), 1);
    for uv in [Vec2::ZERO, Vec2::new(0.99, 0.3), Vec2::new(-7.5, 12.25), Vec2::NAN] {
        assert!((t.sample_bilinear(uv, 0) - c).length() < 1e-6);
        assert!((t.sample_trilinear(uv, 3.7) - c).length() < 1e-6);
    }
}

#[test]
fn bad_sizes_are_errors() {
    let invalid = |r: Result<Texture, scene::SceneError>, name: &str, why: &str| match r {
        Err(scene::SceneError::Invalid { element, reason }) => {
            assert!(element.contains(name) && reason.contains(why), "{element}: {reason}")
        }
        other => panic!("{name}: expected an invalid-texture error, got {other:?}"),
    };
    invalid(Texture::from_rgba8("z", 0, 4, &[], ColorSpace::Srgb), "z", "0");
    invalid(Texture::from_rgba8("short", 2, 2, &[0; 15], ColorSpace::Srgb), "short", "15 bytes");
    invalid(Texture::from_linear("nan", 1, 1, vec![Vec4::NAN]), "nan", "");
}

#[test]
fn bilinear_interpolates_between_texel_centres_and_clamp_mode_holds_edges() {
    let mut t = Texture::from_linear("g", 2, 1, vec![Vec4::ZERO, Vec4::ONE]).unwrap();
    // Texel centres at u = 0.25 and 0.75; halfway is the mean.
    assert!((t.sample_bilinear(Vec2::new(0.5, 0.5), 0).x - 0.5).abs() < 1e-6);
    assert!((t.sample_bilinear(Vec2::new(0.25, 0.5), 0).x).abs() < 1e-6);
    // Repeat wraps: u = 0 is halfway between the last and the first texel.
    assert!((t.sample_bilinear(Vec2::new(0.0, 0.5), 0).x - 0.5).abs() < 1e-6);
    t.wrap = [Wrap::Clamp; 2];
    assert!(t.sample_bilinear(Vec2::new(0.0, 0.5), 0).x.abs() < 1e-6);
    // Trilinear halfway between level 0 (at u = 0.75: 1.0) and level 1 (the mean, 0.5).
    assert!((t.sample_trilinear(Vec2::new(0.75, 0.5), 0.5).x - 0.75).abs() < 1e-6);
    // The LOD rule: a footprint of 2 texels is level 1.
    assert!((t.lod(Vec2::new(1.0, 0.0), Vec2::ZERO) - 1.0).abs() < 1e-6);
}

/// Mirrored repeat reads the texture backwards in every other copy; nearest magnification
/// reads the texel under the point, with no blend: on a 4-texel ramp 0, 1/3, 2/3, 1.
#[test]
fn mirror_wrap_and_nearest_magnification_read_the_texels_they_name() {
    let ramp: Vec<Vec4> = (0..4).map(|i| Vec4::splat(i as f32 / 3.0)).collect();
    let mut t = Texture::from_linear("ramp", 4, 1, ramp).unwrap();
    t.wrap = [Wrap::Mirror, Wrap::Clamp];
    t.magnify = scene::Filter::Nearest;
    let at = |u: f32| t.sample_bilinear(Vec2::new(u, 0.5), 0).x;
    // Texel 1 at u = 0.3; the mirrored copy puts texel 1 at u = 1.7 and texel 3 at 1.1;
    // the copy before it (u < 0) is mirrored too: u = -0.3 is texel 1.
    for (u, want) in [(0.3, 1.0 / 3.0), (1.7, 1.0 / 3.0), (1.1, 1.0), (-0.3, 1.0 / 3.0)] {
        assert!((at(u) - want).abs() < 1e-6, "u {u}: {} against {want}", at(u));
    }
    // Linear magnification blends across the mirror's seam at u = 1: texel 3 twice.
    t.magnify = scene::Filter::Linear;
    assert!((t.sample_bilinear(Vec2::new(1.0, 0.5), 0).x - 1.0).abs() < 1e-6);
    // Between texels 0 and 1 at u = 0.25.
    assert!((t.sample_bilinear(Vec2::new(0.25, 0.5), 0).x - 1.0 / 6.0).abs() < 1e-6);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(48)))]

    /// Any size (non-powers of two included): sizes halve (rounded down) to 1x1, and every
    /// level keeps the image's mean (the box filter is exactly area-weighted).
    #[test]
    fn mip_chain_has_the_right_sizes_and_keeps_the_mean(w in 1u32..70, h in 1u32..70, seed in any::<u64>()) {
        let mut x = seed | 1;
        let texels: Vec<Vec4> = (0..w * h).map(|_| {
            x ^= x << 13; x ^= x >> 7; x ^= x << 17;
            Vec4::new((x % 1000) as f32 / 999.0, ((x >> 10) % 1000) as f32 / 999.0, 0.5, 1.0)
        }).collect();
        let t = Texture::from_linear("r", w, h, texels).unwrap();
        t.validate().unwrap();
        let expect = 1 + (w.max(h) as f32).log2().floor() as usize;
        prop_assert_eq!(t.levels.len(), expect);
        let mean = |l: &scene::TextureLevel| l.texels.iter().copied().sum::<Vec4>() / l.texels.len() as f32;
        let m0 = mean(&t.levels[0]);
        for l in &t.levels {
            prop_assert!((mean(l) - m0).abs().max_element() < 1e-4, "{} vs {}", mean(l), m0);
            prop_assert!(l.texels.iter().all(|p| p.min_element() >= -1e-6 && p.max_element() <= 1.0 + 1e-6));
        }
        let last = t.levels.last().unwrap();
        prop_assert_eq!((last.width, last.height), (1, 1));
        // Sampling stays within the range of the texels, at any uv and lod.
        let s = t.sample_trilinear(Vec2::new(seed as f32 * 1e-9, 0.37), (seed % 9) as f32 * 0.7);
        prop_assert!(s.is_finite() && s.min_element() >= -1e-5 && s.max_element() <= 1.0 + 1e-5);
    }
}
