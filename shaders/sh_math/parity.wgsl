// include: sh_math/sh.inc.wgsl
// Parity kernel: the 25 basis values and the 3-band irradiance of fixed coefficients for each
// input direction, so the CPU and GPU evaluations can be compared.

@group(0) @binding(0) var<storage, read> dirs: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> basis_out: array<f32>;
@group(0) @binding(2) var<storage, read_write> irradiance_out: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&dirs) {
        return;
    }
    let d = dirs[i].xyz;
    let y = sh_basis_25(d);
    for (var k = 0u; k < 25u; k++) {
        basis_out[i * 25u + k] = y[k];
    }
    let radiance = array<f32, 9>(1.0, 0.5, -0.25, 0.125, 0.3, -0.2, 0.1, 0.05, -0.4);
    irradiance_out[i] = sh_irradiance_9(radiance, d);
}
