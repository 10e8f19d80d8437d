#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! [`SkyVolume`] over a [`VolumeGrid`] and [`OcclusionQuad`]s, with [`Settings`] and
//! [`FillMethod`]; skies through [`SkyRadiance`] ([`ConstantSky`], [`AnalyticSky`]);
//! [`SkyVolume::update`] for amortised, [`Dirty`]-tracked updates; [`generated_city`] for
//! tests and demos; with feature `gpu`, module `gpu`.
//!
//! Why three fills: the visibility of every sample from every probe depends only on the quads,
//! so when only the sky changes (time of day) the cached-visibility fill re-lights the volume
//! with a masked projection and no rays; precomputed radiance transfer goes further (per probe
//! a 9 x k² matrix from the sky's SH to the probe's), and brute force needs no memory.

mod demo;
mod error;
mod fill;
#[cfg(feature = "gpu")]
pub mod gpu;
mod grid;
mod lookup;
mod masked;
#[cfg(feature = "gpu")]
mod resident;
mod samples;
mod settings;
mod sky;
mod visibility;
mod volume;

pub use demo::generated_city;
pub use error::SkyVolumeError;
pub use grid::{MAX_POINTS, VolumeGrid};
pub use settings::{FillMethod, Settings, Window};
pub use sky::{AnalyticSky, ConstantSky, SkyRadiance};
pub use vocab::OcclusionQuad;
pub use volume::{Dirty, SkyVolume, UpdateReport};
