//! Structure-aware fuzzing of every loader (glTF, its node graph, GLB, OBJ + MTL, scene TOML
//! with includes, PNG textures): each input is a valid file mutated in its structure (see
//! `fuzz/mutate.rs`); every load must give a valid scene or a typed error naming a file, never a
//! panic, a hang or a stack overflow, and peak memory must stay under `PEAK_BOUND_MIB`.
//!
//! The normal test run spends a short budget on a fixed seed and then a new one (both printed);
//! `cargo xtask fuzz [--minutes N] [--target NAME] [--seed N]` runs longer. A load slower than
//! the plan's bound is a failure like any other. A failure prints `SEREIN_FUZZ_SEED=...`:
//! `SEREIN_FUZZ_SEED=<seed> SEREIN_FUZZ_TARGET=<name> cargo test -p serein-scene --test
//! fuzz_structured -- --nocapture` reproduces it. One `#[test]` runs the targets one after the
//! other so that each target's peak memory is its own.

mod common;
mod fuzz;

#[test]
fn every_loader_survives_structured_mutations_within_its_memory_budget() {
    let plan = fuzz::Plan::from_env();
    let mut outcomes = Vec::new();
    for &seed in &plan.seeds {
        eprintln!("fuzz seed {seed} (SEREIN_FUZZ_SEED={seed} replays it)");
        for t in fuzz::TARGETS.iter().filter(|t| plan.only.as_deref().is_none_or(|o| o == t.name)) {
            let o = fuzz::run(t, &plan, seed);
            eprintln!(
                "{:<11} {:>7} inputs, {} failures, peak {:.0} MiB, slowest {:.1} ms",
                o.target,
                o.inputs,
                o.failures.len(),
                o.peak_mib.unwrap_or(f64::NAN),
                o.slowest_ms
            );
            outcomes.push(o);
        }
    }
    if let Ok(path) = std::env::var("SEREIN_FUZZ_SUMMARY") {
        std::fs::write(&path, serde_json::to_string_pretty(&outcomes).unwrap()).unwrap();
    }
    assert!(!outcomes.is_empty(), "no fuzz target named {:?}", plan.only);
    let failures: Vec<&String> = outcomes.iter().flat_map(|o| &o.failures).collect();
    assert!(failures.is_empty(), "fuzz failures:\n{failures:#?}");
    for o in &outcomes {
        assert!(o.inputs > 0, "{}: no inputs tried", o.target);
        if let Some(p) = o.peak_mib {
            assert!(p < fuzz::PEAK_BOUND_MIB, "{}: peak {p:.0} MiB", o.target);
        }
    }
}
