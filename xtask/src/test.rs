//! `cargo xtask test`: the checks CI runs, in the order that fails fastest.

use crate::{package_check, run_cmd, shaders};
use std::path::Path;
use std::process::Command;

pub fn run(root: &Path, test_args: &[String]) -> anyhow::Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    run_cmd(Command::new(&cargo).current_dir(root).args(["fmt", "--all", "--check"]))?;
    run_cmd(Command::new(&cargo).current_dir(root).args([
        "clippy",
        "--workspace",
        "--all-targets",
        "--all-features",
        "--",
        "-D",
        "warnings",
    ]))?;
    let n = shaders::validate_all(root)?;
    eprintln!("naga: {n} top-level WGSL shaders valid");
    // After clippy, whose dependency artifacts the packaged crates' checks reuse.
    package_check::run(root)?;
    // The report page, built from a small fixture, rendered in headless Chromium.
    crate::browser::check(root)?;
    // Last, so the run ends with the test runner's own summary. Property tests draw from a
    // fixed seed unless the caller picks another (`PROPTEST_RNG_SEED`), so CI is reproducible;
    // `--no-fail-fast` reports every failing test binary, not just the first.
    let seed = std::env::var("PROPTEST_RNG_SEED").unwrap_or_else(|_| "20261122".into());
    run_cmd(
        Command::new(&cargo)
            .current_dir(root)
            .env("PROPTEST_RNG_SEED", seed)
            .args(["test", "--workspace", "--all-features", "--no-fail-fast", "--"])
            .args(test_args),
    )
}
