//! The harness itself works on whatever adapter this machine has.

use gpu_harness::{Binding, gpu_test_context};

#[test]
fn doubles_a_buffer_and_writes_an_output() {
    let Some(ctx) = gpu_test_context() else { return };
    let wgsl = "
        @group(0) @binding(0) var<storage, read> input: array<f32>;
        @group(0) @binding(1) var<storage, read_write> output: array<f32>;
        @compute @workgroup_size(64)
        fn main(@builtin(global_invocation_id) id: vec3<u32>) {
            if id.x < arrayLength(&input) { output[id.x] = input[id.x] * 2.0 + 1.0; }
        }";
    let input: Vec<f32> = (0..1000).map(|i| i as f32 * 0.5).collect();
    let out = ctx
        .run_compute(
            wgsl,
            "main",
            &[Binding::Read(bytemuck::cast_slice(&input)), Binding::Output(4 * 1000)],
            [1000u32.div_ceil(64), 1, 1],
        )
        .unwrap();
    assert!(out[0].is_empty());
    let got: Vec<f32> = gpu_harness::cast_vec(&out[1]);
    for (i, (g, x)) in got.iter().zip(&input).enumerate() {
        assert_eq!(*g, x * 2.0 + 1.0, "element {i}");
    }
    eprintln!("adapter: {}", ctx.describe());
}

#[test]
fn invalid_shader_is_a_typed_error_not_a_panic() {
    let Some(ctx) = gpu_test_context() else { return };
    let err = ctx.run_compute("fn main( {", "main", &[], [1, 1, 1]);
    assert!(
        matches!(err, Err(gpu_harness::GpuError::Validation(ref m)) if !m.to_string().is_empty()),
        "{err:?}"
    );
}
