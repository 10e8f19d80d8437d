//! Emissive triangles as lights: next-event estimation of area emitters.
//!
//! An emitter is chosen in proportion to its power (`Y(emission) * area`, doubled when it
//! emits from both sides) from an **alias table** (A. J. Walker, "An efficient method for
//! generating discrete random variables with general distributions", ACM TOMS 1977; built
//! with M. D. Vose's stable method, IEEE TSE 1991): constant time per sample whatever the
//! number of emitters, and the probability of any triangle is a table look-up, which the
//! BRDF-sampled side of multiple importance sampling needs when a path hits an emitter.
//! A point on the chosen triangle is then uniform in area, so the density of a point `y` on
//! triangle `t` is `P(t) / A(t)`, and in solid angle at `x`: `P(t) / A(t) |x - y|^2 / |cos_y|`.
//! A textured emitter's power is its material's emission, which bounds the textures'
//! (`Material::emission`), and the radiance of a sampled point is the textures' there
//! (`World::emitted_at`): every point that emits has a positive density, so the estimate
//! stays unbiased; only its variance depends on how tight the bound is.

use crate::rng::Rng;
use crate::sampling::luminance;
use crate::world::World;
use glam::{Vec2, Vec3};

/// Walker's alias table over `n` outcomes.
#[derive(Clone, Debug, Default)]
pub(crate) struct AliasTable {
    /// Probability of keeping bucket `i` (otherwise its alias).
    keep: Vec<f32>,
    alias: Vec<u32>,
    /// The normalised probabilities.
    pmf: Vec<f32>,
}

impl AliasTable {
    /// A table for non-negative `weights`; `None` when they sum to zero (or are not finite).
    pub fn new(weights: &[f64]) -> Option<Self> {
        let total: f64 = weights.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let n = weights.len();
        let pmf: Vec<f32> = weights.iter().map(|w| (w / total) as f32).collect();
        let mut scaled: Vec<f64> = weights.iter().map(|w| w / total * n as f64).collect();
        let mut keep = vec![1.0f32; n];
        let mut alias: Vec<u32> = (0..n as u32).collect();
        let (mut small, mut large): (Vec<usize>, Vec<usize>) =
            (0..n).partition(|&i| scaled[i] < 1.0);
        while let (Some(s), Some(&l)) = (small.pop(), large.last()) {
            keep[s] = scaled[s] as f32;
            alias[s] = l as u32;
            scaled[l] -= 1.0 - scaled[s];
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // What is left (rounding) keeps itself with probability one.
        Some(Self { keep, alias, pmf })
    }

    /// An outcome for `u` (chooses the bucket) and `v` (keep it or take its alias), both
    /// uniform in `[0, 1)`: two numbers, so the coin keeps full precision with many buckets.
    pub fn sample(&self, u: f32, v: f32) -> usize {
        let n = self.keep.len();
        let i = ((u * n as f32) as usize).min(n - 1);
        if v < self.keep[i] { i } else { self.alias[i] as usize }
    }

    /// Probability of outcome `i`.
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf[i]
    }
}

/// The emissive triangles of a world and the table that chooses among them.
#[derive(Clone, Debug, Default)]
pub(crate) struct Emitters {
    /// Triangle ids of the emitters.
    triangles: Vec<u32>,
    table: Option<AliasTable>,
    /// Per world triangle: the area density `P(t) / A(t)` of a sampled point on it (zero for
    /// triangles that are never sampled).
    area_pdf: Vec<f32>,
}

impl Emitters {
    /// Collects the emitters from per-triangle `(corners, emission, double_sided)`.
    pub fn new(tris: impl ExactSizeIterator<Item = ([Vec3; 3], Vec3, bool)>) -> Self {
        let count = tris.len();
        let mut triangles = Vec::new();
        let mut weights = Vec::new();
        let mut areas = Vec::new();
        for (t, ([a, b, c], emission, two)) in tris.enumerate() {
            let area = 0.5 * (b - a).cross(c - a).length();
            let power = luminance(emission) as f64 * area as f64 * if two { 2.0 } else { 1.0 };
            if power > 0.0 && power.is_finite() {
                triangles.push(t as u32);
                weights.push(power);
                areas.push(area);
            }
        }
        let table = AliasTable::new(&weights);
        let mut area_pdf = Vec::new();
        if let Some(tab) = &table {
            area_pdf = vec![0.0; count];
            for (k, &t) in triangles.iter().enumerate() {
                area_pdf[t as usize] = tab.pmf(k) / areas[k];
            }
        }
        Self { triangles, table, area_pdf }
    }

    /// True when there is something to sample.
    pub fn any(&self) -> bool {
        self.table.is_some()
    }

    /// Number of emissive triangles.
    pub fn count(&self) -> usize {
        self.triangles.len()
    }

    /// Area density of a sampled point on `triangle` (zero when it is no emitter).
    pub fn area_pdf(&self, triangle: u32) -> f32 {
        self.area_pdf.get(triangle as usize).copied().unwrap_or(0.0)
    }

    /// A triangle and barycentrics `(b1, b2)` of a point uniform in its area.
    fn sample(&self, rng: &mut Rng) -> Option<(u32, Vec2)> {
        let (u, v) = rng.next_2d();
        let t = self.triangles[self.table.as_ref()?.sample(u, v)];
        let (u0, u1) = rng.next_2d();
        let su = u0.sqrt();
        Some((t, Vec2::new(u1 * su, 1.0 - su)))
    }
}

/// One sampled emitter point as seen from a shading point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EmitterSample {
    /// Unit direction from the shading point towards the emitter point.
    pub wi: Vec3,
    /// The emitter point.
    pub point: Vec3,
    /// Emitted radiance towards the shading point (unoccluded).
    pub radiance: Vec3,
    /// Solid-angle density of `wi` at the shading point.
    pub pdf: f32,
}

/// Samples a point on an emitter seen from `p` (power-proportional triangle, uniform area)
/// and traces the shadow ray. `None` when there are no emitters or the sample carries no
/// light (back of a one-sided emitter, an alpha-tested hole, occluded).
pub(crate) fn sample_emitter(world: &World, p: Vec3, rng: &mut Rng) -> Option<EmitterSample> {
    let (t, bary) = world.emitters().sample(rng)?;
    let [a, b, c] = world.triangle(t);
    let y = a * (1.0 - bary.x - bary.y) + b * bary.x + c * bary.y;
    let d = y - p;
    let dist2 = d.length_squared();
    if !(dist2 > 0.0) {
        return None;
    }
    let dist = dist2.sqrt();
    let wi = d / dist;
    let ny = world.normal(t);
    let cos_y = -ny.dot(wi);
    let radiance = world.emitted_at(t, bary, cos_y > 0.0);
    if cos_y == 0.0 || radiance == Vec3::ZERO || !world.passes_alpha(t, bary) {
        return None;
    }
    let pdf = world.emitters().area_pdf(t) * dist2 / cos_y.abs();
    if !(pdf > 0.0 && pdf.is_finite()) {
        return None;
    }
    Some(EmitterSample { wi, point: y, radiance, pdf })
}

/// Shadow ray from `p` (normal `n`) to a sampled emitter point (separate from
/// [`sample_emitter`] so a caller skips it when the BRDF is zero there). The ray is aimed
/// from the offset origin at the point itself: a ray along `wi` from the offset origin runs
/// parallel to the true segment and, at grazing angles, meets the emitter's own plane
/// before its end (the light would shadow itself).
pub(crate) fn visible(world: &World, p: Vec3, n: Vec3, s: &EmitterSample) -> bool {
    let o = world.offset(p, n, s.wi);
    let d = s.point - o;
    let len = d.length();
    let t = len * (1.0 - 1e-4) - world.epsilon();
    t > 0.0 && !world.occluded(o, d / len, t)
}

/// Solid-angle density with which [`sample_emitter`] would have chosen the point hit at `h`
/// seen from `from` (zero for triangles that are not sampled).
pub(crate) fn emitter_pdf(world: &World, from: Vec3, hit: Vec3, triangle: u32) -> f32 {
    let a = world.emitters().area_pdf(triangle);
    if !(a > 0.0) {
        return 0.0;
    }
    let d = hit - from;
    let dist2 = d.length_squared();
    let cos = world.normal(triangle).dot(d).abs() / dist2.sqrt();
    if !(cos > 0.0) { 0.0 } else { a * dist2 / cos }
}

/// Balance heuristic weight of a strategy with density `a` against one with density `b`
/// (E. Veach and L. Guibas, SIGGRAPH 1995), the same heuristic the materials use between
/// their lobes.
pub(crate) fn balance(a: f32, b: f32) -> f32 {
    if a + b > 0.0 { a / (a + b) } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alias_table_reproduces_its_weights() {
        let w = [1.0, 0.0, 3.0, 0.5, 5.5];
        let tab = AliasTable::new(&w).unwrap();
        let n = 200_000;
        let mut counts = [0u32; 5];
        let mut rng = Rng::for_sample(3, 0, 0);
        for _ in 0..n {
            let (u, v) = rng.next_2d();
            counts[tab.sample(u, v)] += 1;
        }
        for (i, &c) in counts.iter().enumerate() {
            let p = w[i] / 10.0;
            let se = (p * (1.0 - p) / n as f64).sqrt();
            assert!((c as f64 / n as f64 - p).abs() < 5.0 * se + 1e-9, "{i}: {c}");
            assert!((tab.pmf(i) as f64 - p).abs() < 1e-6);
        }
        assert!(AliasTable::new(&[0.0, 0.0]).is_none());
    }
}
