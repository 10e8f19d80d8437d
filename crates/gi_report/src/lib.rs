#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! [`Entry`] and [`Comparison`], collected by a [`Sweep`] into a [`Part`]; the metrics
//! [`rel_rms`], [`max_rel`], [`mean_rel_luminance`]; the timing helpers [`time_ms`],
//! [`time_ns_per_call`], [`interleaved`]. The sweep reads [`ENV_OUT`] (where to write this
//! crate's part, JSON) and [`ENV_QUICK`] (`1` for the reduced sweep that must finish in about
//! a minute per crate on 2 cores), which `cargo xtask bench` sets.

//!
//! Every timing the harness takes keeps its spread (min, quartiles, median, max, samples), and
//! every interleaved race the interval of its ratio from the per-round pairs;
//! [`Sweep::entry`] and [`Sweep::comparison`] attach them to the records made from those
//! medians (optional fields `spread` and `interval`: older reports still read). Sweeps that
//! produce images attach [`Pictures`] written with the [`pictures`] module.

mod metrics;
#[cfg(feature = "sweep")]
pub mod pictures;
#[cfg(feature = "sweep")]
mod sweep;
mod timing;

pub use metrics::{ImageErrors, image_errors, max_rel, mean_rel_luminance, rel_rms};
#[cfg(feature = "sweep")]
pub use sweep::{
    Comparison, ENV_OUT, ENV_QUICK, Entry, ErrorValue, PICTURES, Part, Pictures, Sweep,
};
pub use timing::{
    Race, RatioInterval, Spread, black_box, interleaved, race, time_ms, time_ns_per_call,
    time_spread,
};
