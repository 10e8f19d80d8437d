// The paraboloid sky map's bilinear sample, the twin of atmosphere::SkyMap::sample: the upper
// hemisphere's radiance towards `dir` (normalised here; a direction below the horizon is read
// at the horizon in its azimuth; a zero direction or an empty map gives zero). The including
// shader defines `fn skymap_texel(index: i32) -> vec3<f32>` over its own binding (texels
// row-major, row j towards +z) and passes the map's size in texels per side.

fn skymap_sample(dir: vec3<f32>, size: i32) -> vec3<f32> {
    if size <= 0 || dot(dir, dir) == 0.0 {
        return vec3<f32>(0.0);
    }
    var d = normalize(dir);
    if d.y < 0.0 {
        let h = vec3<f32>(d.x, 0.0, d.z);
        d = select(vec3<f32>(1.0, 0.0, 0.0), normalize(h), dot(h, h) > 1e-12);
    }
    let disk = vec2<f32>(d.x, d.z) / (1.0 + d.y);
    let c = (disk + 1.0) * 0.5 * f32(size) - 0.5;
    let f = floor(c);
    let t = c - f;
    let x0 = clamp(i32(f.x), 0, size - 1);
    let y0 = clamp(i32(f.y), 0, size - 1);
    let x1 = clamp(i32(f.x) + 1, 0, size - 1);
    let y1 = clamp(i32(f.y) + 1, 0, size - 1);
    let a = mix(skymap_texel(y0 * size + x0), skymap_texel(y0 * size + x1), t.x);
    let b = mix(skymap_texel(y1 * size + x0), skymap_texel(y1 * size + x1), t.x);
    return mix(a, b, t.y);
}
