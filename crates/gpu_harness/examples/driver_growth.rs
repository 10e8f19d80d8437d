//! Resident memory over repeated submissions of one kind of GPU work, with nothing of the
//! workspace's crates around it: to tell a renderer's growth from its driver's.
//!
//! `cargo run --release -p serein-gpu-harness --example driver_growth -- MODE [N]` runs
//! `N` (default 300) iterations of `MODE` and prints `VmRSS` every tenth of them:
//!
//! - `idle`: submits an empty command buffer and waits (the baseline);
//! - `dispatch`: one compute pipeline made once, dispatched and waited for each iteration;
//! - `write`: the same with a uniform rewritten (`Queue::write_buffer`) before each dispatch;
//! - `create`: a compute pipeline made, dispatched once and dropped each iteration;
//! - `buffers`: a storage buffer made, bound, dispatched and dropped each iteration;
//! - `draw`: one render pipeline made once, a full-screen triangle drawn into a 160x90
//!   target each iteration;
//! - `timed`: the dispatch bracketed by two empty compute passes writing timestamps, each
//!   submitted alone, the stamps resolved and read back (what `frame_scheduler`'s
//!   `WgpuTimer` does around every GPU pass);
//! - `stamps`: the two timestamp passes alone, no dispatch and no read-back;
//! - `loop`: one pipeline whose loop count is read from a uniform buffer, that count
//!   changing every iteration (as a camera or a sun in a frame uniform does);
//! - `loop_same`: the same with the count never changing;
//! - `loop_storage`: the changing count read from a read-only storage buffer instead;
//! - `draw_loop`, `draw_loop_same`, `draw_loop_storage`: the same three with the loop in a
//!   fragment shader drawn over the 160x90 target;
//! - `branch`, `branch_storage`: a fragment shader of more than a hundred SSA values with a
//!   large branch and a loop skipped on a uniform count (0, never changing), read from a
//!   uniform buffer or from a read-only storage buffer.
//!
//! Issue 57 §1 (the soak's growth of about 5 MiB per frame on Mesa 22.3's lavapipe): 200 to
//! 300 iterations of every mode here stay flat after the first tenth (0.0 KiB per iteration;
//! `create` 0.4), so creating and dropping objects, write_buffer's staging, timestamps and
//! read-backs are not what grows. What grew was the engine's lighting shader compiled anew
//! at every bind: lavapipe inlines uniform values its branches depend on when that removes
//! most of the shader (`shaders/engine/lighting.wgsl`, `load_frame`). The `branch` mode
//! aims at that and does not trigger it (no JIT after the first draw, as `branch_storage`): lavapipe's
//! criteria (which uniforms it collects, how much the inlined shader must shrink) are not
//! met by this small shader; the lighting shader is the reproduction.

const COMPUTE: &str = r#"
struct P { k: f32, n: u32 }
@group(0) @binding(0) var<uniform> p: P;
@group(0) @binding(1) var<storage, read_write> out: array<f32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < p.n { out[id.x] = sin(f32(id.x) * p.k); }
}
"#;

/// A loop whose trip count is a uniform (`LOOP_UNIFORM`) or a storage value
/// (`LOOP_STORAGE`): Mesa's lavapipe compiles a variant of the shader for each value of a
/// uniform that decides control flow ("uniform inlining") and keeps every variant.
const LOOP_UNIFORM: &str = r#"
struct P { k: f32, n: u32 }
@group(0) @binding(0) var<uniform> p: P;
@group(0) @binding(1) var<storage, read_write> out: array<f32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    var s = 0.0;
    for (var i = 0u; i < p.n; i++) { s += sin(f32(i + id.x)); }
    out[id.x] = s;
}
"#;

const LOOP_STORAGE: &str = r#"
struct P { k: f32, n: u32 }
@group(0) @binding(0) var<storage, read> p: P;
@group(0) @binding(1) var<storage, read_write> out: array<f32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    var s = 0.0;
    for (var i = 0u; i < p.n; i++) { s += sin(f32(i + id.x)); }
    out[id.x] = s;
}
"#;

/// The loop of [`LOOP_UNIFORM`] in a fragment shader; `VAR` is replaced by the binding's
/// address space (`uniform` or `storage, read`).
const DRAW_LOOP: &str = r#"
struct P { k: f32, n: u32 }
@group(0) @binding(0) var<VAR> p: P;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) q: vec4<f32>) -> @location(0) vec4<f32> {
    var s = 0.0;
    for (var i = 0u; i < p.n; i++) { s += sin(f32(i) + q.x); }
    if p.k > 0.5 { s = -s; }
    return vec4<f32>(s, 0.0, 0.5, 1.0);
}
"#;

/// A large branch and a loop on `p.n`, in a shader big enough for lavapipe to inline the uniform.
const DRAW_BRANCH: &str = r#"
struct P { k: f32, n: u32 }
@group(0) @binding(0) var<VAR> p: P;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}
fn wave(x: f32, y: f32) -> f32 {
    return sin(x * 1.3 + y) * cos(y * 0.7 - x) + sqrt(abs(x * y) + 1.0);
}
@fragment fn fs(@builtin(position) q: vec4<f32>) -> @location(0) vec4<f32> {
    var s = q.x * 0.01;
    if p.n != 0u {
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
    }
    for (var i = 0u; i < p.n; i++) {
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
        s = wave(s, q.y); s = wave(s, q.x); s = wave(s, q.y); s = wave(s, q.x);
    }
    return vec4<f32>(s, p.k, 0.5, 1.0);
}
"#;

const DRAW: &str = r#"
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(sin(p.x * 0.1), cos(p.y * 0.1), 0.5, 1.0);
}
"#;

fn rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmRSS:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse().ok()))
        })
        .unwrap_or(0)
}

/// Waits for the queue and prints `VmRSS` every tenth of `n` iterations.
fn continue_frame(
    device: &wgpu::Device,
    i: u32,
    n: u32,
    first_tenth: &mut u64,
) -> Result<(), Box<dyn std::error::Error>> {
    device.poll(wgpu::PollType::wait_indefinitely())?;
    let tenth = (n / 10).max(1);
    if (i + 1).is_multiple_of(tenth) {
        let rss = rss_kib();
        if i + 1 == tenth {
            *first_tenth = rss;
        }
        let since = rss as i64 - *first_tenth as i64;
        println!(
            "{:>6} iterations: VmRSS {rss:>8} KiB ({since:+} KiB since the first tenth)",
            i + 1
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let mode = args.next().unwrap_or_else(|| "dispatch".into());
    let n: u32 = args.next().map(|s| s.parse()).transpose()?.unwrap_or(300);
    let ctx = gpu_harness::GpuContext::new()?;
    let (device, queue) = (&ctx.device, &ctx.queue);
    println!("{} mode {mode}, {n} iterations", ctx.describe());

    const LEN: u32 = 160 * 90;
    let params =
        gpu_harness::uniform_buffer(device, "params", bytemuck::cast_slice(&[0.1f32, 0.0]));
    queue.write_buffer(&params, 4, bytemuck::bytes_of(&LEN));
    let out = gpu_harness::empty_storage(device, "out", LEN as u64 * 4);
    let make = || gpu_harness::compute_pipeline(device, "growth", COMPUTE, "main", None);
    let pipeline = make();
    let bind = |p: &wgpu::ComputePipeline, out: &wgpu::Buffer| {
        gpu_harness::bind_group(
            device,
            "growth",
            &p.get_bind_group_layout(0),
            &[params.as_entire_binding(), out.as_entire_binding()],
        )
    };
    let group = bind(&pipeline, &out);
    let target = gpu_harness::texture_2d(
        device,
        "target",
        (160, 90),
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    );
    let target = target.create_view(&Default::default());
    let draw = gpu_harness::fullscreen_pipeline(
        device,
        "growth draw",
        DRAW,
        ("vs", "fs"),
        wgpu::TextureFormat::Rgba8Unorm,
    );
    let groups = [LEN.div_ceil(64), 1, 1];
    let looped = gpu_harness::compute_pipeline(device, "loop", LOOP_UNIFORM, "main", None);
    let loop_group = bind(&looped, &out);
    let storage_params = gpu_harness::storage_buffer(device, "params", &[0; 16]);
    let looped_storage =
        gpu_harness::compute_pipeline(device, "loop storage", LOOP_STORAGE, "main", None);
    let loop_storage_group = gpu_harness::bind_group(
        device,
        "loop storage",
        &looped_storage.get_bind_group_layout(0),
        &[storage_params.as_entire_binding(), out.as_entire_binding()],
    );
    let draw_with = |shader: &str, var: &str| {
        let source = shader.replace("VAR", var);
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let p =
            gpu_harness::fullscreen_pipeline(device, "draw loop", &source, ("vs", "fs"), format);
        let params = if var == "uniform" { &params } else { &storage_params };
        let g = gpu_harness::bind_group(
            device,
            "draw loop",
            &p.get_bind_group_layout(0),
            &[params.as_entire_binding()],
        );
        (p, g)
    };
    let draw_uniform = draw_with(DRAW_LOOP, "uniform");
    let draw_storage = draw_with(DRAW_LOOP, "storage, read");
    let branch_uniform = draw_with(DRAW_BRANCH, "uniform");
    let branch_storage = draw_with(DRAW_BRANCH, "storage, read");
    let timed = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
    let set = timed.then(|| {
        device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("stamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        })
    });
    let resolve = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("stamps"),
        size: 256,
        usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let read_back = gpu_harness::ReadBack::new(device, "stamps", 16);
    let stamp = |index: u32| {
        let Some(set) = &set else { return };
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let writes = wgpu::ComputePassTimestampWrites {
                query_set: set,
                beginning_of_pass_write_index: (index == 0).then_some(0),
                end_of_pass_write_index: (index == 1).then_some(1),
            };
            let _pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("stamp"),
                timestamp_writes: Some(writes),
            });
        }
        queue.submit([enc.finish()]);
    };
    if !timed && matches!(mode.as_str(), "timed" | "stamps") {
        return Err("the adapter lacks TIMESTAMP_QUERY".into());
    }

    let start = rss_kib();
    let mut first_tenth = start;
    for i in 0..n {
        let mut enc = device.create_command_encoder(&Default::default());
        match mode.as_str() {
            "idle" => {}
            "dispatch" => gpu_harness::dispatch(&mut enc, &pipeline, &group, groups),
            "write" => {
                queue.write_buffer(&params, 0, bytemuck::bytes_of(&(i as f32 * 0.01)));
                gpu_harness::dispatch(&mut enc, &pipeline, &group, groups);
            }
            "create" => {
                let p = make();
                let g = bind(&p, &out);
                gpu_harness::dispatch(&mut enc, &p, &g, groups);
            }
            "buffers" => {
                let b = gpu_harness::empty_storage(device, "per iteration", LEN as u64 * 4);
                let g = bind(&pipeline, &b);
                gpu_harness::dispatch(&mut enc, &pipeline, &g, groups);
            }
            "draw" => {
                let mut pass = gpu_harness::clear_pass(&mut enc, "growth", &target);
                pass.set_pipeline(&draw);
                pass.draw(0..3, 0..1);
            }
            "timed" => {
                stamp(0);
                let mut work = device.create_command_encoder(&Default::default());
                gpu_harness::dispatch(&mut work, &pipeline, &group, groups);
                queue.submit([work.finish()]);
                stamp(1);
                if let Some(set) = &set {
                    enc.resolve_query_set(set, 0..2, &resolve, 0);
                    read_back.read_after(device, queue, enc, &resolve, 16)?;
                }
                continue_frame(device, i, n, &mut first_tenth)?;
                continue;
            }
            "loop" | "loop_same" => {
                let count: u32 = if mode == "loop" { 8 + i } else { 8 };
                queue.write_buffer(&params, 4, bytemuck::bytes_of(&count));
                gpu_harness::dispatch(&mut enc, &looped, &loop_group, groups);
            }
            "loop_storage" => {
                queue.write_buffer(&storage_params, 4, bytemuck::bytes_of(&(8 + i)));
                gpu_harness::dispatch(&mut enc, &looped_storage, &loop_storage_group, groups);
            }
            "draw_loop" | "draw_loop_same" | "draw_loop_storage" => {
                let (count, k) = if mode == "draw_loop_same" {
                    (8, 0.0)
                } else {
                    (8 + i, 0.3 + (i % 2) as f32 * 0.5)
                };
                let (buffer, (p, g)) = match mode.as_str() {
                    "draw_loop_storage" => (&storage_params, &draw_storage),
                    _ => (&params, &draw_uniform),
                };
                queue.write_buffer(buffer, 0, bytemuck::bytes_of(&k));
                queue.write_buffer(buffer, 4, bytemuck::bytes_of(&count));
                let mut pass = gpu_harness::clear_pass(&mut enc, "draw loop", &target);
                pass.set_pipeline(p);
                pass.set_bind_group(0, g, &[]);
                pass.draw(0..3, 0..1);
            }
            "branch" | "branch_storage" => {
                let (buffer, (p, g)) = match mode.as_str() {
                    "branch" => (&params, &branch_uniform),
                    _ => (&storage_params, &branch_storage),
                };
                // The flag off: inlined, it removes the branch.
                queue.write_buffer(buffer, 4, bytemuck::bytes_of(&0u32));
                let mut pass = gpu_harness::clear_pass(&mut enc, "branch", &target);
                pass.set_pipeline(p);
                pass.set_bind_group(0, g, &[]);
                pass.draw(0..3, 0..1);
            }
            "stamps" => {
                stamp(0);
                stamp(1);
            }
            other => return Err(format!("unknown mode {other}").into()),
        }
        queue.submit([enc.finish()]);
        continue_frame(device, i, n, &mut first_tenth)?;
    }
    let end = rss_kib();
    let per = (end as f64 - first_tenth as f64) / (n as f64 * 0.9);
    println!(
        "{mode}: {start} KiB at the start, {end} KiB at the end, {per:.1} KiB per iteration after the first tenth"
    );
    Ok(())
}
