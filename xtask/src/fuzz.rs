//! `cargo xtask fuzz [--minutes N] [--target NAME] [--seed S]`: the loaders' structure-aware
//! fuzzer (`crates/scene/tests/fuzz_structured.rs`) run for longer than the test suite's short
//! budget, with a new seed each run (printed; a failure prints the seed that reproduces it).
//! Writes `target/fuzz/summary.json`: per target, inputs tried, failures, peak memory.

use crate::run_cmd;
use std::path::Path;
use std::process::Command;

pub fn run(
    root: &Path,
    minutes: f64,
    target: Option<&str>,
    seed: Option<&str>,
) -> anyhow::Result<()> {
    anyhow::ensure!(minutes > 0.0 && minutes.is_finite(), "--minutes must be positive");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = root.join("target/fuzz");
    std::fs::create_dir_all(&out)?;
    // The time is shared between the targets that run.
    let targets = if target.is_some() { 1.0 } else { 6.0 };
    let summary = summary_path(root);
    let mut cmd = Command::new(cargo);
    cmd.current_dir(root)
        .env("SEREIN_FUZZ_SEED", seed.unwrap_or("random"))
        .env("SEREIN_FUZZ_SECONDS", format!("{}", minutes * 60.0 / targets))
        .env("SEREIN_FUZZ_CASES", "200")
        .env("SEREIN_FUZZ_SUMMARY", &summary)
        .args([
            "test",
            "--release",
            "-p",
            &crate::package_name(root, "scene")?,
            "--test",
            "fuzz_structured",
            "--",
            "--nocapture",
        ]);
    if let Some(t) = target {
        cmd.env("SEREIN_FUZZ_TARGET", t);
    }
    run_cmd(&mut cmd)?;
    eprintln!("fuzz summary: {}", summary.display());
    Ok(())
}

/// Where `run` writes its summary.
pub fn summary_path(root: &Path) -> std::path::PathBuf {
    root.join("target/fuzz/summary.json")
}
