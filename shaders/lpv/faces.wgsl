// include: lpv/common.inc.wgsl
// The geometry volume's blocking at the centre of every cell face (the mean of the face's 4
// corners; CPU twin: src/geometry.rs `GeometryVolume::faces`), from the fixed-point corners
// the RSM injection wrote. One invocation per (cell, axis).

@group(0) @binding(0) var<uniform> grid: LpvGrid;
// the geometry volume's fixed-point scale in x
@group(0) @binding(1) var<uniform> scale: vec4<f32>;
@group(0) @binding(2) var<storage, read> blocking: array<i32>;
@group(0) @binding(3) var<storage, read_write> faces: array<f32>;

fn corner(x: u32, y: u32, z: u32, k: u32) -> f32 {
    let m = grid.res + 1u;
    return f32(blocking[((z * m + y) * m + x) * 4u + k]);
}

@compute @workgroup_size(4, 4, 4)
fn faces_of(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = grid.res;
    if id.x >= n || id.y >= n || id.z >= n * 3u {
        return;
    }
    let x = id.x;
    let y = id.y;
    let z = id.z % n;
    let axis = id.z / n;
    for (var k = 0u; k < 4u; k++) {
        var s = 0.0;
        for (var o = 0u; o < 4u; o++) {
            let u = o >> 1u;
            let v = o & 1u;
            if axis == 0u {
                s += corner(x, y + u, z + v, k);
            } else if axis == 1u {
                s += corner(x + u, y, z + v, k);
            } else {
                s += corner(x + u, y + v, z, k);
            }
        }
        faces[((z * 12u + axis * 4u + k) * n + y) * n + x] = 0.25 * s / scale.x;
    }
}
