//! The structure-aware fuzzer of every loader: targets (the valid files each starts from and
//! how it mutates them), the run (a seeded proptest runner per batch, repeated until a case or
//! time budget is spent) and what it measured (inputs, failures, peak memory).
//!
//! Environment: `SEREIN_FUZZ_SEED` = a number (replay) or `random` (a new seed per run,
//! printed); unset, the run uses the fixed [`FIXED_SEED`] and then a fresh seed (printed), so
//! CI is reproducible and still explores; `SEREIN_FUZZ_CASES` (inputs per target, seed and
//! batch, default 250); `SEREIN_FUZZ_INPUT_MS` (the time one load may take before it counts
//! as a failure, default [`INPUT_MS`]);
//! `SEREIN_FUZZ_SECONDS` (keep running batches per target for this long);
//! `SEREIN_FUZZ_TARGET` (one target by name); `SEREIN_FUZZ_SUMMARY` (write a JSON summary).
#![allow(dead_code)]

pub mod mutate;

use crate::common::*;
use mutate::Step;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestError, TestRng, TestRunner};
use scene::{LoadOptions, Scene, SceneError};
use std::cell::Cell;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Peak resident memory a run may reach (the loaders' budgets keep it far below this).
pub const PEAK_BOUND_MIB: f64 = 1024.0;

/// The seed every plain test run starts with (then a fresh one): a failure in CI replays.
pub const FIXED_SEED: u64 = 20_261_207;

/// One load slower than this (ms) is a failure carrying its seed: the loaders' size budgets
/// keep every valid or mutated input of these small files to milliseconds even in a debug
/// build, so seconds mean a loop that does far more work than its input asks for.
pub const INPUT_MS: f64 = 5_000.0;

/// A loader under test: writes the mutated input (and what it references) into a folder and
/// returns the file to load.
pub struct Target {
    pub name: &'static str,
    prepare: fn(&Path, &[Step]) -> PathBuf,
}

pub const TARGETS: [Target; 6] = [
    Target { name: "gltf", prepare: gltf },
    Target { name: "glb", prepare: glb },
    Target { name: "obj_mtl", prepare: obj },
    Target { name: "scene_toml", prepare: toml },
    Target { name: "png", prepare: png_texture },
    Target { name: "gltf_nodes", prepare: gltf_nodes },
];

/// What one target's run measured.
#[derive(Debug, serde::Serialize)]
pub struct Outcome {
    pub target: &'static str,
    pub seed: u64,
    pub inputs: u64,
    pub failures: Vec<String>,
    /// Peak resident memory during this target (Linux; `None` elsewhere).
    pub peak_mib: Option<f64>,
    pub slowest_ms: f64,
}

/// The run's budget and seed, from the environment.
pub struct Plan {
    /// The seeds to run, one after the other.
    pub seeds: Vec<u64>,
    pub cases: u32,
    /// [`INPUT_MS`] unless the environment sets another bound.
    pub input_ms: f64,
    pub seconds: Option<f64>,
    pub only: Option<String>,
}

impl Plan {
    pub fn from_env() -> Self {
        let var = |k: &str| std::env::var(k).ok().filter(|v| !v.is_empty());
        // The fixed seed then a new one (printed, and in every failure's message); `random`
        // only a new one; a number replays.
        let fresh = || {
            let t = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH);
            t.map_or(1, |d| d.as_nanos() as u64 ^ u64::from(std::process::id()))
        };
        let seeds = match var("SEREIN_FUZZ_SEED").as_deref() {
            None => vec![FIXED_SEED, fresh()],
            Some("random") => vec![fresh()],
            Some(s) => vec![s.parse().expect("SEREIN_FUZZ_SEED: a number or `random`")],
        };
        Self {
            seeds,
            cases: var("SEREIN_FUZZ_CASES").and_then(|v| v.parse().ok()).unwrap_or(250),
            input_ms: var("SEREIN_FUZZ_INPUT_MS").and_then(|v| v.parse().ok()).unwrap_or(INPUT_MS),
            seconds: var("SEREIN_FUZZ_SECONDS").and_then(|v| v.parse().ok()),
            only: var("SEREIN_FUZZ_TARGET"),
        }
    }
}

fn steps() -> impl Strategy<Value = Vec<Step>> {
    prop::collection::vec((any::<u8>(), any::<u64>(), any::<u64>()), 1..8)
}

/// Runs one target under the plan from `seed`.
pub fn run(t: &Target, plan: &Plan, seed: u64) -> Outcome {
    let dir = std::env::temp_dir().join(format!("serein_fuzz_{}_{}", t.name, std::process::id()));
    let opts = LoadOptions::default();
    reset_peak();
    let start = Instant::now();
    let (inputs, slowest) = (Cell::new(0u64), Cell::new(0f64));
    let mut failures = Vec::new();
    for batch in 0u64.. {
        // Each batch's seed is printed: `SEREIN_FUZZ_SEED=<it>` replays that batch first.
        let batch_seed = seed.wrapping_add(batch.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let mut bytes = [0u8; 32];
        for (k, c) in bytes.chunks_mut(8).enumerate() {
            c.copy_from_slice(&(batch_seed ^ k as u64).to_le_bytes());
        }
        let config = Config {
            cases: plan.cases,
            failure_persistence: None,
            max_shrink_iters: 512,
            ..Config::default()
        };
        let mut runner =
            TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &bytes));
        let result = runner.run(&steps(), |s| {
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).unwrap();
            let path = (t.prepare)(&dir, &s);
            inputs.set(inputs.get() + 1);
            let t0 = Instant::now();
            let r = scene::load_with(&path, &opts);
            let ms = t0.elapsed().as_secs_f64() * 1e3;
            slowest.set(slowest.get().max(ms));
            if ms > plan.input_ms {
                return Err(TestCaseError::fail(format!(
                    "slow input: {ms:.0} ms, over the {:.0} ms bound",
                    plan.input_ms
                )));
            }
            check(r)
        });
        if let Err(e) = result {
            let what = match e {
                TestError::Fail(why, steps) => format!("{why}; minimal steps {steps:?}"),
                TestError::Abort(why) => format!("aborted: {why}"),
            };
            failures.push(format!(
                "{}: SEREIN_FUZZ_SEED={batch_seed} SEREIN_FUZZ_TARGET={}: {what}",
                t.name, t.name
            ));
            break;
        }
        if plan.seconds.is_none_or(|s| start.elapsed().as_secs_f64() >= s) {
            break;
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    Outcome {
        target: t.name,
        seed,
        inputs: inputs.get(),
        failures,
        peak_mib: peak_mib(),
        slowest_ms: slowest.get(),
    }
}

/// The property: a scene that validates, or a load error that names a file.
fn check(r: Result<Scene, SceneError>) -> Result<(), TestCaseError> {
    match r {
        Ok(s) => {
            prop_assert!(s.validate().is_ok(), "loaded an invalid scene: {:?}", s.validate());
            prop_assert!(s.triangles().positions.iter().all(|p| p.is_finite()));
        }
        Err(SceneError::Load(e)) => {
            prop_assert!(!e.file.is_empty() && !e.to_string().is_empty(), "{e:?}");
        }
        Err(other) => prop_assert!(false, "not a load error: {other}"),
    }
    Ok(())
}

/// Resets the kernel's peak-resident-memory counter of this process (Linux).
fn reset_peak() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

fn peak_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn split(steps: &[Step]) -> (Vec<Step>, Vec<Step>) {
    steps.iter().partition(|s| s.0 & 0x80 == 0)
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn finish_bytes(mut v: Vec<u8>, byte_steps: &[Step]) -> Vec<u8> {
    for &s in byte_steps {
        mutate::bytes_step(&mut v, s);
    }
    v
}

fn gltf(dir: &Path, steps: &[Step]) -> PathBuf {
    let (structural, bytes) = split(steps);
    let base = if steps.first().is_some_and(|s| s.1 & 1 == 0) {
        tiny_gltf(false)
    } else {
        textured_gltf()
    };
    let mut doc: serde_json::Value = serde_json::from_slice(&base).unwrap();
    for s in structural {
        mutate::json_step(&mut doc, s);
    }
    write(dir, "quad.bin", &quad_buffer(false).0);
    write(dir, "a.gltf", &finish_bytes(serde_json::to_vec(&doc).unwrap(), &bytes))
}

/// Only the node graph is mutated (children cycles, DAGs, repeats): the explosion target.
fn gltf_nodes(dir: &Path, steps: &[Step]) -> PathBuf {
    let mut doc: serde_json::Value = serde_json::from_slice(&tiny_gltf(false)).unwrap();
    for &(_, a, b) in steps {
        mutate::json_step(&mut doc, (4, a, b));
    }
    write(dir, "n.gltf", &serde_json::to_vec(&doc).unwrap())
}

fn glb(dir: &Path, steps: &[Step]) -> PathBuf {
    let (structural, bytes) = split(steps);
    let mut chunks = mutate::glb_chunks(&tiny_glb()).unwrap();
    let mut total = None;
    for s in structural {
        mutate::glb_step(&mut chunks, &mut total, s);
    }
    write(dir, "a.glb", &finish_bytes(mutate::glb_join(&chunks, total), &bytes))
}

fn lines(text: &str) -> Vec<String> {
    text.lines().map(str::to_owned).collect()
}

const OBJ_EXTRA: [&str; 14] = [
    "mtllib a.obj",
    "mtllib /dev/zero",
    "mtllib ../outside.mtl",
    "mtllib box.mtl",
    "f 1 2 99999999",
    "f -1 -2 -3",
    "f 1 1 1",
    "v 1e30 1e30 1e30",
    "usemtl nothing",
    "map_Kd t.png",
    "map_Kd /dev/zero",
    "map_Kd ../x.png",
    "map_d t.png",
    "newmtl shiny",
];

fn obj(dir: &Path, steps: &[Step]) -> PathBuf {
    let (mut o, mut m) = (lines(OBJ), lines(&format!("{MTL}map_Kd t.png")));
    for &s in steps {
        let file = if s.0 & 0x40 == 0 { &mut o } else { &mut m };
        mutate::lines_step(file, s, &OBJ_EXTRA);
    }
    write(dir, "t.png", &png(4, 4, |x, y| [x as u8 * 60, y as u8 * 60, 9, 255]));
    write(dir, "box.mtl", m.join("\n").as_bytes());
    write(dir, "a.obj", o.join("\n").as_bytes())
}

const TOML_EXTRA: [&str; 16] = [
    "[[mesh]]",
    "file = \"a.toml\"",
    "file = \"b.toml\"",
    "file = \"t.gltf\"",
    "file = \"/dev/zero\"",
    "file = \"../x.obj\"",
    "file = \".\"",
    "generated = \"plane_box\"",
    "seed = 18446744073709551615",
    "scale = 1e38",
    "rotate_y_deg = nan",
    "[sun]",
    "utc_hours = 1e300",
    "direction = [0.0, 0.0, 0.0]",
    "[camera]",
    "fov_y_deg = 180.0",
];

fn toml(dir: &Path, steps: &[Step]) -> PathBuf {
    let base = format!("{SCENE_TOML}\n[[mesh]]\nfile = \"b.toml\"\n");
    let (mut a, mut b) = (lines(&base), lines("[[mesh]]\nfile = \"t.gltf\"\n"));
    for &s in steps {
        let file = if s.0 & 0x40 == 0 { &mut a } else { &mut b };
        mutate::lines_step(file, s, &TOML_EXTRA);
    }
    write(dir, "t.gltf", &tiny_gltf(false));
    write(dir, "b.toml", b.join("\n").as_bytes());
    write(dir, "a.toml", a.join("\n").as_bytes())
}

fn png_texture(dir: &Path, steps: &[Step]) -> PathBuf {
    let (structural, bytes) = split(steps);
    let base = if steps.first().is_some_and(|s| s.1 & 1 == 0) {
        png(16, 9, |x, y| [x as u8 * 15, y as u8 * 25, 200, 128])
    } else {
        let img = image::GrayImage::from_fn(33, 17, |x, y| image::Luma([(x * y) as u8]));
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Png).unwrap();
        out.into_inner()
    };
    let mut chunks = mutate::png_chunks(&base).unwrap();
    for s in structural {
        mutate::png_step(&mut chunks, s);
    }
    write(dir, "t.png", &finish_bytes(mutate::png_join(&chunks), &bytes));
    write(dir, "box.mtl", format!("{MTL}map_Kd t.png\nmap_Bump t.png\n").as_bytes());
    write(dir, "a.obj", OBJ.as_bytes())
}
