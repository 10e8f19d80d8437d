//! One file per pass; each pass is a struct of its pipelines and a plain function that
//! records or runs it.

pub mod cache_bounce;
pub mod display;
pub mod lighting;
pub mod lpv;
pub mod point_shadows;
pub mod radiance_cache;
pub mod rsm_gather;
pub mod shadow;
pub mod sky;
pub mod sky_bounce;
pub mod sun_rsm;
pub mod traced_lighting;
