//! Without any adapter the renderer says so, with the fix, instead of panicking. (Its own test
//! binary: `WGPU_BACKEND` is process-wide.)

#[test]
fn no_adapter_is_a_clear_error() {
    // A backend this machine cannot have: no adapter is found.
    let backend = if cfg!(target_os = "macos") { "dx12" } else { "metal" };
    // SAFETY: this test binary has one test; nothing else reads the environment concurrently.
    unsafe { std::env::set_var("WGPU_BACKEND", backend) };
    let settings = engine::Settings::preset(engine::Preset::Low, 64, 36);
    let err = match engine::Renderer::new(scene::Generated::PlaneBox.build(1), settings) {
        Ok(_) => panic!("a renderer without an adapter"),
        Err(e) => e,
    };
    assert!(matches!(err, engine::EngineError::NoAdapter(_)), "{err}");
    let msg = err.to_string();
    assert!(msg.contains("no GPU adapter") && msg.contains("mesa-vulkan-drivers"), "{msg}");
}
