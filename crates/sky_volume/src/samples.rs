//! The sample directions of one volume: Saff-Kuijlaars points on the upper hemisphere
//! (thesis 5.3.4, 100 by default), **sorted by height** so that the directions a quad can
//! cover from a point (an elevation band) are one contiguous index range.

use glam::Vec3;
use sh_math::{Sh3, eval_basis, saff_kuijlaars_hemisphere};

#[derive(Clone, Debug)]
pub(crate) struct SamplePlan {
    pub dirs: Vec<Vec3>,
    /// `dirs[i].y`, ascending.
    pub ys: Vec<f32>,
    /// Solid angle per sample, `2 pi / n`.
    pub weight: f32,
    /// 3-band basis at each direction.
    pub basis: Vec<Sh3>,
}

impl SamplePlan {
    pub fn new(n: usize) -> Self {
        let set = saff_kuijlaars_hemisphere(n, Vec3::Y);
        let mut dirs = set.dirs;
        // Every direction strictly above the horizon (the set is built so; rotation error aside).
        for d in &mut dirs {
            if d.y <= 0.0 {
                *d = Vec3::new(d.x, 1e-6, d.z).normalize();
            }
        }
        dirs.sort_by(|a, b| a.y.total_cmp(&b.y));
        let ys = dirs.iter().map(|d| d.y).collect();
        let basis = dirs.iter().map(|d| eval_basis::<9>(*d)).collect();
        let weight = std::f32::consts::TAU / n.max(1) as f32;
        Self { dirs, ys, weight, basis }
    }

    pub fn len(&self) -> usize {
        self.dirs.len()
    }

    /// Bytes of one visibility mask (one bit per sample, padded to whole bytes).
    pub fn mask_bytes(&self) -> usize {
        self.len().div_ceil(8)
    }

    /// Index range of the samples with `lo <= y <= hi`.
    pub fn range(&self, lo: f32, hi: f32) -> (usize, usize) {
        (self.ys.partition_point(|&y| y < lo), self.ys.partition_point(|&y| y <= hi))
    }
}
