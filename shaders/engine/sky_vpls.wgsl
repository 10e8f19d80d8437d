// include: scene/brdf.inc.wgsl
// include: scene/material.inc.wgsl
// include: traced_effects/fresnel.inc.wgsl
// include: traced_effects/screen.inc.wgsl
// include: engine/common.inc.wgsl
// Sky light bounced once, as VPLs for the LPV (thesis 5.3.7, Fig. 5.16): the G-buffer sampled
// on a coarse grid of cells is a reflective shadow map of sky light. Two entry points, with
// the sky volume's lookup kernel (crate `sky_volume`) between them:
// - `queries`: per cell, the surface at the cell's centre pixel: its position and shading
//   normal go to the RSM's targets, and its sky-volume lookup query (albedo 1) to `queries`;
// - `flux`: once the lookup has turned the queries into E / pi, each VPL's flux: the
//   surface's diffuse reflectance times its sky irradiance times the area the cell covers
//   on it (the cell's solid angle times distance^2 over |n.v|, |n.v| at least 0.2), which is
//   what makes near and far surfaces bounce alike although the view samples them unevenly
//   (thesis Fig. 5.17). Clamped to `grid.limits.x`, the LPV's fixed-point bound.
// Background cells get a zero normal (an empty texel).

struct SkyVplGrid {
    // cells across, cells down, unused x2
    cells: vec4<u32>,
    // largest flux of one VPL (per channel), unused x3
    limits: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> grid: SkyVplGrid;
@group(0) @binding(2) var normal_t: texture_2d<f32>;
@group(0) @binding(3) var depth_t: texture_2d<f32>;
@group(0) @binding(4) var<storage, read_write> queries: array<SkyQuery>;
@group(0) @binding(5) var normal_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(6) var position_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(7) var base_t: texture_2d<f32>;
@group(0) @binding(8) var geometry_t: texture_2d<f32>;
@group(0) @binding(9) var<storage, read> materials: array<Material>;
@group(0) @binding(10) var<storage, read> sky_e: array<vec4<f32>>;
@group(0) @binding(11) var flux_out: texture_storage_2d<rgba32float, write>;

// The pixel at the centre of cell `c`, and the cell's size in pixels.
fn cell_pixel(c: vec2<u32>) -> vec2<i32> {
    let px = (vec2<f32>(c) + 0.5) * cell_pixels();
    return min(vec2<i32>(px), vec2<i32>(frame.size.xy) - 1);
}

fn cell_pixels() -> vec2<f32> {
    return vec2<f32>(frame.size.xy) / vec2<f32>(grid.cells.xy);
}

@compute @workgroup_size(8, 8)
fn sky_vpl_queries(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= grid.cells.x || id.y >= grid.cells.y {
        return;
    }
    let px = cell_pixel(id.xy);
    let depth = textureLoad(depth_t, px, 0).x;
    var p = vec3<f32>(0.0);
    var n = vec3<f32>(0.0);
    if depth > 0.0 {
        p = world_position(frame, vec2<f32>(px), depth);
        n = normalize(textureLoad(normal_t, px, 0).xyz);
    }
    queries[id.y * grid.cells.x + id.x] = SkyQuery(vec4<f32>(p, 1.0), vec4<f32>(n, 0.0), vec4<f32>(1.0));
    textureStore(normal_out, vec2<i32>(id.xy), vec4<f32>(n, 0.0));
    textureStore(position_out, vec2<i32>(id.xy), vec4<f32>(p, 1.0));
}

@compute @workgroup_size(8, 8)
fn sky_vpl_flux(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= grid.cells.x || id.y >= grid.cells.y {
        return;
    }
    let i = id.y * grid.cells.x + id.x;
    let q = queries[i];
    var flux = vec3<f32>(0.0);
    if dot(q.normal.xyz, q.normal.xyz) > 0.0 {
        let px = cell_pixel(id.xy);
        let pxf = vec2<f32>(px);
        let m = materials[u32(textureLoad(geometry_t, px, 0).w + 0.5)];
        let rho = material_diffuse_albedo(m, textureLoad(base_t, px, 0));
        let ray = view_ray(frame, pxf);
        let dx = length(view_ray(frame, pxf + vec2<f32>(1.0, 0.0)) - ray);
        let dy = length(view_ray(frame, pxf + vec2<f32>(0.0, 1.0)) - ray);
        let cells = cell_pixels();
        let solid_angle = dx * cells.x * dy * cells.y;
        let d = q.position.xyz - frame.camera_pos.xyz;
        let area = solid_angle * dot(d, d) / max(abs(dot(q.normal.xyz, ray)), 0.2);
        flux = min(rho * PI * sky_e[i].xyz * area, vec3<f32>(grid.limits.x));
    }
    textureStore(flux_out, vec2<i32>(id.xy), vec4<f32>(flux, 0.0));
}
