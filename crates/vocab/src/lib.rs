#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! - [`Sun`]: direction towards the sun, irradiance, angular radius.
//! - [`OcclusionQuad`]: a rectangle standing in for a large occluder of sky light, with its
//!   hit rule ([`hit_test`]) and [`InvalidQuad`].
//! - [`Component`]: the lighting terms a frame splits into.
//! - [`Pinhole`]: a camera's position, orientation, vertical field of view and aspect.

mod component;
mod pinhole;
mod quad;
mod sun;

pub use component::Component;
pub use pinhole::Pinhole;
pub use quad::{AXIS_TOLERANCE, InvalidQuad, OcclusionQuad, hit_test};
pub use sun::Sun;
