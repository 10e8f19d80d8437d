//! Every shader of the crate parses and validates with naga, and names the entry points the
//! passes build their pipelines from.
#![cfg(feature = "gpu")]

#[test]
fn shaders_validate_with_naga() {
    for (name, source) in post::gpu::SHADERS {
        let module = gpu_harness::validate_wgsl(source).unwrap_or_else(|e| panic!("{name}: {e}"));
        let entries: Vec<&str> = module.entry_points.iter().map(|e| e.name.as_str()).collect();
        let want: &[&str] = match name {
            "tonemap" => &["reduce", "adapt", "map"],
            _ => &["vs_fullscreen", "fs_accumulate"],
        };
        assert_eq!(entries, want, "{name}");
    }
}
