// include: scene/brdf.inc.wgsl
// include: scene/material.inc.wgsl
// include: traced_effects/fresnel.inc.wgsl
// include: traced_effects/screen.inc.wgsl
// include: traced_effects/common.inc.wgsl
// Combines the lit main view with the ray-traced reflections and refractions (thesis
// 6.3.4-6.3.5). Traced radiance lives at quarter resolution; each full-resolution mirror or
// glass pixel gathers the traced texels of the 3x3 quarter-resolution neighbourhood that
// had a ray and lie at a similar depth (the thesis's "smart" blur that masks aliasing along
// silhouettes), with tent weights, and adds them with its own weights: the smooth surface's
// mirror weight (material_mirror_weight, RGB) plus the glass's Fresnel share.
// The lit view is copied first; this shader then runs only where a mirror or glass draw is
// the visible surface (`vs_reflective`, depth test `Equal` against the G-buffer's z-buffer),
// not over the whole screen. Twin: traced_effects::combine::traced_radiance.

@group(0) @binding(0) var<uniform> view: TracedView;
@group(0) @binding(1) var lit_t: texture_2d<f32>;
@group(0) @binding(2) var normal_t: texture_2d<f32>;
@group(0) @binding(3) var geometry_t: texture_2d<f32>;
@group(0) @binding(4) var depth_t: texture_2d<f32>;
@group(0) @binding(5) var<storage, read> materials: array<Material>;
@group(0) @binding(6) var<storage, read> rays: array<RayCast>;
// Two entries per quarter texel: reflected radiance, refracted radiance.
@group(0) @binding(7) var<storage, read> traced: array<vec4<f32>>;

struct ReflectiveOut {
    // Invariant: equal, bit for bit, to the depth the caller's G-buffer pass wrote with the
    // same view-projection and an invariant position.
    @builtin(position) @invariant clip: vec4<f32>,
}

@vertex
fn vs_reflective(@location(0) position: vec3<f32>) -> ReflectiveOut {
    return ReflectiveOut(view.view_proj * vec4<f32>(position, 1.0));
}

@fragment
fn fs_combine(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let px = vec2<i32>(frag.xy);
    // The caller may want the lit view alone (a renderer showing one lighting term).
    if (view.size.z & TRACED_ADD) == 0u {
        return textureLoad(lit_t, px, 0);
    }
    let lit = textureLoad(lit_t, px, 0);
    let depth = textureLoad(depth_t, px, 0).x;
    if depth <= 0.0 {
        return lit;
    }
    let m = materials[u32(textureLoad(geometry_t, px, 0).w + 0.5)];
    let trans = m.params.y;
    if !material_is_smooth(m) && trans <= 0.0 {
        return lit;
    }
    let p = traced_world_position(view, vec2<f32>(px), depth);
    let n = normalize(textureLoad(normal_t, px, 0).xyz);
    let v = normalize(view.eye.xyz - p);
    let f = fresnel_schlick(dot(n, v), m.params.z);
    let refl = material_mirror_weight(m, dot(n, v));
    let qw = i32((view.size.x + 1u) / 2u);
    let qh = i32((view.size.y + 1u) / 2u);
    let qc = vec2<f32>((f32(px.x) + 0.5) * 0.5 - 0.5, (f32(px.y) + 0.5) * 0.5 - 0.5);
    var sum_r = vec3<f32>(0.0);
    var sum_t = vec3<f32>(0.0);
    var wsum = 0.0;
    for (var dy = -1; dy <= 1; dy = dy + 1) {
        for (var dx = -1; dx <= 1; dx = dx + 1) {
            let q = vec2<i32>(i32(round(qc.x)) + dx, i32(round(qc.y)) + dy);
            if q.x < 0 || q.y < 0 || q.x >= qw || q.y >= qh {
                continue;
            }
            let k = q.y * qw + q.x;
            let rc = rays[k];
            if rc.origin.w <= 0.0 || abs(rc.origin.w - depth) > 0.05 * depth + 0.05 {
                continue;
            }
            let d = abs(vec2<f32>(q) - qc);
            let w = max(1.5 - d.x, 0.0) * max(1.5 - d.y, 0.0);
            sum_r += traced[2 * k].xyz * w;
            sum_t += traced[2 * k + 1].xyz * w;
            wsum += w;
        }
    }
    if wsum <= 0.0 {
        return lit;
    }
    let c = lit.rgb + (refl + trans * f) * sum_r / wsum + trans * (1.0 - f) * sum_t / wsum;
    return vec4<f32>(c, 1.0);
}
