//! [`SkyVolume`]: the grid of 3-band RGB SH, its occlusion quads, dirty tracking and the
//! amortised update that dispatches to the fill method of its [`Settings`].

use crate::fill::{
    Locals, RowCache, RowJob, build_transfer, relight_transfer, relight_visibility, sky_sh,
    sky_terms, transfer_terms,
};
use crate::samples::SamplePlan;
use crate::visibility::QuadSet;
use crate::{FillMethod, OcclusionQuad, Settings, SkyRadiance, SkyVolumeError, VolumeGrid};
use rayon::prelude::*;
use sh_math::{Sh3Rgb, ShRgb};
use std::ops::Range;

/// What has changed since the volume was last fully up to date.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dirty {
    /// Every layer is lit with the current sky and quads.
    Nothing,
    /// Some layers need re-lighting only (the sky changed; cached methods need no rays).
    SkyChanged,
    /// Some layers need their visibility (or transfer) rebuilt: quads moved, or never filled.
    QuadsMoved,
}

/// What one [`SkyVolume::update`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UpdateReport {
    /// Layers whose rays were traced (visibility or transfer rebuilt, or brute-force filled).
    pub rebuilt_layers: u32,
    /// Layers re-lit from cached visibility or transfer (no rays).
    pub relit_layers: u32,
    /// Layers still out of date after this call.
    pub remaining_layers: u32,
}

/// The sky-light irradiance volume (thesis 5.3): per grid point the sky radiance visible
/// through the occlusion quads, projected onto 3-band SH per colour channel.
#[derive(Clone, Debug)]
pub struct SkyVolume {
    pub(crate) grid: VolumeGrid,
    pub(crate) settings: Settings,
    plan: SamplePlan,
    quads: Vec<OcclusionQuad>,
    quad_set: QuadSet,
    pub(crate) probes: Vec<Sh3Rgb>,
    rows: Vec<RowCache>,
    /// Per layer: cached visibility / transfer matches the quads (always false for brute force).
    geometry_valid: Vec<bool>,
    /// Per layer: probes match the current sky and quads.
    lit: Vec<bool>,
    pub(crate) kernel: [f32; 9],
}

impl SkyVolume {
    /// An empty (all dark, every layer dirty) volume with no quads.
    pub fn new(grid: VolumeGrid, settings: Settings) -> Result<Self, SkyVolumeError> {
        grid.validate()?;
        settings.validate()?;
        let plan = SamplePlan::new(settings.samples);
        let layers = grid.dims.y as usize;
        Ok(Self {
            grid,
            settings,
            quad_set: QuadSet::new(&[], &plan),
            plan,
            quads: Vec::new(),
            probes: vec![Sh3Rgb::ZERO; grid.len()],
            rows: vec![RowCache::default(); layers * grid.dims.z as usize],
            geometry_valid: vec![false; layers],
            lit: vec![false; layers],
            kernel: crate::lookup::kernel(settings.window),
        })
    }

    /// The same, with quads.
    pub fn with_quads(
        grid: VolumeGrid,
        settings: Settings,
        quads: &[OcclusionQuad],
    ) -> Result<Self, SkyVolumeError> {
        let mut v = Self::new(grid, settings)?;
        v.set_quads(quads)?;
        Ok(v)
    }

    pub fn grid(&self) -> &VolumeGrid {
        &self.grid
    }

    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    pub fn quads(&self) -> &[OcclusionQuad] {
        &self.quads
    }

    /// The sample directions (unit, upper hemisphere, sorted by height).
    pub fn sample_directions(&self) -> &[glam::Vec3] {
        &self.plan.dirs
    }

    /// Radiance SH of every point (27 floats each: r, g, b x 9), in grid order (x fastest,
    /// then z, then y).
    pub fn probes(&self) -> &[Sh3Rgb] {
        &self.probes
    }

    /// Replaces the quads (validated: a bad quad is a typed error and changes nothing).
    /// Only layers below the top of a quad that was added, removed or moved are marked for
    /// rebuild: directions are all upward, so a quad cannot shade a point at or above it.
    pub fn set_quads(&mut self, quads: &[OcclusionQuad]) -> Result<(), SkyVolumeError> {
        SkyVolumeError::check_quads(quads)?;
        let mut top = f32::NEG_INFINITY;
        let n = self.quads.len().max(quads.len());
        for i in 0..n {
            let (old, new) = (self.quads.get(i), quads.get(i));
            if old != new {
                for q in [old, new].into_iter().flatten() {
                    top = top.max(q.top());
                }
            }
        }
        for y in 0..self.grid.dims.y {
            if self.grid.layer_height(y) < top {
                self.geometry_valid[y as usize] = false;
                self.lit[y as usize] = false;
            }
        }
        self.quads = quads.to_vec();
        self.quad_set = QuadSet::new(quads, &self.plan);
        Ok(())
    }

    /// Marks every layer for re-lighting (call when the time of day or the weather changed).
    pub fn sky_changed(&mut self) {
        self.lit.fill(false);
    }

    /// The volume's state.
    pub fn dirty(&self) -> Dirty {
        if self.lit.iter().all(|&l| l) {
            Dirty::Nothing
        } else if self.needs_rebuild().any(|b| b) {
            Dirty::QuadsMoved
        } else {
            Dirty::SkyChanged
        }
    }

    /// Layers not up to date.
    pub fn pending_layers(&self) -> u32 {
        self.lit.iter().filter(|&&l| !l).count() as u32
    }

    fn needs_rebuild(&self) -> impl Iterator<Item = bool> + '_ {
        let cached = self.settings.method != FillMethod::BruteForce;
        self.lit.iter().zip(&self.geometry_valid).map(move |(&lit, &g)| !(lit || (cached && g)))
    }

    /// Amortised update: traces rays for at most `max_rebuild_layers` out-of-date layers
    /// (lowest first) and re-lights **every** layer whose cached visibility or transfer is
    /// still valid (no rays; under a millisecond for the thesis's volume, so not budgeted).
    pub fn update(&mut self, sky: &impl SkyRadiance, max_rebuild_layers: u32) -> UpdateReport {
        let mut rebuild: Vec<bool> = self.needs_rebuild().collect();
        let mut budget = max_rebuild_layers;
        for r in &mut rebuild {
            if *r {
                if budget == 0 {
                    *r = false;
                } else {
                    budget -= 1;
                }
            }
        }
        let relight: Vec<bool> = self
            .lit
            .iter()
            .zip(&self.geometry_valid)
            .map(|(&lit, &g)| !lit && g && self.settings.method != FillMethod::BruteForce)
            .collect();
        self.process(sky, &rebuild, &relight)
    }

    /// Traces and lights the layers in `layers` now, whatever their state.
    pub fn fill_layers(
        &mut self,
        layers: Range<u32>,
        sky: &impl SkyRadiance,
    ) -> Result<UpdateReport, SkyVolumeError> {
        let ny = self.grid.dims.y;
        if layers.start > layers.end || layers.end > ny {
            return Err(SkyVolumeError::LayerOutOfRange {
                start: layers.start,
                end: layers.end,
                layers: ny,
            });
        }
        let rebuild: Vec<bool> = (0..ny).map(|y| layers.contains(&y)).collect();
        Ok(self.process(sky, &rebuild, &vec![false; ny as usize]))
    }

    /// Traces and lights the whole volume.
    pub fn fill(&mut self, sky: &impl SkyRadiance) -> UpdateReport {
        let ny = self.grid.dims.y as usize;
        self.process(sky, &vec![true; ny], &vec![false; ny])
    }

    /// Re-lights the whole volume for a new sky. With cached visibility or transfer this
    /// traces no rays (layers whose cache is invalid are rebuilt); brute force fills again.
    pub fn relight(&mut self, sky: &impl SkyRadiance) -> UpdateReport {
        self.sky_changed();
        self.update(sky, u32::MAX)
    }

    fn process(
        &mut self,
        sky: &dyn SkyRadiance,
        rebuild: &[bool],
        relight: &[bool],
    ) -> UpdateReport {
        let nx = self.grid.dims.x as usize;
        let nz = self.grid.dims.z as usize;
        let Self { grid, settings, plan, quad_set, probes, rows, .. } = self;
        let (plan, quad_set, grid) = (&*plan, &*quad_set, &*grid);
        let selected = |row: usize| {
            let y = row / nz;
            rebuild[y] || relight[y]
        };
        let job_for = |row: usize| {
            let (y, z) = ((row / nz) as u32, (row % nz) as u32);
            RowJob {
                plan,
                quads: quad_set,
                start: grid.position(glam::UVec3::new(0, y, z)),
                step: grid.spacing.x,
            }
        };
        let work = probes.par_chunks_mut(nx).zip(rows.par_iter_mut()).enumerate();
        match settings.method {
            FillMethod::BruteForce => {
                let sky = sky_terms(plan, sky);
                work.filter(|(r, _)| selected(*r))
                    .for_each_init(Locals::default, |l, (r, (out, _))| {
                        job_for(r).brute_force(&sky, out, l)
                    });
            }
            FillMethod::CachedVisibility => {
                let sky = sky_terms(plan, sky);
                let mb = plan.mask_bytes();
                work.filter(|(r, _)| selected(*r)).for_each_init(
                    Locals::default,
                    |l, (r, (out, cache))| {
                        if rebuild[r / nz] {
                            job_for(r).build_visibility(nx, cache, l);
                        }
                        relight_visibility(&sky, mb, cache, out);
                    },
                );
            }
            FillMethod::Transfer { sky_bands } => {
                let n = settings.sky_projection_samples;
                match sky_bands {
                    3 => transfer::<9, 81>(work, plan, sky, n, nx, nz, rebuild, relight, &job_for),
                    4 => {
                        transfer::<16, 144>(work, plan, sky, n, nx, nz, rebuild, relight, &job_for)
                    }
                    _ => {
                        transfer::<25, 225>(work, plan, sky, n, nx, nz, rebuild, relight, &job_for)
                    }
                }
            }
        }
        let cached = settings.method != FillMethod::BruteForce;
        let mut report = UpdateReport::default();
        for y in 0..rebuild.len() {
            if rebuild[y] {
                report.rebuilt_layers += 1;
                self.geometry_valid[y] = cached;
                self.lit[y] = true;
            } else if relight[y] {
                report.relit_layers += 1;
                self.lit[y] = true;
            }
        }
        report.remaining_layers = self.pending_layers();
        report
    }

    /// Bytes held by the cached visibility or transfer.
    pub fn cache_bytes(&self) -> usize {
        self.rows.iter().map(RowCache::bytes).sum()
    }

    /// Checks the invariants: grid, settings, quads, storage sizes, finite coefficients.
    pub fn validate(&self) -> Result<(), SkyVolumeError> {
        self.grid.validate()?;
        self.settings.validate()?;
        SkyVolumeError::check_quads(&self.quads)?;
        let bad = |s: String| Err(SkyVolumeError::Invariant(s));
        if self.probes.len() != self.grid.len() {
            return bad(format!("{} probes for {} points", self.probes.len(), self.grid.len()));
        }
        if self.plan.len() != self.settings.samples {
            return bad("sample set does not match the settings".into());
        }
        if let Some(i) = self.probes.iter().position(|p| !p.is_finite()) {
            return bad(format!("probe {i} is not finite"));
        }
        let nx = self.grid.dims.x as usize;
        let nz = self.grid.dims.z as usize;
        for (y, &valid) in self.geometry_valid.iter().enumerate() {
            if !valid {
                continue;
            }
            for row in &self.rows[y * nz..(y + 1) * nz] {
                let ok = match self.settings.method {
                    FillMethod::BruteForce => false,
                    FillMethod::CachedVisibility => {
                        row.masks.len() == nx * self.plan.mask_bytes()
                            && row.partial_start.len() == nx + 1
                    }
                    FillMethod::Transfer { sky_bands } => {
                        row.transfer.len() == nx * 9 * (sky_bands * sky_bands) as usize
                            && row.tinted_index.len() == nx
                    }
                };
                if !ok {
                    return bad(format!("layer {y}: cache does not match the method"));
                }
            }
        }
        Ok(())
    }
}

#[allow(clippy::too_many_arguments)]
fn transfer<'a, const K: usize, const W: usize>(
    work: impl ParallelIterator<Item = (usize, (&'a mut [Sh3Rgb], &'a mut RowCache))>,
    plan: &SamplePlan,
    sky: &dyn SkyRadiance,
    projection_samples: usize,
    nx: usize,
    nz: usize,
    rebuild: &[bool],
    relight: &[bool],
    job_for: &(dyn Fn(usize) -> RowJob<'a> + Sync),
) {
    let sky: ShRgb<K> = sky_sh(sky, projection_samples);
    let terms = rebuild.iter().any(|&b| b).then(|| transfer_terms::<K, W>(plan));
    work.filter(|(r, _)| rebuild[r / nz] || relight[r / nz]).for_each_init(
        Locals::default,
        |l, (r, (out, cache))| {
            if let Some(terms) = &terms
                && rebuild[r / nz]
            {
                build_transfer::<K, W>(&job_for(r), terms, nx, cache, l);
            }
            relight_transfer::<K, W>(&sky, cache, out);
        },
    );
}
