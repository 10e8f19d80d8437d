//! The cascaded volume: placement, update (inject + propagate per cascade) and lookup.

use crate::error::LpvError;
use crate::geometry::GeometryVolume;
use crate::grid::{Grid, Volume};
use crate::inject::{InjectStats, inject};
use crate::lookup::{CellMajor, cascade_weight, irradiance_from, radiance_from, sample_trilinear};
use crate::propagate::propagate;
use crate::settings::LpvSettings;
use crate::vpl::{Surfel, Vpl};
use glam::Vec3;

/// One cascade: where it is, its accumulated light, and its geometry volume (when on).
#[derive(Clone, Debug, PartialEq)]
pub struct Cascade {
    pub grid: Grid,
    /// Injected + propagated intensity, summed over all iterations (what lookups read).
    pub volume: Volume,
    /// The blocking potential used by the last update (`None` with the geometry volume off).
    pub geometry: Option<GeometryVolume>,
}

/// What the last [`Lpv::update`] did, per cascade.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UpdateStats {
    pub injected: Vec<InjectStats>,
}

/// Cascaded light propagation volumes.
#[derive(Clone, Debug, PartialEq)]
pub struct Lpv {
    settings: LpvSettings,
    cascades: Vec<Cascade>,
    /// Each cascade's volume cell-major, for the CPU lookup (rebuilt by every update).
    tables: Vec<CellMajor>,
}

impl Lpv {
    /// Empty cascades centred on the world origin.
    pub fn new(settings: LpvSettings) -> Result<Self, LpvError> {
        settings.validate()?;
        let cascades = (0..settings.cascades)
            .map(|i| Cascade {
                grid: Grid::snapped(Vec3::ZERO, settings.cell_size(i), settings.resolution),
                volume: Volume::new(settings.resolution),
                geometry: None,
            })
            .collect::<Vec<_>>();
        let tables = cascades.iter().map(|c| CellMajor::from_volume(&c.volume)).collect();
        Ok(Self { settings, cascades, tables })
    }

    pub fn settings(&self) -> &LpvSettings {
        &self.settings
    }

    pub fn cascades(&self) -> &[Cascade] {
        &self.cascades
    }

    #[cfg(feature = "gpu")]
    pub(crate) fn cascades_mut(&mut self) -> &mut [Cascade] {
        &mut self.cascades
    }

    /// Re-centres every cascade on `camera`, snapped to its own whole cells (the lattice
    /// never moves by a fraction of a cell). Takes effect at the next [`Lpv::update`]; a
    /// cascade whose origin changes is cleared. Non-finite positions are ignored.
    pub fn follow(&mut self, camera: Vec3) {
        if !camera.is_finite() {
            return;
        }
        for (c, t) in self.cascades.iter_mut().zip(&mut self.tables) {
            let g = Grid::snapped(camera, c.grid.cell_size, c.grid.res);
            if g != c.grid {
                c.grid = g;
                c.volume.clear();
                c.geometry = None;
                t.cells.fill([0.0; crate::grid::COEFFS]);
            }
        }
    }

    /// The sphere around the coarsest cascade (centre, radius: half its diagonal), in `f64`:
    /// the region a light's reflective shadow map must cover for this LPV after it
    /// [`Lpv::follow`]ed the camera (texels outside it would be dropped by every cascade).
    pub fn bounce_region(&self) -> (glam::DVec3, f64) {
        let grid = self.cascades.last().expect("validated settings have a cascade").grid;
        let half = grid.extent() as f64 * 0.5;
        let center = grid.origin.as_dvec3() + glam::DVec3::splat(half);
        (center, half * 3f64.sqrt())
    }

    /// Rebuilds the light of every cascade: injects `vpls`, builds the geometry volume from
    /// `surfels` (when the setting is on), and propagates `iterations` steps.
    pub fn update(&mut self, vpls: &[Vpl], surfels: &[Surfel]) -> UpdateStats {
        let mut stats = UpdateStats::default();
        let (iterations, gv_on) = (self.settings.iterations, self.settings.geometry_volume);
        for c in &mut self.cascades {
            let mut initial = Volume::new(c.grid.res);
            stats.injected.push(inject(&c.grid, vpls, &mut initial));
            c.geometry = gv_on.then(|| GeometryVolume::build(&c.grid, surfels));
            let faces = c.geometry.as_ref().map(GeometryVolume::faces);
            c.volume = propagate(&initial, iterations, faces.as_ref());
        }
        self.refresh_tables();
        stats
    }

    /// Rebuilds the lookup tables from the volumes (after an update).
    pub(crate) fn refresh_tables(&mut self) {
        use rayon::prelude::*;
        self.cascades
            .par_iter()
            .map(|c| CellMajor::from_volume(&c.volume))
            .collect_into_vec(&mut self.tables);
    }

    /// Blend weight of each cascade at `p` (finest first; they sum to at most 1, and to 0
    /// outside every cascade).
    pub fn cascade_weights(&self, p: Vec3) -> [f32; LpvSettings::MAX_CASCADES as usize] {
        let mut w = [0.0; LpvSettings::MAX_CASCADES as usize];
        let mut rest = 1.0f32;
        for (i, c) in self.cascades.iter().enumerate() {
            let wi = cascade_weight(&c.grid, p, self.settings.blend_cells);
            w[i] = rest * wi;
            rest *= 1.0 - wi;
            if rest <= 0.0 {
                break;
            }
        }
        w
    }

    /// Indirect irradiance at `p` on a surface with normal `normal` (normalised here; a
    /// zero normal reads the direction-averaged irradiance `pi * L0`). Trilinear inside each
    /// cascade, the finest cascade that holds `p` blended into the next coarser one at its
    /// border; zero outside every cascade. Non-negative by construction (every stored lobe
    /// satisfies `|band 1| <= band 0`, so `E >= pi a / 3 >= 0`; float rounding aside).
    pub fn irradiance(&self, p: Vec3, normal: Vec3) -> Vec3 {
        let n = sh_math::normalize_dir(normal).unwrap_or(Vec3::ZERO);
        let w = self.cascade_weights(p);
        let mut e = Vec3::ZERO;
        for ((c, t), &wi) in self.cascades.iter().zip(&self.tables).zip(&w) {
            if wi > 0.0 {
                let h = c.grid.cell_size;
                let q = p + n * (self.settings.lookup_offset_cells * h);
                e += wi * irradiance_from(&t.sample(&c.grid, q), n, h);
            }
        }
        e
    }

    /// Radiance arriving at `p` from direction `from` (normalised here), with the same
    /// cascade blending as [`Lpv::irradiance`].
    pub fn radiance(&self, p: Vec3, from: Vec3) -> Vec3 {
        let Some(d) = sh_math::normalize_dir(from) else { return Vec3::ZERO };
        let w = self.cascade_weights(p);
        let mut l = Vec3::ZERO;
        for (c, &wi) in self.cascades.iter().zip(&w) {
            if wi > 0.0 {
                let h = c.grid.cell_size;
                l += wi * radiance_from(&sample_trilinear(&c.grid, &c.volume, p), d, h);
            }
        }
        l
    }

    /// Glossy lookup (the thesis used the LPV for glossy reflections): the mean radiance
    /// arriving from the reflection direction `reflect` at `steps` points marched along it
    /// from `p`, one finest-cascade cell apart (from half a cell), so the lookup reads the
    /// light of the region the reflection sees rather than only the surface's own cell.
    pub fn glossy(&self, p: Vec3, reflect: Vec3, steps: u32) -> Vec3 {
        let Some(r) = sh_math::normalize_dir(reflect) else { return Vec3::ZERO };
        let h = self.cascades[0].grid.cell_size;
        let steps = steps.max(1);
        let sum: Vec3 = (0..steps).map(|k| self.radiance(p + r * ((k as f32 + 0.5) * h), r)).sum();
        sum / steps as f32
    }

    /// Checks the invariants: settings valid, one cascade per setting, grids snapped to
    /// whole cells, volumes of the right size, finite, and non-negative lobes.
    pub fn validate(&self) -> Result<(), LpvError> {
        self.settings.validate()?;
        let bad = |s: String| Err(LpvError::Invariant(s));
        if self.cascades.len() != self.settings.cascades as usize {
            return bad(format!(
                "{} cascades, settings say {}",
                self.cascades.len(),
                self.settings.cascades
            ));
        }
        for (i, c) in self.cascades.iter().enumerate() {
            let g = &c.grid;
            if g.res != self.settings.resolution || c.volume.res != g.res {
                return bad(format!("cascade {i}: resolution mismatch"));
            }
            if c.volume.data.len() != g.cells() * crate::grid::COEFFS {
                return bad(format!("cascade {i}: storage of {} floats", c.volume.data.len()));
            }
            let k = g.origin / g.cell_size;
            if (k - k.round()).abs().max_element() > 1e-3 {
                return bad(format!("cascade {i}: origin {} not on whole cells", g.origin));
            }
            if !c.volume.is_finite() {
                return bad(format!("cascade {i}: non-finite coefficients"));
            }
            if !c.volume.lobes_non_negative(1e-4) {
                return bad(format!("cascade {i}: a lobe is negative somewhere"));
            }
            if let Some(gv) = &c.geometry
                && (gv.res != g.res || !gv.is_finite())
            {
                return bad(format!("cascade {i}: bad geometry volume"));
            }
        }
        Ok(())
    }
}
