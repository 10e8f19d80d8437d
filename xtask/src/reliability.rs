//! The report's `reliability` section: the loaders' structure-aware fuzzer run for a short
//! budget with a fresh seed (inputs tried, failures, peak memory per target, from
//! `cargo xtask fuzz`'s summary) and the number of tests and property tests per crate.

use crate::fuzz;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

#[derive(Serialize, Deserialize)]
pub struct Reliability {
    pub fuzz: Vec<FuzzTarget>,
    /// Per crate: `#[test]` functions and proptest properties (functions of a `proptest!`
    /// block, counted from the source of `crates/<crate>/tests/`).
    pub tests: BTreeMap<String, TestCounts>,
}

#[derive(Serialize, Deserialize)]
pub struct FuzzTarget {
    pub target: String,
    pub seed: u64,
    pub inputs: u64,
    pub failures: usize,
    /// Peak resident memory while this target ran, MiB (Linux).
    pub peak_mib: Option<f64>,
}

#[derive(Serialize, Deserialize, Default)]
pub struct TestCounts {
    pub tests: usize,
    pub properties: usize,
}

/// The fuzzer's per-target outcome as `crates/scene/tests/fuzz_structured.rs` writes it.
#[derive(Deserialize)]
struct Outcome {
    target: String,
    seed: u64,
    inputs: u64,
    failures: Vec<String>,
    peak_mib: Option<f64>,
}

/// Runs the fuzzer for `minutes` over every target (a failure is recorded, not fatal: the
/// report shows it) and counts the tests.
pub fn collect(root: &Path, minutes: f64) -> anyhow::Result<Reliability> {
    if let Err(e) = fuzz::run(root, minutes, None, None) {
        eprintln!("fuzz run failed (recorded in the report): {e:#}");
    }
    let summary = std::fs::read_to_string(fuzz::summary_path(root))?;
    let outcomes: Vec<Outcome> = serde_json::from_str(&summary)?;
    let fuzz = outcomes
        .into_iter()
        .map(|o| FuzzTarget {
            target: o.target,
            seed: o.seed,
            inputs: o.inputs,
            failures: o.failures.len(),
            peak_mib: o.peak_mib,
        })
        .collect();
    Ok(Reliability { fuzz, tests: count_tests(root)? })
}

fn count_tests(root: &Path) -> anyhow::Result<BTreeMap<String, TestCounts>> {
    let mut out = BTreeMap::new();
    for entry in std::fs::read_dir(root.join("crates"))? {
        let dir = entry?.path();
        let mut counts = TestCounts::default();
        for file in rust_files(&dir.join("tests")) {
            let text = std::fs::read_to_string(&file)?;
            counts.tests += text.matches("#[test]").count();
            if text.contains("proptest!") {
                counts.properties += count_properties(&text);
            }
        }
        out.insert(dir.file_name().unwrap().to_string_lossy().into_owned(), counts);
    }
    Ok(out)
}

fn rust_files(dir: &Path) -> Vec<std::path::PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    let mut files = Vec::new();
    for path in entries.flatten().map(|e| e.path()) {
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files
}

/// Functions whose parameter list draws from a strategy (`fn name(x in strategy, ...)`).
fn count_properties(text: &str) -> usize {
    let mut n = 0;
    let mut rest = text;
    while let Some(i) = rest.find("fn ") {
        rest = &rest[i + 3..];
        let Some(open) = rest.find('(') else { break };
        if !rest[..open].chars().all(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let mut depth = 0usize;
        let mut end = rest.len();
        for (k, c) in rest[open..].char_indices() {
            match c {
                '(' => depth += 1,
                ')' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + k;
                        break;
                    }
                }
                _ => {}
            }
        }
        if rest[open..end].contains(" in ") {
            n += 1;
        }
    }
    n
}

pub fn markdown(r: &Reliability) -> String {
    let mut md = String::from(
        "\n## Reliability\n\nThe loaders' structure-aware fuzzer (`cargo xtask fuzz`), this run: \
         every input must load or give a typed error naming its file, within the memory bound.\n\n\
         | target | seed | inputs | failures | peak memory (MiB) |\n|---|---:|---:|---:|---:|\n",
    );
    for t in &r.fuzz {
        let peak = t.peak_mib.map_or("n/a".into(), |p| format!("{p:.0}"));
        md +=
            &format!("| {} | {} | {} | {} | {} |\n", t.target, t.seed, t.inputs, t.failures, peak);
    }
    md += "\nTests per crate (`#[test]` functions; properties: proptest functions drawing from \
           strategies).\n\n| crate | tests | properties |\n|---|---:|---:|\n";
    for (name, c) in &r.tests {
        md += &format!("| {name} | {} | {} |\n", c.tests, c.properties);
    }
    md
}

#[cfg(test)]
mod tests {
    use super::count_properties;

    #[test]
    fn properties_are_functions_drawing_from_strategies() {
        let text = "proptest! {\n #[test]\n fn a(x in 0..3, y in any::<u8>()) {}\n \
                    #[test]\n fn b(\n  v in vec(0..1, 1..(2)),\n) {}\n}\n fn helper(z: u32) {}\n";
        assert_eq!(count_properties(text), 2);
    }
}
