//! Real spherical harmonics for lighting: evaluate, project, convolve, rotate and window.
//!
//! Light propagation volumes store 2 bands (4 coefficients per colour), irradiance volumes 3
//! bands (9), references and tests up to 5 bands (25). This crate gives fixed-size coefficient
//! types for 1..=5 bands ([`Sh`], [`ShRgb`]), closed-form basis polynomials for bands 0..=4
//! with the associated-Legendre recurrence as their reference, projection over weighted point
//! sets (Saff-Kuijlaars, spherical Fibonacci, Hammersley, seeded random), clamped-cosine
//! convolution (Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance
//! Environment Maps"), deringing windows (Hann, Lanczos, and Sloan 2008, "Stupid Spherical
//! Harmonics (SH) Tricks"), rotation, and the same evaluation in WGSL
//! (`shaders/sh_math/sh.inc.wgsl`, exposed as [`WGSL`]).
//!
//! **Names.** A *band* is one value of `l`; an SH with `b` bands has `b²` *coefficients*
//! (`C` in the types). [`Sh3`] has 3 bands and 9 coefficients. The word "order" is not used.
//!
//! **Convention.** Real, orthonormal SH **without** the Condon-Shortley phase, polar axis +Z:
//! `Y(1,-1), Y(1,0), Y(1,1) = 0.488603 (y, z, x)`. Coefficient `i = l(l+1) + m`. Directions are
//! normalised; a zero (or non-finite) direction evaluates to the band-0 term alone, the
//! average of the basis over the sphere, so nothing returns NaN.
//!
//! ```
//! use glam::Vec3;
//! use sh_math::{irradiance, project_fn, saff_kuijlaars_sphere, Sh3};
//! use std::f32::consts::PI;
//!
//! // Project a sky of constant radiance 2.0 with 400 Saff-Kuijlaars points...
//! let points = saff_kuijlaars_sphere(400);
//! let sky: Sh3 = project_fn(&points, |_dir| 2.0);
//! // ...and the irradiance at any normal is pi * L.
//! let e = irradiance(&sky, Vec3::new(0.3, 0.9, -0.1));
//! assert!((e - PI * 2.0).abs() < 1e-3 * PI * 2.0);
//! ```

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
