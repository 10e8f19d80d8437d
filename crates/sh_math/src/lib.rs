#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! - [`Sh`], [`ShRgb`] and their aliases: the coefficient types; [`sh_index`], [`bands_for`].
//! - [`eval_basis`] (closed form) and [`eval_basis_recurrence`] (its reference).
//! - [`PointSet`] and its constructors: weighted directions for projection.
//! - [`project_fn`], [`project_fn_rgb`], [`project_direction`], [`project_clamped_cosine`],
//!   [`project_constant`].
//! - [`ZonalKernel`]: [`CLAMPED_COSINE`], the windows; [`irradiance`], [`evaluate`].
//! - [`ShRotation`].
//! - [`WGSL`]: the shader twin.

mod basis;
mod coeffs;
mod convolve;
mod points;
mod project;
mod rotate;

pub use basis::{eval_basis, eval_basis_recurrence, eval_basis_recurrence_all, normalize_dir};
pub use coeffs::{
    Sh, Sh1, Sh2, Sh2Rgb, Sh3, Sh3Rgb, Sh4, Sh4Rgb, Sh5, Sh5Rgb, ShRgb, bands_for, sh_index,
};
pub use convolve::{
    CLAMPED_COSINE, IDENTITY, ZonalKernel, evaluate, evaluate_rgb, find_sloan_lambda, hann_window,
    irradiance, irradiance_rgb, lanczos_window, sloan_window,
};
pub use points::{
    PointSet, fibonacci_hemisphere, fibonacci_sphere, gauss_product_sphere, hammersley_hemisphere,
    hammersley_sphere, random_hemisphere, random_sphere, saff_kuijlaars_hemisphere,
    saff_kuijlaars_sphere,
};
pub use project::{
    project_clamped_cosine, project_constant, project_direction, project_fn, project_fn_rgb,
};
pub use rotate::ShRotation;

/// The WGSL snippet with the same basis evaluation (`sh_basis_4`, `sh_basis_9`, `sh_basis_16`,
/// `sh_basis_25`, `sh_irradiance_9`): prepend it to a shader that uses it.
pub const WGSL: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/sh.inc.wgsl"));
