// include: scene/brdf.inc.wgsl
// include: scene/material.inc.wgsl
// include: traced_effects/fresnel.inc.wgsl
// include: traced_effects/screen.inc.wgsl
// include: traced_effects/common.inc.wgsl
// The ray casting buffer (thesis 6.2.6, Table 6.1) at quarter resolution (half width, half
// height): for every 2x2 block the pixel with a mirror or glass material nearest the block's
// centre writes its origin, view depth, and the reflection and refraction directions with
// their weights (reflect: reflectivity + transparency * Fresnel; refract: transparency *
// (1 - Fresnel)). Texels without such a pixel have zero weights and are not traced. The
// texels with such a pixel are also appended to `list` (in no particular order), which is
// all the CPU reads back. Twin: traced_effects::ray_casting::cast_rays.

@group(0) @binding(0) var<uniform> view: TracedView;
@group(0) @binding(1) var normal_t: texture_2d<f32>;
@group(0) @binding(2) var geometry_t: texture_2d<f32>;
@group(0) @binding(3) var depth_t: texture_2d<f32>;
@group(0) @binding(4) var<storage, read> materials: array<Material>;
@group(0) @binding(5) var<storage, read_write> rays: array<RayCast>;

// A texel with a ray and its index (traced_effects::ray_casting::ListedRay).
struct ListedRay {
    ray: RayCast,
    texel: vec4<u32>,
}

// The texels with a ray: their count (the recorder clears it), then the texels.
struct RayList {
    count: atomic<u32>,
    texels: array<ListedRay>,
}
@group(0) @binding(6) var<storage, read_write> list: RayList;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let qw = (view.size.x + 1u) / 2u;
    let qh = (view.size.y + 1u) / 2u;
    if id.x >= qw || id.y >= qh {
        return;
    }
    // The first of the block's pixels (all equally near its centre) with a mirror or glass
    // part, found with a few reads each; then its rays, computed once (on llvmpipe, which
    // runs a loop's body under a lane mask until every lane is done, rays computed inside the
    // search cost four times over).
    var found = vec2<i32>(-1);
    var m: Material;
    var depth = 0.0;
    for (var k = 0u; k < 4u; k = k + 1u) {
        let px = vec2<i32>(i32(id.x * 2u + (k & 1u)), i32(id.y * 2u + (k >> 1u)));
        if px.x >= i32(view.size.x) || px.y >= i32(view.size.y) {
            continue;
        }
        let d = textureLoad(depth_t, px, 0).x;
        if d <= 0.0 {
            continue;
        }
        let mk = materials[u32(textureLoad(geometry_t, px, 0).w + 0.5)];
        if material_is_smooth(mk) || mk.params.y > 0.0 {
            found = px;
            m = mk;
            depth = d;
            break;
        }
    }
    var out = RayCast(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
    if found.x >= 0 {
        let trans = m.params.y;
        let p = traced_world_position(view, vec2<f32>(found), depth);
        let n = normalize(textureLoad(normal_t, found, 0).xyz);
        let v = normalize(view.eye.xyz - p);
        let f = fresnel_schlick(dot(n, v), m.params.z);
        let mirror = material_mirror_weight(m, dot(n, v));
        let refl = max(mirror.r, max(mirror.g, mirror.b));
        let r = reflect(-v, n);
        var t = refract(-v, n, 1.0 / max(m.params.z, 1e-3));
        var wt = trans * (1.0 - f);
        if dot(t, t) < 1e-12 {
            t = vec3<f32>(0.0);
            wt = 0.0;
        }
        // A switched-off kind of ray gets no weight, so it is not traced.
        let flags = view.size.z;
        let wr = select(0.0, refl + trans * f, (flags & TRACED_REFLECTIONS) != 0u);
        wt = select(0.0, wt, (flags & TRACED_REFRACTIONS) != 0u);
        out.origin = vec4<f32>(p, depth);
        out.reflect = vec4<f32>(r, wr);
        out.refract = vec4<f32>(normalize(t + vec3<f32>(1e-20)), wt);
    }
    let i = id.y * qw + id.x;
    rays[i] = out;
    if out.origin.w > 0.0 {
        list.texels[atomicAdd(&list.count, 1u)] = ListedRay(out, vec4<u32>(i, 0u, 0u, 0u));
    }
}
