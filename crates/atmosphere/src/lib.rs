//! A physically based clear-sky atmosphere (work in progress: solar position first).

mod error;
pub mod geometry;
mod params;
mod phase;
mod solar;
mod transmittance;

pub use error::AtmosphereError;
pub use params::{Atmosphere, Medium};
pub use phase::{cornette_shanks_phase, henyey_greenstein_phase, rayleigh_phase};
pub use solar::{CivilDate, SolarPosition, solar_position};
pub use transmittance::{
    TransmittanceLut, optical_depth, transmittance_between_exact, transmittance_to_top_exact,
};
