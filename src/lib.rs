//! serein: real-time global-illumination techniques, one crate each, measured against ground
//! truth. This facade re-exports every technique crate under one name; depend on the single
//! crates directly to keep your dependency tree small. The root package also holds the
//! cross-crate integration tests (`tests/`).

pub use atmosphere;
pub use frame_scheduler;
pub use kdtree_tracer;
pub use lpv;
pub use reference;
pub use scene;
pub use sh_math;
pub use shadows;
pub use sky_volume;
