//! The WGSL sources, available without the `gpu` feature (for validation and for consumers
//! that build their own pipelines).

/// The WGSL snippet consumers include (lattice, octahedral moments, visibility weight).
pub const COMMON_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/common.inc.wgsl"));
/// The lookup kernel with its snippets prepended (`sh_math`'s basis, then ours), as
/// `cargo xtask shaders` assembles it from its `// include:` lines.
pub const LOOKUP_WGSL: &str = constcat::concat!(
    sh_math::WGSL,
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/common.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/lookup.wgsl")),
);
