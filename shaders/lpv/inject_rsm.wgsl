// include: lpv/common.inc.wgsl
// include: lpv/inject.inc.wgsl
// Injection straight from a reflective shadow map (its flux, normal and position targets,
// a texel with a zero normal is empty): one invocation per texel, each texel one VPL. With
// the geometry volume on, the texel is also a surfel of area texel_area / max(|n.l|, 0.2)
// whose blocking SH is added to the corner nearest to it (CPU twin: src/geometry.rs
// `GeometryVolume::build`), in fixed point (`limits.y` per unit). The texels as VPLs and
// surfels on the CPU: src/rsm.rs (`rsm_vpls`, `rsm_surfels`; the 0.2 is its
// `SURFEL_MIN_COS`, a test checks that this file still says so).

struct RsmInject {
    // xyz unit direction towards the light, w the texel's area across the light (world²)
    to_light: vec4<f32>,
    // RSM width, height; 1 when the geometry volume is on and the texels are surfels; unused
    size: vec4<u32>,
    // largest flux one texel can carry (per channel; the fixed-point scale's bound),
    // geometry volume fixed-point scale, unused x2
    limits: vec4<f32>,
}

@group(0) @binding(0) var<uniform> grid: LpvGrid;
@group(0) @binding(1) var<uniform> rsm: RsmInject;
@group(0) @binding(2) var rsm_flux: texture_2d<f32>;
@group(0) @binding(3) var rsm_normal: texture_2d<f32>;
@group(0) @binding(4) var rsm_position: texture_2d<f32>;
@group(0) @binding(5) var<storage, read_write> cells: array<atomic<i32>>;
@group(0) @binding(6) var<storage, read_write> blocking: array<atomic<i32>>;

fn add_surfel(p: vec3<f32>, n: vec3<f32>) {
    let area = rsm.to_light.w / max(abs(dot(n, rsm.to_light.xyz)), 0.2);
    let c = floor((p - grid.origin) / grid.cell_size + 0.5);
    let r = f32(grid.res);
    if any(c < vec3<f32>(0.0)) || any(c > vec3<f32>(r)) {
        return;
    }
    let m = grid.res + 1u;
    let corner = (u32(c.z) * m + u32(c.y)) * m + u32(c.x);
    let w = area / (grid.cell_size * grid.cell_size);
    let a = w / 3.0;
    let b = -2.0 / 3.0 * w * n;
    let sh = array<f32, 4>(a / LPV_Y00, b.y / LPV_K1, b.z / LPV_K1, b.x / LPV_K1);
    for (var k = 0u; k < 4u; k++) {
        atomicAdd(&blocking[corner * 4u + k], i32(round(sh[k] * rsm.limits.y)));
    }
}

@compute @workgroup_size(8, 8)
fn inject_rsm(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= rsm.size.x || id.y >= rsm.size.y {
        return;
    }
    let t = vec2<i32>(id.xy);
    let raw = textureLoad(rsm_normal, t, 0).xyz;
    let len2 = dot(raw, raw);
    if !(len2 > 0.0) {
        return;
    }
    let p = textureLoad(rsm_position, t, 0).xyz;
    let flux = min(textureLoad(rsm_flux, t, 0).xyz, vec3<f32>(rsm.limits.x));
    lpv_inject(p, raw, flux);
    if rsm.size.z == 1u {
        add_surfel(p, raw * inverseSqrt(len2));
    }
}
