//! A generated block of buildings as occlusion quads, for examples, tests and benchmarks
//! (seeded; no dependency on `scene`).

use crate::{OcclusionQuad, VolumeGrid};
use glam::Vec3;

/// `quads / 4` box-shaped buildings (four walls each, no roofs, as the thesis's Fig. 5.13
/// fits walls to buildings) standing on the grid's floor, spread over its footprint on a
/// jittered lattice so that they do not overlap; heights from 6 m up to 80% of the grid's
/// height. `quads` is rounded down to a multiple of 4.
pub fn generated_city(grid: &VolumeGrid, quads: usize, seed: u64) -> Vec<OcclusionQuad> {
    let mut state = seed ^ 0x5DEE_CE66_D1CE_4E5B;
    let mut rnd = move || {
        state =
            state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        ((state >> 40) as f32) / (1u64 << 24) as f32
    };
    let buildings = quads / 4;
    let lo = grid.origin;
    let hi = grid.max_corner();
    let size = hi - lo;
    let cells = (buildings as f32).sqrt().ceil().max(1.0) as usize;
    let cell = Vec3::new(size.x / cells as f32, 0.0, size.z / cells as f32);
    let mut out = Vec::with_capacity(buildings * 4);
    for b in 0..buildings {
        let (cx, cz) = (b % cells, b / cells);
        let half = Vec3::new(cell.x * (0.2 + 0.15 * rnd()), 0.0, cell.z * (0.2 + 0.15 * rnd()));
        let slack = Vec3::new(cell.x * 0.5 - half.x, 0.0, cell.z * 0.5 - half.z);
        let centre = Vec3::new(
            lo.x + (cx as f32 + 0.5) * cell.x + (rnd() * 2.0 - 1.0) * slack.x * 0.8,
            0.0,
            lo.z + (cz as f32 + 0.5) * cell.z + (rnd() * 2.0 - 1.0) * slack.z * 0.8,
        );
        let height = 6.0 + rnd() * (0.8 * size.y - 6.0).max(0.0);
        let min = Vec3::new(centre.x - half.x, lo.y - 0.5, centre.z - half.z);
        let max = Vec3::new(centre.x + half.x, lo.y + height, centre.z + half.z);
        out.extend(OcclusionQuad::box_walls(min, max));
    }
    out
}
