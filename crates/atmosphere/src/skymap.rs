//! The sky map (thesis 3.6.2): the upper hemisphere's radiance stored in a paraboloid-mapped
//! square image, regenerated only when the sun has moved far enough.
//!
//! # Mapping (Heidrich & Seidel 1998, upper paraboloid)
//!
//! A unit direction `d` with `d.y >= 0` maps to the disk point `(s, t) = (d.x, d.z) / (1 + d.y)`
//! (zenith at the centre, horizon on the unit circle) and back through
//! `d = (2 s, 1 - s^2 - t^2, 2 t) / (1 + s^2 + t^2)`. Texel `(i, j)` of an `n x n` map has its
//! centre at `s = 2 (i + 0.5) / n - 1`, `t = 2 (j + 0.5) / n - 1` (row `j`, +Z down the image).
//! The map is twice as dense (per radian of elevation) at the horizon as at the zenith.
//! Texels whose centre lies outside the disk but within two texels of it hold the horizon's
//! radiance in their radial direction so that bilinear sampling is exact up to the horizon;
//! texels further out are zero. Below-horizon directions are sampled at the horizon.

use crate::{AtmosphereError, Sky, SkyViewLut};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Anything that gives the sky's radiance in a world direction (+Y up). Implemented by
/// [`SkyMap`] and by closures `Fn(Vec3) -> Vec3`.
pub trait SkyRadiance {
    /// Radiance arriving from direction `dir` (unit, pointing away from the viewer).
    fn radiance(&self, dir: Vec3) -> Vec3;
}

impl<F: Fn(Vec3) -> Vec3> SkyRadiance for F {
    fn radiance(&self, dir: Vec3) -> Vec3 {
        self(dir)
    }
}

/// How the sky map's texels are computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkyMapMethod {
    /// One full view-ray integration per texel ([`Sky::radiance`]); what the GPU shader does.
    PerTexel,
    /// Integrate a coarse [`SkyViewLut`] of phase-free integrals, then per texel a bilinear
    /// lookup and the exact phase functions (the fast CPU default).
    SkyViewLut { width: u32, height: u32 },
}

/// Knobs of the sky map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyMapSettings {
    /// Side of the square map, texels (thesis: 256).
    pub size: u32,
    pub method: SkyMapMethod,
    /// Camera altitude above the ground, km.
    pub altitude_km: f32,
    /// The map is regenerated when the sun has moved by more than this angle, radians.
    pub dirty_angle: f32,
}

impl SkyMapSettings {
    pub const fn low() -> Self {
        Self {
            size: 128,
            method: SkyMapMethod::SkyViewLut { width: 8, height: 24 },
            altitude_km: 0.0,
            dirty_angle: 0.01,
        }
    }
    /// 256 x 256, sky-view table 16 x 32 (as accurate as 64 x 128 once the phase functions
    /// are factored out: see the sweep), camera on the ground, regenerated after 0.25
    /// degree of sun motion (about a minute of time).
    pub const DEFAULT: Self = Self {
        size: 256,
        method: SkyMapMethod::SkyViewLut { width: 16, height: 32 },
        altitude_km: 0.0,
        dirty_angle: 0.0044,
    };
    pub const fn high() -> Self {
        Self {
            size: 512,
            method: SkyMapMethod::SkyViewLut { width: 64, height: 128 },
            altitude_km: 0.0,
            dirty_angle: 0.001,
        }
    }
    /// Every texel integrated on its own.
    pub const fn reference() -> Self {
        Self { size: 256, method: SkyMapMethod::PerTexel, altitude_km: 0.0, dirty_angle: 0.0 }
    }

    pub fn validate(&self) -> Result<(), AtmosphereError> {
        if !(2..=8192).contains(&self.size) {
            return Err(AtmosphereError::InvalidSetting {
                name: "size",
                value: self.size as u64,
                reason: "must be within 2..=8192",
            });
        }
        if !self.altitude_km.is_finite() {
            return Err(AtmosphereError::InvalidParameter {
                name: "altitude_km",
                value: self.altitude_km as f64,
                reason: "must be finite",
            });
        }
        if !self.dirty_angle.is_finite() || self.dirty_angle < 0.0 {
            return Err(AtmosphereError::InvalidParameter {
                name: "dirty_angle",
                value: self.dirty_angle as f64,
                reason: "must be finite and >= 0",
            });
        }
        Ok(())
    }
}

impl Default for SkyMapSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Paraboloid disk coordinates of texel `(i, j)`'s centre.
#[inline]
pub fn texel_disk(size: u32, i: u32, j: u32) -> Vec2 {
    Vec2::new(
        2.0 * (i as f32 + 0.5) / size as f32 - 1.0,
        2.0 * (j as f32 + 0.5) / size as f32 - 1.0,
    )
}

/// Unit direction of a disk point (any point; outside the unit disk it is below the
/// horizon).
#[inline]
pub fn disk_to_direction(p: Vec2) -> Vec3 {
    let q = p.length_squared();
    Vec3::new(2.0 * p.x, 1.0 - q, 2.0 * p.y) / (1.0 + q)
}

/// Disk point of an upper-hemisphere unit direction (below-horizon directions are first
/// moved to the horizon).
#[inline]
pub fn direction_to_disk(dir: Vec3) -> Vec2 {
    let d = if dir.y < 0.0 {
        Vec3::new(dir.x, 0.0, dir.z).try_normalize().unwrap_or(Vec3::X)
    } else {
        dir
    };
    Vec2::new(d.x, d.z) / (1.0 + d.y)
}

/// The direction stored in texel `(i, j)`: `Some` for texels whose centre is in the disk.
pub fn texel_direction(size: u32, i: u32, j: u32) -> Option<Vec3> {
    let p = texel_disk(size, i, j);
    (p.length_squared() <= 1.0).then(|| disk_to_direction(p))
}

/// Continuous texel coordinates of a direction (texel centres at integers).
#[inline]
pub fn direction_to_texel(size: u32, dir: Vec3) -> Vec2 {
    let p = direction_to_disk(dir);
    (p + 1.0) * 0.5 * size as f32 - 0.5
}

/// Precomputed geometry of one texel that a sky map reads (inside the disk or within the
/// bilinear margin).
#[derive(Clone, Copy, Debug)]
struct TexelGeom {
    /// Column.
    i: u32,
    /// Direction (texels in the margin: the horizon in their radial direction).
    dir: Vec3,
    /// Unit horizontal direction (0 at the zenith).
    h: Vec2,
    /// Sky-view row coordinate `sqrt(dir.y)`.
    v: f32,
}

fn texel_geometry(n: u32) -> Vec<Vec<TexelGeom>> {
    // Texels further than two texels outside the disk are never read by bilinear lookups.
    let margin = 1.0 + 4.0 / n as f32;
    (0..n)
        .into_par_iter()
        .map(|j| {
            (0..n)
                .filter_map(|i| {
                    let p = texel_disk(n, i, j);
                    let l = p.length();
                    let dir = if l > margin {
                        return None;
                    } else if l > 1.0 {
                        disk_to_direction(p / l)
                    } else {
                        disk_to_direction(p)
                    };
                    let h = Vec2::new(dir.x, dir.z).try_normalize().unwrap_or(Vec2::ZERO);
                    Some(TexelGeom { i, dir, h, v: dir.y.max(0.0).sqrt() })
                })
                .collect()
        })
        .collect()
}

/// A paraboloid-mapped sky map of the upper hemisphere.
#[derive(Clone, Debug)]
pub struct SkyMap {
    size: u32,
    texels: Vec<Vec3>,
    sun: Vec3,
    settings: SkyMapSettings,
    rows: Vec<Vec<TexelGeom>>,
}

impl SkyMap {
    /// Computes the map for the sun towards `sun` (world frame, need not be normalised).
    pub fn new(sky: &Sky, settings: SkyMapSettings, sun: Vec3) -> Result<Self, AtmosphereError> {
        settings.validate()?;
        let n = settings.size;
        let mut map = Self {
            size: n,
            texels: vec![Vec3::ZERO; (n * n) as usize],
            sun: Vec3::Y,
            settings,
            rows: texel_geometry(n),
        };
        map.compute(sky, sun)?;
        Ok(map)
    }

    /// Recomputes every texel for the sun towards `sun` (ignores the dirty rule).
    pub fn compute(&mut self, sky: &Sky, sun: Vec3) -> Result<(), AtmosphereError> {
        let sun = sun.try_normalize().filter(|s| s.is_finite()).ok_or(
            AtmosphereError::InvalidVector { name: "sun", reason: "must be finite and non-zero" },
        )?;
        let settings = self.settings;
        match settings.method {
            SkyMapMethod::PerTexel => {
                let rows = &self.rows;
                self.texels.par_chunks_mut(self.size as usize).zip(rows).for_each(|(row, geo)| {
                    for g in geo {
                        row[g.i as usize] = sky.radiance(settings.altitude_km, g.dir, sun);
                    }
                });
                self.sun = sun;
            }
            SkyMapMethod::SkyViewLut { width, height } => {
                let lut = SkyViewLut::new(sky, settings.altitude_km, sun, width, height)?;
                self.fill_from_sky_view(sky, &lut);
            }
        }
        Ok(())
    }

    /// Fills the texels from a sky-view table computed for this map's altitude (the sun is
    /// the table's).
    pub fn fill_from_sky_view(&mut self, sky: &Sky, lut: &SkyViewLut) {
        let atm = sky.atmosphere();
        let sun = lut.sun();
        let (shx, shz) = lut.sun_horizontal();
        let sh = Vec2::new(shx, shz);
        let e = atm.sun_irradiance;
        let g = atm.mie_g;
        // Cornette-Shanks as k (1 + c^2) / (a - b c)^{3/2}.
        let k = 3.0 / (8.0 * std::f32::consts::PI) * (1.0 - g * g) / (2.0 + g * g);
        let (a, b) = (1.0 + g * g, 2.0 * g);
        let kr = 3.0 / (16.0 * std::f32::consts::PI);
        let rows = &self.rows;
        self.texels.par_chunks_mut(self.size as usize).zip(rows).for_each(|(row, geo)| {
            for t in geo {
                let cos_phi = if t.h == Vec2::ZERO { 1.0 } else { t.h.dot(sh) };
                let [ir, im, is] = lut.lookup(cos_phi, t.v);
                let c = t.dir.dot(sun);
                let c2 = 1.0 + c * c;
                let den = (a - b * c).max(1e-12);
                let pm = k * c2 / (den * den.sqrt());
                row[t.i as usize] = e * (ir * (kr * c2) + im * pm + is);
            }
        });
        self.sun = sun;
    }

    /// Wraps texels computed elsewhere (the GPU path); checks the count and values.
    pub fn from_texels(
        settings: SkyMapSettings,
        sun: Vec3,
        texels: Vec<Vec3>,
    ) -> Result<Self, AtmosphereError> {
        settings.validate()?;
        let sun = sun.try_normalize().ok_or(AtmosphereError::InvalidVector {
            name: "sun",
            reason: "must be finite and non-zero",
        })?;
        let map = Self {
            size: settings.size,
            texels,
            sun,
            settings,
            rows: texel_geometry(settings.size),
        };
        map.validate()?;
        Ok(map)
    }

    pub fn size(&self) -> u32 {
        self.size
    }
    /// Row-major texels, row `j` = +Z.
    pub fn texels(&self) -> &[Vec3] {
        &self.texels
    }
    /// The sun direction the map was computed for.
    pub fn sun_direction(&self) -> Vec3 {
        self.sun
    }
    pub fn settings(&self) -> &SkyMapSettings {
        &self.settings
    }

    /// The dirty rule: whether the sun at `sun` is more than `settings.dirty_angle` away
    /// from the sun the map was computed for (a non-finite or zero `sun` is always dirty).
    pub fn needs_update(&self, sun: Vec3) -> bool {
        match sun.try_normalize() {
            Some(s) => {
                let angle = s.dot(self.sun).clamp(-1.0, 1.0).acos();
                angle > self.settings.dirty_angle
            }
            None => true,
        }
    }

    /// Regenerates the map if [`SkyMap::needs_update`]; returns whether it did.
    pub fn update(&mut self, sky: &Sky, sun: Vec3) -> Result<bool, AtmosphereError> {
        if !self.needs_update(sun) {
            return Ok(false);
        }
        self.compute(sky, sun)?;
        Ok(true)
    }

    /// Bilinear sample in direction `dir` (normalised here; below-horizon directions are
    /// sampled at the horizon; a degenerate `dir` gives zero).
    pub fn sample(&self, dir: Vec3) -> Vec3 {
        let Some(d) = dir.try_normalize() else { return Vec3::ZERO };
        let n = self.size as i64;
        let c = direction_to_texel(self.size, d);
        let (fx, fy) = (c.x.floor(), c.y.floor());
        let (tx, ty) = (c.x - fx, c.y - fy);
        let at = |x: i64, y: i64| {
            let (x, y) = (x.clamp(0, n - 1), y.clamp(0, n - 1));
            self.texels[(y * n + x) as usize]
        };
        let (x0, y0) = (fx as i64, fy as i64);
        let a = at(x0, y0).lerp(at(x0 + 1, y0), tx);
        let b = at(x0, y0 + 1).lerp(at(x0 + 1, y0 + 1), tx);
        a.lerp(b, ty)
    }

    /// Every texel finite and non-negative, and the texel count right.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        if self.texels.len() != (self.size * self.size) as usize {
            return Err(AtmosphereError::Invalid {
                what: "sky map",
                reason: "texel count is not size x size".into(),
            });
        }
        match self.texels.iter().position(|t| !t.is_finite() || t.min_element() < 0.0) {
            Some(i) => Err(AtmosphereError::Invalid {
                what: "sky map",
                reason: format!("texel {i} = {} not finite and >= 0", self.texels[i]),
            }),
            None => Ok(()),
        }
    }
}

impl SkyRadiance for SkyMap {
    fn radiance(&self, dir: Vec3) -> Vec3 {
        self.sample(dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texel_direction_round_trips() {
        for n in [4, 64, 256] {
            for j in 0..n {
                for i in 0..n {
                    if let Some(d) = texel_direction(n, i, j) {
                        assert!((d.length() - 1.0).abs() < 1e-5 && d.y >= -1e-6);
                        let c = direction_to_texel(n, d);
                        assert!((c - Vec2::new(i as f32, j as f32)).abs().max_element() < 1e-3);
                    }
                }
            }
        }
        assert!((disk_to_direction(Vec2::ZERO) - Vec3::Y).length() < 1e-7);
        assert!((disk_to_direction(Vec2::X) - Vec3::X).length() < 1e-7);
    }
}
