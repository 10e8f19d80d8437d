//! The engine's typed errors.

/// Everything that can stop a frame or a renderer from being made.
#[derive(Debug, thiserror::Error)]
pub enum EngineError {
    /// No wgpu adapter: neither a GPU nor Mesa's software rasterisers.
    #[error(
        "no GPU adapter found ({0}); on a machine without a GPU install Mesa's Vulkan lavapipe \
         (apt-get install mesa-vulkan-drivers) or make sure llvmpipe (GL) is available"
    )]
    NoAdapter(String),
    /// The scene could not be loaded or is invalid.
    #[error("scene: {0}")]
    Scene(#[from] scene::SceneError),
    /// A wgpu error (validation, out of memory, lost device).
    #[error("GPU: {0}")]
    Gpu(String),
    /// A wgpu call through the shared GPU plumbing failed (validation, read-back).
    #[error("GPU: {0}")]
    Wgpu(#[from] gpu_harness::GpuError),
    /// The scene could not be prepared for ray tracing.
    #[error("ray tracer: {0}")]
    Trace(#[from] traced_effects::TraceError),
    /// A technique crate refused its input or failed; `source` is its own typed error.
    #[error("{technique}: {source}")]
    Technique {
        technique: &'static str,
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// A pass of the frame failed.
    #[error("pass '{pass}' failed: {message}")]
    Pass { pass: String, message: String },
    /// Invalid settings.
    #[error("settings: {0}")]
    Settings(String),
    /// Writing an output file failed.
    #[error("writing {path}: {message}")]
    Io { path: String, message: String },
}

impl EngineError {
    /// `e`, the error of the technique crate `technique`, kept as the source.
    pub fn technique(
        technique: &'static str,
        e: impl std::error::Error + Send + Sync + 'static,
    ) -> Self {
        Self::Technique { technique, source: Box::new(e) }
    }
}
