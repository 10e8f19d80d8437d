//! Use `gpu_harness` in your crate's GPU tests: get a device on whatever adapter exists (a
//! GPU, or Mesa's lavapipe / llvmpipe on a machine without one), dispatch a compute shader
//! over your CPU data, read it back and compare with the CPU path.
//!
//! `cargo run -p serein-gpu-harness --example double`

use gpu_harness::{Binding, GpuContext};

fn main() -> Result<(), gpu_harness::GpuError> {
    let ctx = GpuContext::new()?;
    println!("adapter: {} ({:?})", ctx.adapter_info.name, ctx.adapter_info.backend);
    let wgsl = "@group(0) @binding(0) var<storage, read_write> data: array<f32>;
        @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {
            if id.x < arrayLength(&data) { data[id.x] = data[id.x] * 2.0 + 1.0; }
        }";
    let input: Vec<f32> = (0..1000).map(|i| i as f32 * 0.5).collect();
    let out = ctx.run_compute(
        wgsl,
        "main",
        &[Binding::ReadWrite(bytemuck::cast_slice(&input))],
        [16, 1, 1],
    )?;
    let gpu: Vec<f32> = gpu_harness::cast_vec(&out[0]);
    let cpu: Vec<f32> = input.iter().map(|x| x * 2.0 + 1.0).collect();
    assert_eq!(gpu, cpu, "the GPU and CPU paths agree");
    println!("{} values doubled plus one on the GPU, equal to the CPU's", gpu.len());
    Ok(())
}
