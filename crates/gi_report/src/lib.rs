#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! [`Entry`] and [`Comparison`], collected by a [`Sweep`] into a [`Part`]; the metrics
//! [`rel_rms`], [`max_rel`], [`mean_rel_luminance`]; the timing helpers [`time_ms`],
//! [`time_ns_per_call`], [`interleaved`]. The sweep reads [`ENV_OUT`] (where to write this
//! crate's part, JSON) and [`ENV_QUICK`] (`1` for the reduced sweep that must finish in about
//! a minute per crate on 2 cores), which `cargo xtask bench` sets.

mod metrics;
#[cfg(feature = "sweep")]
mod sweep;
mod timing;

pub use metrics::{max_rel, mean_rel_luminance, rel_rms};
#[cfg(feature = "sweep")]
pub use sweep::{Comparison, ENV_OUT, ENV_QUICK, Entry, ErrorValue, Part, Sweep};
pub use timing::{black_box, interleaved, time_ms, time_ns_per_call};
