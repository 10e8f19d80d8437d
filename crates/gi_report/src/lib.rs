//! The workspace's accuracy-vs-time report: what every technique's sweep writes.
//!
//! Every technique crate has a bench target named `gi_sweep` (`harness = false`) that measures
//! its settings against a reference and records one [`Entry`] per point (error on one axis,
//! milliseconds on the other) and one [`Comparison`] per side-by-side race with a peer.
//! `cargo xtask bench` runs each crate's sweep, merges the parts into
//! `target/gi-report/report.json`, and writes `report.md` and one SVG chart per technique.
//!
//! ```no_run
//! use gi_report::{Entry, Sweep, time_ms};
//! let mut sweep = Sweep::from_env("my_crate");
//! let (ms, sum) = time_ms(sweep.reps(20), || (0..1000).map(|i| i as f64).sum::<f64>());
//! sweep.entry(
//!     Entry::new("my_crate/sum_1000", "sum", ms)
//!         .setting("n", 1000)
//!         .error("rel_rms", (sum - 499_500.0).abs() / 499_500.0, "closed_form"),
//! );
//! sweep.finish().unwrap();
//! ```
//!
//! The sweep reads two environment variables that `cargo xtask bench` sets:
//! [`ENV_OUT`] (where to write this crate's part, JSON) and [`ENV_QUICK`] (`1` for the
//! reduced sweep that must finish in about a minute per crate on 2 cores).

mod metrics;
mod sweep;
mod timing;

pub use metrics::{ImageErrors, image_errors, max_rel, mean_rel_luminance, rel_rms};
pub use sweep::{Comparison, ENV_OUT, ENV_QUICK, Entry, ErrorValue, Part, Sweep};
pub use timing::{black_box, interleaved, time_ms, time_ns_per_call};
