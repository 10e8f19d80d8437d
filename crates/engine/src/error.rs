//! The engine's typed errors.

/// Everything that can stop a frame or a renderer from being made.
#[derive(Debug, thiserror::Error)]
pub enum EngineError {
    /// No wgpu adapter: neither a GPU nor Mesa's software rasterisers.
    #[error(
        "no GPU adapter found ({0}); on a machine without a GPU install Mesa's Vulkan lavapipe \
         (apt-get install mesa-vulkan-drivers)"
    )]
    NoAdapter(String),
    /// The best adapter there is lacks capabilities the engine's passes need (a downlevel
    /// one, such as GL's llvmpipe: no float render targets with every usage, ...).
    #[error(
        "the adapter {adapter} is downlevel (it lacks {missing}); the engine needs a full \
         WebGPU adapter: a Vulkan, Metal or DX12 GPU, or on a machine without one Mesa's \
         Vulkan lavapipe (apt-get install mesa-vulkan-drivers)"
    )]
    DownlevelAdapter { adapter: String, missing: String },
    /// The scene could not be loaded or is invalid.
    #[error("scene: {0}")]
    Scene(#[from] scene::SceneError),
    /// A wgpu error (validation, out of memory, lost device).
    #[error("GPU: {0}")]
    Gpu(String),
    /// A wgpu call through the shared GPU plumbing failed (validation, read-back).
    #[error("GPU: {0}")]
    Wgpu(#[from] gpu_harness::GpuError),
    /// The scene could not be prepared for ray tracing, or a pass of the traced rays
    /// (`traced_effects::gpu`) could not be made or run.
    #[error("traced effects: {0}")]
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
