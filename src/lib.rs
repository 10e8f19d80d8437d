//! serein: real-time global-illumination techniques, one crate each, measured against ground
//! truth. This facade re-exports every technique crate under one name; depend on the single
//! crates directly to keep your dependency tree small. The root package also holds the
//! cross-crate integration tests (`tests/`) and the benchmarks that compose crates
//! (`benches/`: the engine's frame per preset, the three one-bounce techniques raced; run
//! with `cargo bench -p serein`).

pub use atmosphere;
pub use engine;
pub use frame_scheduler;
pub use gi_report;
pub use gpu_harness;
pub use kdtree_tracer;
pub use lpv;
pub use post;
pub use radiance_cache;
pub use reference;
pub use rsm_gi;
pub use scene;
pub use sh_math;
pub use shadows;
pub use sky_volume;
pub use ssao;
pub use traced_effects;
pub use vocab;
