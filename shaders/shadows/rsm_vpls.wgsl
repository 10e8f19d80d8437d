// The reflective shadow map reduced to VPLs, one per block x block tile of texels: the
// twin of crates/shadows/src/rsm.rs `Rsm::extract_vpls` (same sums in the same order): the
// tile's summed flux, its luminance-weighted mean position and normal (plain means where
// the flux is zero). Covered texels have normal.w = 1 and a non-zero normal. One invocation
// per tile; position.w = 1 where the tile has a covered texel (else the tile gives no VPL).

struct Params {
    resolution: u32,
    block: u32,
    tiles_x: u32,
    _pad: u32,
}

struct GpuVpl {
    position: vec4<f32>,
    normal: vec4<f32>,
    flux: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var flux_t: texture_2d<f32>;
@group(0) @binding(2) var normal_t: texture_2d<f32>;
@group(0) @binding(3) var position_t: texture_2d<f32>;
@group(0) @binding(4) var<storage, read_write> vpls: array<GpuVpl>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let tiles = params.tiles_x;
    if (id.x >= tiles || id.y >= tiles) {
        return;
    }
    let b = params.block;
    let n = params.resolution;
    var flux = vec3<f32>(0.0);
    var pw = vec3<f32>(0.0);
    var nw = vec3<f32>(0.0);
    var wsum = 0.0;
    var pp = vec3<f32>(0.0);
    var np = vec3<f32>(0.0);
    var count = 0u;
    for (var y = id.y * b; y < min((id.y + 1u) * b, n); y++) {
        for (var x = id.x * b; x < min((id.x + 1u) * b, n); x++) {
            let t = vec2<i32>(i32(x), i32(y));
            let nt = textureLoad(normal_t, t, 0);
            if (!(nt.w > 0.5) || all(nt.xyz == vec3<f32>(0.0))) {
                continue;
            }
            let f = textureLoad(flux_t, t, 0).xyz;
            let p = textureLoad(position_t, t, 0).xyz;
            let lum = max(dot(f, vec3<f32>(0.2126, 0.7152, 0.0722)), 0.0);
            flux += f;
            pw += p * lum;
            nw += nt.xyz * lum;
            wsum += lum;
            pp += p;
            np += nt.xyz;
            count += 1u;
        }
    }
    var out: GpuVpl;
    out.position = vec4<f32>(0.0);
    out.normal = vec4<f32>(0.0);
    out.flux = vec4<f32>(flux, 0.0);
    if (count > 0u) {
        var position = pp / f32(count);
        var normal = np;
        if (wsum > 0.0) {
            position = pw / wsum;
            normal = nw;
        }
        let l = length(normal);
        let lp = length(np);
        if (l > 0.0) {
            normal = normal / l;
        } else if (lp > 0.0) {
            normal = np / lp;
        } else {
            normal = vec3<f32>(0.0);
        }
        out.position = vec4<f32>(position, 1.0);
        out.normal = vec4<f32>(normal, 0.0);
    }
    vpls[id.y * tiles + id.x] = out;
}
