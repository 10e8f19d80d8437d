//! Helpers for tests: read-back conversion, the local skip switch, the test context.

use crate::GpuContext;

/// Environment variable that lets a developer skip GPU tests on a machine with no adapter.
/// CI never sets it.
pub const SKIP_ENV: &str = "SEREIN_SKIP_GPU";

/// Copies read-back bytes into a vector of `T` (read-back `Vec<u8>`s are not guaranteed to be
/// aligned for `T`, so `bytemuck::cast_slice` on them may fail; this never does).
pub fn cast_vec<T: bytemuck::Pod>(bytes: &[u8]) -> Vec<T> {
    bytemuck::pod_collect_to_vec(bytes)
}

/// True when the developer asked to skip GPU tests (`SEREIN_SKIP_GPU=1`) and this is not CI.
pub fn skip_requested() -> bool {
    let skip = std::env::var(SKIP_ENV).is_ok_and(|v| v == "1");
    let ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false");
    skip && !ci
}

/// For tests: a [`GpuContext`], or `None` when the developer explicitly skips GPU tests.
/// Panics with the [`GpuError`](crate::GpuError) message (naming `mesa-vulkan-drivers`) when no adapter
/// exists and no skip was requested, so GPU tests never pass silently.
pub fn gpu_test_context() -> Option<GpuContext> {
    if skip_requested() {
        eprintln!("{SKIP_ENV}=1: skipping a GPU test");
        return None;
    }
    match GpuContext::new() {
        Ok(ctx) => Some(ctx),
        Err(e) => panic!("{e}"),
    }
}

/// GPU objects alive on a device, for tests that check a resident pass creates nothing per
/// frame (read after the queue drained, so that no staging buffer is counted).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LiveObjects {
    pub buffers: isize,
    pub textures: isize,
    pub texture_views: isize,
    pub bind_groups: isize,
}

/// Waits for `device`'s queue to drain and counts its live [`LiveObjects`].
pub fn live_objects(device: &wgpu::Device) -> LiveObjects {
    device.poll(wgpu::PollType::wait_indefinitely()).expect("the device polls");
    let c = device.get_internal_counters().hal;
    LiveObjects {
        buffers: c.buffers.read(),
        textures: c.textures.read(),
        texture_views: c.texture_views.read(),
        bind_groups: c.bind_groups.read(),
    }
}

/// Parses and validates `source` with naga (every validation flag and capability), as the
/// tests of every crate's WGSL do: the module, or naga's report with the source lines.
pub fn validate_wgsl(source: &str) -> Result<naga::Module, String> {
    let module = naga::front::wgsl::parse_str(source).map_err(|e| e.emit_to_string(source))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|e| e.emit_to_string(source))?;
    Ok(module)
}

/// The size in bytes of struct `name` as WGSL lays it out in `source` (naga's layouter): what
/// the tests of a `#[repr(C)]` struct shared with a shader compare its Rust size with, so
/// that a field added on one side only fails there, not in a wrong image.
pub fn wgsl_struct_size(source: &str, name: &str) -> Result<usize, String> {
    let module = naga::front::wgsl::parse_str(source).map_err(|e| e.emit_to_string(source))?;
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).map_err(|e| e.to_string())?;
    let (handle, _) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .ok_or_else(|| format!("struct {name} not in the shader"))?;
    Ok(layouter[handle].size as usize)
}

#[cfg(test)]
mod tests {
    #[test]
    fn validate_wgsl_names_what_is_wrong() {
        let ok = "@compute @workgroup_size(1) fn main() {}";
        assert!(super::validate_wgsl(ok).is_ok());
        let unknown = "@compute @workgroup_size(1) fn main() { let x = missing; }";
        let e = super::validate_wgsl(unknown).expect_err("an unknown name");
        assert!(e.contains("missing"), "{e}");
        // Parses, but a storage write to a read-only binding does not validate.
        let read_only = "@group(0) @binding(0) var<storage, read> d: array<f32>;
            @compute @workgroup_size(1) fn main() { d[0] = 1.0; }";
        assert!(super::validate_wgsl(read_only).is_err());
    }

    #[test]
    fn wgsl_struct_size_lays_out_as_wgsl_does() {
        let src = "struct S { a: vec3<f32>, b: f32, c: mat4x4<f32> }";
        assert_eq!(super::wgsl_struct_size(src, "S"), Ok(80));
        assert!(super::wgsl_struct_size(src, "T").unwrap_err().contains('T'));
    }
}
