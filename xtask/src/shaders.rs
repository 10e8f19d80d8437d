//! naga validation of every top-level WGSL file under `shaders/`.
//!
//! Shared snippets are named `*.inc.wgsl` and are validated inside the shaders that include
//! them. A top-level shader names its snippets in leading comment lines of the form
//! `// include: sh_math/sh.inc.wgsl` (paths relative to `shaders/`); the Rust side builds the
//! same source from its own files (`crates/<crate>/shaders` is a link to `shaders/<crate>`, so
//! the package carries them: `include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/..."))`)
//! and from the snippets other crates export as `pub const`s (`sh_math::WGSL`), and each
//! crate's own test validates that string too.

use anyhow::Context;
use std::path::{Path, PathBuf};

/// Returns the number of shaders validated.
pub fn validate_all(root: &Path) -> anyhow::Result<usize> {
    let dir = root.join("shaders");
    let mut files = Vec::new();
    collect(&dir, &mut files)?;
    files.sort();
    let mut failures = Vec::new();
    for file in &files {
        if let Err(e) = validate(&dir, file) {
            failures.push(format!("{}: {e:#}", file.display()));
        }
    }
    anyhow::ensure!(failures.is_empty(), "WGSL validation failed:\n{}", failures.join("\n"));
    Ok(files.len())
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) -> anyhow::Result<()> {
    if !dir.exists() {
        return Ok(());
    }
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        if path.is_dir() {
            collect(&path, out)?;
        } else if name.ends_with(".wgsl") && !name.ends_with(".inc.wgsl") {
            out.push(path);
        }
    }
    Ok(())
}

/// The shader with its `// include:` snippets prepended, in order.
pub fn assemble(shaders_dir: &Path, file: &Path) -> anyhow::Result<String> {
    let body =
        std::fs::read_to_string(file).with_context(|| format!("reading {}", file.display()))?;
    let mut source = String::new();
    for line in body.lines().take_while(|l| l.trim_start().starts_with("//")) {
        if let Some(inc) = line.trim_start().trim_start_matches('/').trim().strip_prefix("include:")
        {
            let inc_path = shaders_dir.join(inc.trim());
            source += &std::fs::read_to_string(&inc_path)
                .with_context(|| format!("include {} not found", inc_path.display()))?;
            source.push('\n');
        }
    }
    source += &body;
    Ok(source)
}

fn validate(shaders_dir: &Path, file: &Path) -> anyhow::Result<()> {
    let source = assemble(shaders_dir, file)?;
    let module = naga::front::wgsl::parse_str(&source)
        .map_err(|e| anyhow::anyhow!("{}", e.emit_to_string(&source)))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|e| anyhow::anyhow!("{}", e.emit_to_string(&source)))?;
    Ok(())
}
