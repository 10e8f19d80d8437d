//! The engine's typed errors. Each either shows its source in its message or returns it from
//! [`std::error::Error::source`], never both: the wrappers of the scene's, the GPU harness's and
//! the traced effects' errors are transparent (those messages say enough), a technique's error
//! is the source of a message naming the technique. [`error_chain`] prints the whole chain.

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
    #[error(transparent)]
    Scene(#[from] scene::SceneError),
    /// A wgpu error (validation, out of memory, lost device).
    #[error("GPU: {0}")]
    Gpu(String),
    /// A wgpu call through the shared GPU plumbing failed (validation, read-back).
    #[error(transparent)]
    Wgpu(#[from] gpu_harness::GpuError),
    /// The scene could not be prepared for ray tracing, or a pass of the traced rays
    /// (`traced_effects::gpu`) could not be made or run.
    #[error(transparent)]
    Trace(#[from] traced_effects::TraceError),
    /// A technique crate refused its input or failed; `source` is its own typed error.
    #[error("{technique}")]
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

/// `e` and its sources, outermost first, joined by `": "`: the line to show a person (each
/// cause appears once, as every error of the workspace either shows or returns its source).
pub fn error_chain(e: &(dyn std::error::Error + 'static)) -> String {
    let mut s = e.to_string();
    let mut next = e.source();
    while let Some(cause) = next {
        s.push_str(": ");
        s.push_str(&cause.to_string());
        next = cause.source();
    }
    s
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 57 (4): through every wrapping layer, each cause is named once.
    #[test]
    fn a_nested_error_chain_names_each_cause_once() {
        let lost = std::io::Error::other("device lost");
        let gpu = gpu_harness::GpuError::Readback { what: "mapping", source: Box::new(lost) };
        let e = EngineError::technique("lpv", lpv::LpvError::Gpu(gpu));
        assert_eq!(
            error_chain(&e),
            "lpv: LPV GPU path: buffer read-back failed (mapping): device lost"
        );
        let missing = scene::load("/nonexistent/dir/s.toml").expect_err("no such file");
        let e = EngineError::from(missing);
        let chain = error_chain(&e);
        assert_eq!(chain.matches("/nonexistent/dir/s.toml").count(), 2, "{chain}");
        assert!(
            chain.starts_with("/nonexistent/dir/s.toml: cannot read /nonexistent/dir/s.toml: ")
        );
    }
}
