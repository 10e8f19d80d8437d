//! Zero-area triangles in the CPU rasteriser (issue 22): repeated vertices, collinear
//! vertices, slivers exactly edge-on to the light and triangles collapsed to a point, placed
//! over the scene (in front of it, on its silhouettes, through texel centres) never cover a
//! texel: the depth map and the triangle-id map are exactly those of the scene without them.

use glam::Vec3;
use proptest::prelude::*;
use shadows::plane_box::PlaneBox;
use shadows::*;

fn maps(tris: &[[Vec3; 3]], size: u32) -> (Vec<f32>, Vec<u32>) {
    let view = PlaneBox::DEFAULT.shadow_view(size);
    let mut m = DepthMap::new(size, size).unwrap();
    let mut ids = vec![NO_TRIANGLE; (size * size) as usize];
    rasterize(&mut m, Some(&mut ids), &view.view_proj_f64(), tris).unwrap();
    (m.as_slice().to_vec(), ids)
}

fn degenerate(kind: u8, a: Vec3, b: Vec3, t: f32) -> [Vec3; 3] {
    match kind % 4 {
        0 => [a, a, b],                 // a repeated vertex
        1 => [a, a + (b - a) * t, b],   // collinear
        2 => [a, a, a],                 // a point
        _ => [b, a, a + (b - a) * 2.0], // collinear, the middle vertex last
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(24)))]

    #[test]
    fn zero_area_triangles_cover_nothing(
        junk in prop::collection::vec(
            (any::<u8>(), (-3.0f32..3.0, -0.5f32..3.0, -3.0f32..3.0), (-3.0f32..3.0, -0.5f32..3.0, -3.0f32..3.0), 0.0f32..1.0),
            1..40),
        first in any::<bool>(),
    ) {
        let scene = PlaneBox::DEFAULT.triangles();
        let (depth, ids) = maps(&scene, 96);
        let bad: Vec<[Vec3; 3]> = junk
            .iter()
            .map(|&(k, a, b, t)| degenerate(k, Vec3::from(a), Vec3::from(b), t))
            .collect();
        // Degenerate triangles first shift the scene's ids; compare what they cover instead.
        let all: Vec<[Vec3; 3]> = if first {
            bad.iter().chain(&scene).copied().collect()
        } else {
            scene.iter().chain(&bad).copied().collect()
        };
        let (depth2, ids2) = maps(&all, 96);
        prop_assert_eq!(&depth, &depth2);
        let shift = if first { bad.len() as u32 } else { 0 };
        for (a, b) in ids.iter().zip(&ids2) {
            let expected = if *a == NO_TRIANGLE { NO_TRIANGLE } else { a + shift };
            prop_assert_eq!(*b, expected);
        }
    }
}

/// Only degenerate triangles: an empty map, not a panic or a division by zero.
#[test]
fn a_scene_of_only_zero_area_triangles_is_empty() {
    let (a, b) = (Vec3::new(-1.0, 0.5, 0.0), Vec3::new(1.0, 0.5, 0.25));
    let tris: Vec<[Vec3; 3]> = (0..8).map(|k| degenerate(k, a, b, 0.5)).collect();
    let (depth, ids) = maps(&tris, 64);
    assert!(depth.iter().all(|&d| d == 1.0));
    assert!(ids.iter().all(|&i| i == NO_TRIANGLE));
}
