// include: shadows/mask.inc.wgsl
//
// Reflective shadow map pass (Dachsbacher & Stamminger 2005): depth plus three targets per
// texel: reflected flux (light colour * albedo * texel area), world normal facing the light,
// world position.

struct RsmDraw {
    clip_from_local: mat4x4<f32>,
    world_from_local: mat4x4<f32>,
    // xyz: light colour * albedo * texel area; w unused.
    flux: vec4<f32>,
    // xyz: unit direction towards the light; w unused.
    to_light: vec4<f32>,
}

@group(0) @binding(0) var<uniform> draw: RsmDraw;

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
}

fn transform(position: vec3<f32>, normal: vec3<f32>) -> VsOut {
    var o: VsOut;
    o.clip = draw.clip_from_local * vec4<f32>(position, 1.0);
    o.world = (draw.world_from_local * vec4<f32>(position, 1.0)).xyz;
    // Model matrices with non-uniform scale need the inverse transpose; callers pass
    // rigid or uniformly scaled transforms.
    o.normal = (draw.world_from_local * vec4<f32>(normal, 0.0)).xyz;
    return o;
}

@vertex
fn vs_main(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> VsOut {
    return transform(position, normal);
}

// Alpha-tested draws: the same, with texture coordinates for `fs_masked`.
@vertex
fn vs_masked(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
) -> VsOut {
    var o = transform(position, normal);
    o.uv = uv;
    return o;
}

struct FsOut {
    @location(0) flux: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) position: vec4<f32>,
}

fn shade(i: VsOut) -> FsOut {
    var n = normalize(i.normal);
    if dot(n, draw.to_light.xyz) < 0.0 {
        n = -n;
    }
    var o: FsOut;
    o.flux = vec4<f32>(draw.flux.xyz, 1.0);
    o.normal = vec4<f32>(n, 1.0);
    o.position = vec4<f32>(i.world, 1.0);
    return o;
}

@fragment
fn fs_main(i: VsOut) -> FsOut {
    return shade(i);
}

@fragment
fn fs_masked(i: VsOut) -> FsOut {
    if mask_is_hole(i.uv) {
        discard;
    }
    return shade(i);
}
