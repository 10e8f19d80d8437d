//! What a read costs a fragment shader on this adapter: full-screen passes at 1600x900 that
//! each read 32 values per pixel from one kind of resource, interleaved over rounds, against
//! a pass that computes the same indices and reads nothing. On lavapipe (Mesa 22.3 on the
//! CPU, eight pixels to a SIMD group) the reads decide a shader's cost more than its
//! arithmetic: a storage buffer is read lane by lane, a branch per lane; a uniform array
//! indexed by a loop's counter is gathered lane by lane without the branches; only an index
//! the compiler sees as a constant (a loop of constant trip count, unrolled) is read once for
//! the whole group.
//!
//! `cargo run --release -p serein-gpu-harness --example load_costs [ROUNDS]`
//!
//! Measured (2 cores of an Intel Xeon, lavapipe, load 1.0, median of 20 rounds, two runs
//! within 2%): ms per pass of 32 reads a pixel, and per read once the no-read pass is taken
//! off (what one read of every pixel of a 1600x900 frame costs):
//!
//! | reads | ms | ms per read |
//! |---|---:|---:|
//! | none (indices only) | 26.7 | - |
//! | `vec4<u32>`, storage buffer, per-pixel index | 103.5 | 2.4 |
//! | `vec4<u32>`, `rgba32uint` texture, per-pixel index | 84.7 | 1.8 |
//! | `vec2<f32>`, storage buffer, loop index | 57.3 | 0.96 |
//! | `vec2<f32>`, `rg32float` texture, loop index | 67.5 | 1.3 |
//! | `vec2<f32>`, uniform array, loop index | 38.3 | 0.36 |
//! | `vec2<f32>`, uniform array, constant indices | 24.1 | 0 |
//!
//! The texture's row is a constant here; in a first version of this race, which computed it
//! per read from `textureDimensions` (and `countTrailingZeros` for the shift), the texture
//! was 13% slower than the storage buffer. In isolation, then, a per-pixel lookup gains
//! about a quarter from a texture, a small table read in a loop almost three times from a
//! uniform buffer, and fewer reads beat both; inside the engine's lighting pass none of
//! these moves showed in the frame when tried (`docs/ARCHITECTURE.md`, conventions).

use std::time::Instant;

/// The vertex shader and the per-pixel index every variant shares.
const COMMON: &str = r#"
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
// A different index per 8x8 block of pixels and per read, within 65536 vectors.
fn index(f: vec4<f32>, c: u32) -> u32 {
    let px = vec2<u32>(f.xy) / 8u;
    return (px.y * 211u + px.x * 7u + c * 97u) % 65536u;
}
"#;

/// One variant: its name, its binding's declaration, the read of value `c` (a `vec4<f32>`
/// expression that may use `f` and `c`) and the loop's trip count: `count.x` (32, from a
/// uniform, unknown to the compiler) or a constant 32 (the loop is unrolled, every index a
/// constant; `count` stays referenced so that every variant binds the same).
struct Variant {
    name: &'static str,
    binding: &'static str,
    read: &'static str,
    trips: &'static str,
}

const VARIANTS: [Variant; 7] = [
    Variant {
        name: "none (indices only)",
        binding: "",
        read: "vec4<f32>(f32(index(f, c)))",
        trips: "count.x",
    },
    Variant {
        name: "vec4<u32>, storage buffer, per-pixel index",
        binding: "var<storage, read> data: array<vec4<u32>>;",
        read: "vec4<f32>(data[index(f, c)])",
        trips: "count.x",
    },
    Variant {
        name: "vec4<u32>, rgba32uint texture, per-pixel index",
        binding: "var data: texture_2d<u32>;",
        read: "vec4<f32>(textureLoad(data, vec2<u32>(index(f, c) & 1023u, index(f, c) >> 10u), 0))",
        trips: "count.x",
    },
    Variant {
        name: "vec2<f32>, storage buffer, loop index",
        binding: "var<storage, read> data: array<vec2<f32>>;",
        read: "vec4<f32>(data[c] * f.x, 0.0, 0.0)",
        trips: "count.x",
    },
    Variant {
        name: "vec2<f32>, rg32float texture, loop index",
        binding: "var data: texture_2d<f32>;",
        read: "vec4<f32>(textureLoad(data, vec2<u32>(c, 0u), 0).xy * f.x, 0.0, 0.0)",
        trips: "count.x",
    },
    Variant {
        name: "vec2<f32>, uniform array, loop index",
        binding: "var<uniform> data: array<vec4<f32>, 32>;",
        read: "vec4<f32>(data[c].xy * f.x, 0.0, 0.0)",
        trips: "count.x",
    },
    Variant {
        name: "vec2<f32>, uniform array, constant indices",
        binding: "var<uniform> data: array<vec4<f32>, 32>;",
        read: "vec4<f32>(data[c].xy * f.x, 0.0, 0.0)",
        trips: "32u + 0u * count.x",
    },
];

const SIZE: (u32, u32) = (1600, 900);

fn source(v: &Variant) -> String {
    let binding = if v.binding.is_empty() {
        String::new()
    } else {
        format!("@group(0) @binding(1) {}", v.binding)
    };
    format!(
        "{COMMON}@group(0) @binding(0) var<uniform> count: vec4<u32>;
{binding}
@fragment fn fs(@builtin(position) f: vec4<f32>) -> @location(0) vec4<f32> {{
    var s = vec4<f32>(0.0);
    for (var c = 0u; c < {}; c++) {{
        s += {};
    }}
    return s * 1e-9;
}}",
        v.trips, v.read
    )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let rounds: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(10).max(1);
    let gpu = gpu_harness::GpuContext::new()?;
    println!("{}", gpu.describe());
    let d = &gpu.device;
    let words: Vec<u32> = (0..65536 * 4).collect();
    let texels = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    let wide =
        gpu_harness::texture_2d(d, "vec4s", (1024, 64), wgpu::TextureFormat::Rgba32Uint, texels);
    let narrow =
        gpu_harness::texture_2d(d, "vec2s", (32, 1), wgpu::TextureFormat::Rg32Float, texels);
    let floats: Vec<f32> = (0..128).map(|i| i as f32 * 0.01).collect();
    for (texture, bytes, row) in [
        (&wide, bytemuck::cast_slice(&words), 1024 * 16),
        (&narrow, bytemuck::cast_slice(&floats[..64]), 32 * 8),
    ] {
        let layout = wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(row),
            rows_per_image: None,
        };
        gpu.queue.write_texture(texture.as_image_copy(), bytes, layout, texture.size());
    }
    let views = [wide.create_view(&Default::default()), narrow.create_view(&Default::default())];
    let vec4s = gpu_harness::storage_buffer(d, "vec4s", bytemuck::cast_slice(&words));
    let vec2s = gpu_harness::storage_buffer(d, "vec2s", bytemuck::cast_slice(&floats[..64]));
    let uniform = gpu_harness::uniform_buffer(d, "vec4s", bytemuck::cast_slice(&floats));
    let count = gpu_harness::uniform_buffer(d, "count", bytemuck::cast_slice(&[32u32, 0, 0, 0]));
    let resources: [Option<wgpu::BindingResource>; 7] = [
        None,
        Some(vec4s.as_entire_binding()),
        Some(wgpu::BindingResource::TextureView(&views[0])),
        Some(vec2s.as_entire_binding()),
        Some(wgpu::BindingResource::TextureView(&views[1])),
        Some(uniform.as_entire_binding()),
        Some(uniform.as_entire_binding()),
    ];
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
    let target = gpu_harness::texture_2d(d, "target", SIZE, wgpu::TextureFormat::Rgba8Unorm, usage);
    let target = target.create_view(&Default::default());
    let passes: Vec<_> = VARIANTS
        .iter()
        .zip(resources)
        .map(|(v, resource)| {
            let format = wgpu::TextureFormat::Rgba8Unorm;
            let pipeline =
                gpu_harness::fullscreen_pipeline(d, v.name, &source(v), ("vs", "fs"), format);
            let layout = pipeline.get_bind_group_layout(0);
            let bound: Vec<_> =
                std::iter::once(count.as_entire_binding()).chain(resource).collect();
            let group = gpu_harness::bind_group(d, v.name, &layout, &bound);
            (pipeline, group)
        })
        .collect();
    let mut ms = vec![Vec::new(); passes.len()];
    // Two rounds to warm up, then the timed ones, the variants interleaved.
    for round in 0..rounds + 2 {
        for (k, (pipeline, group)) in passes.iter().enumerate() {
            let start = Instant::now();
            let mut enc = d.create_command_encoder(&Default::default());
            gpu_harness::draw_fullscreen(&mut enc, VARIANTS[k].name, pipeline, group, &target);
            gpu.queue.submit([enc.finish()]);
            d.poll(wgpu::PollType::wait_indefinitely())?;
            if round >= 2 {
                ms[k].push(start.elapsed().as_secs_f64() * 1e3);
            }
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let none = median(&mut ms[0]);
    println!("{}x{}, 32 reads a pixel, median of {rounds} rounds", SIZE.0, SIZE.1);
    for (v, times) in VARIANTS.iter().zip(&mut ms) {
        let m = median(times);
        println!("{:50} {m:8.1} ms {:6.2} ms per read", v.name, (m - none) / 32.0);
    }
    Ok(())
}
