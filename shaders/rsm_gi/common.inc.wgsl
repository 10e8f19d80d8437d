// rsm_gi: the pieces the gather and the blur share (CPU twin: crates/rsm_gi/src/input.rs,
// filter.rs).

const RSM_GI_PI: f32 = 3.14159265358979;

// One view of one RSM: matrices, sizes (the pass's image w, h: the low-resolution grid for
// the gather and the blur, the full G-buffer for the upsampling; RSM w, h), pattern (nx, ny,
// blur radius, 1 = vertical blur pass; the upsampling: nx, ny, low-resolution w, h), knobs
// (vpl offset, depth tolerance, normal power, low-resolution factor f).
struct RsmGiView {
    world_to_texel: mat4x4<f32>,
    view_proj: mat4x4<f32>,
    sizes: vec4<u32>,
    pattern: vec4<u32>,
    knobs: vec4<f32>,
}

// A G-buffer pixel: xyz position, w view depth (0 = not shaded); and its unit normal.
struct RsmGiPixel {
    position: vec4<f32>,
    normal: vec3<f32>,
}

// Irradiance at (x, n) from a VPL at p facing np with flux `flux` that is a disc of `area`
// (CPU twin: input.rs vpl_irradiance_area): flux max(0, np.(x - p)) max(0, n.(p - x)) /
// (|x - p|² (pi |x - p|² + area)); area 0 is the point-to-point form factor.
fn rsm_gi_vpl_irradiance(x: vec3<f32>, n: vec3<f32>, p: vec3<f32>, np: vec3<f32>, flux: vec3<f32>, area: f32) -> vec3<f32> {
    let d = x - p;
    let r2 = dot(d, d);
    let c = max(dot(np, d), 0.0) * max(dot(n, -d), 0.0);
    if (r2 <= 1e-12 || c <= 0.0) {
        return vec3<f32>(0.0);
    }
    return flux * (c / (r2 * (RSM_GI_PI * r2 + max(area, 0.0))));
}

const RSM_GI_MAX_TEXEL_STRETCH: f32 = 10.0;

// An orthographic map's texel footprint on a plane facing the light (w) and the direction
// the map looks along (xyz), from world_to_texel's x and y rows (CPU twin: input.rs
// RsmProjection::texel_footprint); zero for a degenerate projection.
fn rsm_gi_texel_footprint(m: mat4x4<f32>) -> vec4<f32> {
    let rx = vec3<f32>(m[0].x, m[1].x, m[2].x);
    let ry = vec3<f32>(m[0].y, m[1].y, m[2].y);
    let c = cross(rx, ry);
    let len = length(c);
    if (!(len > 0.0) || len > 3.4e38) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(c / len, 1.0 / len);
}

// The surface area of a texel with unit normal n (CPU twin: input.rs texel_area).
fn rsm_gi_texel_area(footprint: vec4<f32>, n: vec3<f32>) -> f32 {
    return footprint.w / max(abs(dot(n, footprint.xyz)), 1.0 / RSM_GI_MAX_TEXEL_STRETCH);
}

// The pixel as the passes see it: a zero normal or a point behind the camera is not shaded
// (w = 0). Inputs are finite (the upload or the producing pass guarantees it).
fn rsm_gi_make_pixel(position: vec3<f32>, normal: vec3<f32>, view_proj: mat4x4<f32>) -> RsmGiPixel {
    var px: RsmGiPixel;
    px.position = vec4<f32>(position, 0.0);
    px.normal = vec3<f32>(0.0);
    let len = length(normal);
    if (len > 0.0) {
        let depth = (view_proj * vec4<f32>(position, 1.0)).w;
        if (depth > 0.0) {
            px.position.w = depth;
            px.normal = normal / len;
        }
    }
    return px;
}

// A pixel as the filters keep it on their grid: (unit normal, view depth); depth 0 = not
// shaded. The gather (or the splat) writes one per pixel of its grid, so that the blur and
// the upsampling read one vec4 per neighbour instead of two textures and a projection.
fn rsm_gi_pack(px: RsmGiPixel) -> vec4<f32> {
    return vec4<f32>(px.normal, px.position.w);
}

// The filters' view of a packed pixel: its normal and view depth (no position).
fn rsm_gi_unpack(g: vec4<f32>) -> RsmGiPixel {
    var px: RsmGiPixel;
    px.position = vec4<f32>(0.0, 0.0, 0.0, g.w);
    px.normal = g.xyz;
    return px;
}

// Geometry-aware weight of neighbour q for centre c: -1 at a discontinuity (depth beyond
// the relative tolerance, or normals more than 60 degrees apart), else cos^power.
fn rsm_gi_geometry_weight(c: RsmGiPixel, q: RsmGiPixel, tolerance: f32, power: f32) -> f32 {
    let cosine = dot(c.normal, q.normal);
    if (q.position.w <= 0.0 || abs(q.position.w - c.position.w) > tolerance * c.position.w || cosine < 0.5) {
        return -1.0;
    }
    return pow(cosine, power);
}

// The full-resolution texel a low-resolution pixel `c` stands for (factor `f`; CPU twin:
// filter.rs `fine`): the centre of its f x f block, clamped to the image.
fn rsm_gi_texel(c: vec2<i32>, f: i32, full: vec2<i32>) -> vec2<i32> {
    return min(c * f + vec2<i32>(f / 2), full - vec2<i32>(1));
}
