//! A physically based clear-sky atmosphere for real-time rendering: where the sun is, what
//! colour its light has when it reaches the ground, how bright the sky is in every
//! direction, and a cached paraboloid sky map that the rest of the engine samples.
//!
//! It rebuilds and extends the sky of the Serenity engine (thesis sections 3.6 and 4.3:
//! Rayleigh + Mie single scattering in a 256 x 256 paraboloid sky map regenerated when the
//! time of day changes, and a sun colour computed from the transmittance along the sun ray)
//! with the modern model of
//!
//! * E. Bruneton, *Precomputed Atmospheric Scattering: a New Implementation* (2017): Earth
//!   constants, the transmittance table and its parameterisation ([`TransmittanceLut`]);
//! * S. Hillaire, *A Scalable and Production Ready Sky and Atmosphere Rendering Technique*
//!   (EGSR 2020): ozone, the multiple-scattering table ([`MultipleScatteringLut`]),
//!   energy-conserving integration, the sky-view table ([`SkyViewLut`], here with the phase
//!   functions factored out so it can be coarse);
//! * W. Cornette & J. Shanks (1992) for the aerosol phase function, Rayleigh for molecules;
//! * W. Heidrich & H.-P. Seidel (1998) for the paraboloid map ([`SkyMap`]);
//! * the NOAA solar calculator / J. Meeus, *Astronomical Algorithms*, for [`solar_position`].
//!
//! Units: kilometres; radiance per unit of solar irradiance ([`Atmosphere::sun_irradiance`],
//! 1 in the Earth preset). World frame: +Y up, +X east, -Z north.
//!
//! ```
//! use atmosphere::{solar_position, CivilDate, Sky, SkyMap, SkyMapSettings, SkyRadiance};
//! // 17:30 on 21 June in Lisbon (UTC+1).
//! let sun = solar_position(CivilDate::new(2024, 6, 21), 16.5, 38.72, -9.14)?.direction();
//! let sky = Sky::earth()?; // Earth atmosphere, default quality (builds the tables)
//! let sun_colour = sky.sun_colour(0.0, sun); // irradiance of the sun at the ground, RGB
//! assert!(sun_colour.x > sun_colour.z); // afternoon sun: warmer than white
//! let mut map = SkyMap::new(&sky, SkyMapSettings { size: 64, ..Default::default() }, sun)?;
//! let zenith = map.radiance(glam::Vec3::Y);
//! assert!(zenith.z > zenith.x); // blue sky
//! // A minute later the sun has moved less than the dirty angle: the map is kept.
//! let later = solar_position(CivilDate::new(2024, 6, 21), 16.5 + 1.0 / 60.0, 38.72, -9.14)?;
//! assert!(!map.update(&sky, later.direction())?);
//! # Ok::<(), atmosphere::AtmosphereError>(())
//! ```
//!
//! # How the sky map is made fast
//!
//! The thesis integrated every texel on the GPU. Here the default [`SkyMap`] regenerates in
//! two steps: a 16 x 32 [`SkyViewLut`] of the three *phase-free* integrals (Rayleigh, Mie,
//! multiple scattering) over relative azimuth and view height, whose rows share their
//! densities and view transmittance so that only the sun-dependent lookups run per grid
//! point; then per texel one bilinear lookup and the exact Rayleigh and Cornette-Shanks
//! phase functions (the sharp Mie forward peak is never interpolated). The texel geometry
//! is cached when the map is created, so [`SkyMap::update`] only pays for those two steps.
//!
//! # Accuracy and cost (measured by `benches/gi_sweep.rs`)
//!
//! Against the reference (`SkySettings::reference()`: 512 view samples, the sun-ray
//! transmittance integrated with 256 samples at every view sample, a 64 x 64 multiple
//! scattering table), relative RMS over the map's texels: default 256 x 256 map about
//! 2.4e-3 with the sun at 30 degrees and 4.5e-3 at 5 degrees; single scattering alone (the
//! thesis's model) misses about 38% of the sky's radiance. Regenerating the default map
//! took about 1.3 ms on a 2-core machine shared with other jobs (noisy); one
//! [`Sky::sun_colour`] call about 0.2 us. The largest remaining error is the view-sample
//! count (24 by default; 32 gives 1.6e-3 and costs little more).
//!
//! The GPU path (feature `gpu`, module `gpu`) fills the same sky map with a WGSL compute
//! shader (`shaders/atmosphere/skymap.wgsl`), one view-ray integration per texel, and
//! agrees with the CPU's per-texel map to a relative RMS below 1e-3 (tested).

mod error;
pub mod geometry;
#[cfg(feature = "gpu")]
pub mod gpu;
mod multiscatter;
mod params;
mod phase;
mod sky;
mod skymap;
mod skyview;
mod solar;
mod transmittance;

pub use error::AtmosphereError;
pub use multiscatter::{MultipleScatteringLut, MultipleScatteringSettings};
pub use params::{Atmosphere, Medium};
pub use phase::{cornette_shanks_phase, henyey_greenstein_phase, rayleigh_phase};
pub use sky::{LightTransmittance, ScatteringIntegrals, Sky, SkySettings};
pub use skymap::{
    SkyMap, SkyMapMethod, SkyMapSettings, SkyRadiance, direction_to_disk, direction_to_texel,
    disk_to_direction, texel_direction, texel_disk,
};
pub use skyview::SkyViewLut;
pub use solar::{CivilDate, MAX_UTC_HOURS, SolarPosition, days_in_month, solar_position};
pub use transmittance::{
    TransmittanceLut, optical_depth, optical_depth_quadratic, transmittance_between_exact,
    transmittance_to_top_exact,
};
