// include: sh_math/sh.inc.wgsl
// include: sky_volume/lookup.inc.wgsl
// The sky volume's lookup kernel (thesis 5.3.6): one invocation per query, diffuse light
// albedo / pi * E at the query's position and normal (lookup.inc.wgsl).

struct Query {
    position: vec4<f32>,
    normal: vec4<f32>,
    albedo: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: SkyVolumeLookup;
@group(0) @binding(1) var<storage, read> probes: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read> queries: array<Query>;
@group(0) @binding(3) var<storage, read_write> out_diffuse: array<vec4<f32>>;

fn sky_volume_params() -> SkyVolumeLookup {
    return params;
}

fn sky_volume_probe(i: u32) -> vec4<u32> {
    return probes[i];
}

@compute @workgroup_size(64)
fn lookup(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= arrayLength(&queries)) {
        return;
    }
    let q = queries[i];
    // A zero albedo (the engine's background pixels) reflects nothing: skip the 8 corners.
    if all(q.albedo.xyz == vec3<f32>(0.0)) {
        out_diffuse[i] = vec4<f32>(0.0);
        return;
    }
    let e = sky_volume_irradiance(q.position.xyz, q.normal.xyz);
    out_diffuse[i] = vec4<f32>(q.albedo.xyz * 0.31830988 * e, 0.0);
}
