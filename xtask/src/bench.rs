//! `cargo xtask bench`: runs each crate's `gi_sweep` bench target and merges the parts.

use crate::{reliability, report, run_cmd};
use anyhow::Context;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The crates that have a sweep: every `crates/*/benches/gi_sweep.rs`, sorted by name.
fn sweep_crates(root: &Path) -> anyhow::Result<Vec<String>> {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(root.join("crates"))? {
        let dir = entry?.path();
        if dir.join("benches/gi_sweep.rs").exists() {
            names.push(dir.file_name().unwrap().to_string_lossy().into_owned());
        }
    }
    names.sort();
    Ok(names)
}

pub fn run(root: &Path, quick: bool, json: Option<PathBuf>, only: &[String]) -> anyhow::Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out_dir = root.join("target/gi-report");
    let parts_dir = out_dir.join("parts");
    std::fs::create_dir_all(&parts_dir)?;
    let crates = sweep_crates(root)?;
    // The engine's sweep (entries `engine/...`) lives in `app`, beside the reference comparisons.
    let only: Vec<String> =
        only.iter().map(|n| if n == "engine" { "app".to_owned() } else { n.clone() }).collect();
    let only = &only[..];
    for name in only {
        anyhow::ensure!(
            crates.contains(name),
            "no sweep for `{name}` (crates with one: {crates:?})"
        );
    }
    let selected: Vec<&String> =
        crates.iter().filter(|c| only.is_empty() || only.contains(c)).collect();
    // Build all sweeps first, so the timings below are not disturbed by compilation.
    let mut build = Command::new(&cargo);
    build.current_dir(root).args(["bench", "--no-run", "--bench", "gi_sweep"]);
    for c in &selected {
        build.args(["-p", &crate::package_name(root, c)?]);
    }
    run_cmd(&mut build)?;
    for (i, name) in selected.iter().enumerate() {
        eprintln!(
            "[{}/{}] sweep {name}{}",
            i + 1,
            selected.len(),
            if quick { " (quick)" } else { "" }
        );
        let part = parts_dir.join(format!("{name}.json"));
        let started = std::time::Instant::now();
        run_cmd(
            Command::new(&cargo)
                .current_dir(root)
                .args(["bench", "-q", "-p", &crate::package_name(root, name)?])
                .args(["--bench", "gi_sweep"])
                .env(gi_report::ENV_OUT, &part)
                .env(gi_report::ENV_QUICK, if quick { "1" } else { "0" }),
        )
        .with_context(|| format!("the sweep of `{name}` failed"))?;
        eprintln!("  {name}: {:.1} s", started.elapsed().as_secs_f64());
    }
    let mut merged = report::merge(&parts_dir, &crates, quick)?;
    if only.is_empty() {
        // The loaders' fuzzer with a fresh seed: half a minute quick, three minutes full.
        eprintln!("reliability: fuzzing the loaders");
        merged.reliability = Some(reliability::collect(root, if quick { 0.5 } else { 3.0 })?);
    }
    let text = serde_json::to_string_pretty(&merged)?;
    std::fs::write(out_dir.join("report.json"), &text)?;
    if let Some(path) = json {
        std::fs::write(&path, &text).with_context(|| format!("writing {}", path.display()))?;
    }
    report::redraw(&out_dir)?;
    eprintln!(
        "composed benchmarks (criterion, not in this report): cargo bench -p serein --bench {}",
        composed_benches(root).join(" | --bench ")
    );
    Ok(())
}

/// The root package's criterion benchmarks that compose crates (`benches/*.rs` but its
/// shared `support.rs`), by name.
fn composed_benches(root: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(root.join("benches"))
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| e.file_name().to_str()?.strip_suffix(".rs").map(str::to_owned))
        .filter(|n| n != "support")
        .collect();
    names.sort();
    names
}
