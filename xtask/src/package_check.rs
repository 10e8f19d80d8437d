//! `cargo xtask package-check`: every publishable crate under `crates/` packages, carries its
//! license files, and its packaged `.crate` compiles outside the workspace, once with its
//! default features and once with all of them (`gpu`, `bvh`, `load`, ...).
//!
//! The crates are packaged together (`cargo package -p a -p b ...`: cargo resolves the
//! unpublished ones through a local registry of the packages it just made), unpacked into
//! `target/package-check/`, and checked there as members of a throw-away workspace whose
//! `[patch.crates-io]` points each `serein-*` dependency at its unpacked package, so nothing
//! reaches back into this repository: a shader, license or path outside a package fails here.
//! That workspace takes this one's `Cargo.lock` and profiles and builds into this workspace's
//! target directory, so the third-party dependencies compiled for clippy are reused.

use crate::run_cmd;
use anyhow::Context;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A package this check covers, from `cargo metadata`.
struct Package {
    name: String,
    version: String,
    has_features: bool,
}

pub fn run(root: &Path) -> anyhow::Result<()> {
    let started = std::time::Instant::now();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let (packages, target_dir) = publishable(root, &cargo)?;
    anyhow::ensure!(!packages.is_empty(), "no publishable crate under crates/");

    let mut package = Command::new(&cargo);
    package.current_dir(root).args(["package", "--no-verify", "--allow-dirty", "--quiet"]);
    for p in &packages {
        package.args(["-p", &p.name]);
    }
    run_cmd(&mut package)?;

    let scratch = target_dir.join("package-check");
    if scratch.exists() {
        std::fs::remove_dir_all(&scratch)
            .with_context(|| format!("removing {}", scratch.display()))?;
    }
    std::fs::create_dir_all(&scratch)?;
    let mut manifest = String::from(
        "# Written by `cargo xtask package-check`: the packaged crates, outside the workspace.\n\
         [workspace]\nresolver = \"3\"\nmembers = [\n",
    );
    let mut patches = String::from("\n[patch.crates-io]\n");
    for p in &packages {
        let dir = format!("{}-{}", p.name, p.version);
        let file = target_dir.join("package").join(format!("{dir}.crate"));
        // `-m`: the files get the time of extraction, not the fixed time `cargo package` writes
        // into every `.crate`, so cargo sees a changed file as changed.
        run_cmd(Command::new("tar").arg("-xzmf").arg(&file).arg("-C").arg(&scratch))?;
        for license in ["LICENSE-MIT", "LICENSE-APACHE"] {
            anyhow::ensure!(
                scratch.join(&dir).join(license).is_file(),
                "{} has no {license}",
                file.display()
            );
        }
        manifest += &format!("    \"{dir}\",\n");
        patches += &format!("{} = {{ path = \"{dir}\" }}\n", p.name);
    }
    manifest += "]\n";
    manifest += &patches;
    manifest += &profiles(root)?;
    std::fs::write(scratch.join("Cargo.toml"), manifest)?;
    std::fs::copy(root.join("Cargo.lock"), scratch.join("Cargo.lock"))
        .context("copying Cargo.lock")?;

    let mut failures = Vec::new();
    for p in &packages {
        let modes: &[&[&str]] = if p.has_features { &[&[], &["--all-features"]] } else { &[&[]] };
        for extra in modes {
            let mut check = Command::new(&cargo);
            check
                .current_dir(&scratch)
                .env("CARGO_TARGET_DIR", &target_dir)
                .args(["check", "--quiet", "--lib", "-p", &p.name])
                .args(*extra);
            if let Err(e) = run_cmd(&mut check) {
                failures.push(format!("{} {}: {e}", p.name, extra.join(" ")));
            }
        }
    }
    anyhow::ensure!(
        failures.is_empty(),
        "packaged crates that do not build on their own:\n{}",
        failures.join("\n")
    );
    eprintln!(
        "package-check: {} crates packaged and built outside the workspace in {:.0} s",
        packages.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The publishable packages under `crates/` (a `publish = false` one is skipped) and the
/// target directory, from `cargo metadata`.
fn publishable(root: &Path, cargo: &str) -> anyhow::Result<(Vec<Package>, PathBuf)> {
    let out = Command::new(cargo)
        .current_dir(root)
        .args(["metadata", "--no-deps", "--format-version", "1"])
        .output()
        .context("running cargo metadata")?;
    anyhow::ensure!(out.status.success(), "cargo metadata failed");
    let meta: serde_json::Value = serde_json::from_slice(&out.stdout)?;
    let crates_dir = root.join("crates");
    let mut packages = Vec::new();
    for p in meta["packages"].as_array().context("metadata without packages")? {
        let manifest = PathBuf::from(p["manifest_path"].as_str().unwrap_or_default());
        let unpublished = p["publish"].as_array().is_some_and(|r| r.is_empty());
        if !manifest.starts_with(&crates_dir) || unpublished {
            continue;
        }
        packages.push(Package {
            name: p["name"].as_str().context("package without a name")?.to_owned(),
            version: p["version"].as_str().context("package without a version")?.to_owned(),
            has_features: p["features"].as_object().is_some_and(|f| !f.is_empty()),
        });
    }
    packages.sort_by(|a, b| a.name.cmp(&b.name));
    let target = meta["target_directory"].as_str().context("metadata without target_directory")?;
    Ok((packages, PathBuf::from(target)))
}

/// The workspace's `[profile.*]` tables, so that the dependencies' artifacts are the ones the
/// workspace's own builds made.
fn profiles(root: &Path) -> anyhow::Result<String> {
    let text = std::fs::read_to_string(root.join("Cargo.toml"))?;
    let table: toml::Table = text.parse().context("parsing Cargo.toml")?;
    let Some(profile) = table.get("profile") else { return Ok(String::new()) };
    let mut wrapper = toml::Table::new();
    wrapper.insert("profile".into(), profile.clone());
    Ok(format!("\n{}", toml::to_string(&wrapper)?))
}
