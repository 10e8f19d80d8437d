//! The scene crate's part of the report: generating the reference city with its texture mips
//! (`scene/load_city`, target < 200 ms on 2 cores) and one SceneNeeds query on it
//! (`scene/needs_city`, target < 1 ms), plus the other per-frame helpers.

use gi_report::{Entry, Sweep, black_box, time_ms, time_ns_per_call};
use scene::{Generated, Texture};

fn main() -> std::io::Result<()> {
    let mut sweep = Sweep::from_env("scene");
    let threads = rayon::current_num_threads();

    sweep.stage("load_city");
    let (ms, city) = time_ms(sweep.reps(20), || scene::city(1));
    let stats = city.stats();
    sweep.entry(
        Entry::new("scene/load_city", "generate", ms)
            .setting("triangles", stats.triangles)
            .setting("textures", stats.textures)
            .setting("texture_mib", stats.texture_bytes as f64 / (1 << 20) as f64)
            .threads(threads)
            .note("city generated from a seed, textures decoded sRGB->linear and mip-mapped; target < 200 ms on 2 cores"),
    );

    sweep.stage("needs_city");
    let ns = time_ns_per_call(sweep.reps(20), 200, |_| black_box(&city).needs());
    sweep.entry(
        Entry::new("scene/needs_city", "needs", ns * 1e-6)
            .setting("meshes", stats.meshes)
            .setting("triangles", stats.triangles)
            .note("one SceneNeeds (frustum tests of every mesh, material survey); target < 1 ms"),
    );

    sweep.stage("state_city");
    let ns = time_ns_per_call(sweep.reps(10), 20, |_| black_box(&city).state());
    sweep.entry(
        Entry::new("scene/state_city", "change_detection", ns * 1e-6)
            .note("snapshot for SceneChange (hashes all geometry)"),
    );

    sweep.stage("triangles_city");
    let (ms, tris) = time_ms(sweep.reps(20), || black_box(&city).triangles());
    sweep.entry(
        Entry::new("scene/triangles_city", "flatten", ms)
            .setting("triangles", tris.indices.len())
            .note("world-space positions + indices + mesh ids for an acceleration structure"),
    );

    for g in
        [Generated::CornellWindow, Generated::TwoRooms, Generated::PlaneBox, Generated::Furnace]
    {
        sweep.stage(g.name());
        let (ms, s) = time_ms(sweep.reps(20), || g.build(1));
        sweep.entry(
            Entry::new(format!("scene/load_{}", g.name()), "generate", ms)
                .setting("triangles", s.triangle_count()),
        );
    }

    let sizes: &[u32] = if sweep.quick() { &[256, 1000] } else { &[256, 1000, 2048, 4096] };
    for &n in sizes {
        sweep.stage(&format!("mips_{n}"));
        let bytes: Vec<u8> =
            (0..n * n * 4).map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8).collect();
        let (ms, t) = time_ms(sweep.reps(10), || {
            Texture::from_rgba8("bench", n, n, &bytes, scene::ColorSpace::Srgb)
        });
        let t = t.expect("valid texture");
        // Error: how far the smallest level's mean drifts from the full image's (the box
        // filter is area-exact, so this is float rounding only): relative to the mean.
        let mean = |l: &scene::TextureLevel| {
            l.texels.iter().map(|p| p.x as f64).sum::<f64>() / l.texels.len() as f64
        };
        let m0 = mean(&t.levels[0]);
        let drift = (mean(t.levels.last().expect("levels")) - m0).abs() / m0;
        sweep.entry(
            Entry::new(format!("scene/texture_mips_{n}"), "mips", ms)
                .setting("size", n)
                .error("rel_mean_drift", drift, "level_0_mean")
                .threads(threads),
        );
    }
    sweep.finish().map(|_| ())
}
