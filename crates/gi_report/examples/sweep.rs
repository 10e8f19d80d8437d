//! Use `gi_report` for your technique: measure it at a few settings against a reference and
//! write one entry per setting. Here the "technique" estimates pi by the midpoint rule with
//! `n` intervals, and the reference is the closed form; each entry has its time and its
//! relative error, which is what the report plots (error on one axis, milliseconds on the
//! other). Run alone it prints the JSON part; `cargo xtask bench` would merge it into the
//! report.
//!
//! `cargo run -p serein-gi-report --example sweep`

use gi_report::{Entry, Sweep, rel_rms, time_ms};

fn estimate_pi(n: u32) -> f64 {
    let h = 1.0 / n as f64;
    (0..n).map(|i| 4.0 / (1.0 + ((i as f64 + 0.5) * h).powi(2))).sum::<f64>() * h
}

fn main() -> std::io::Result<()> {
    let mut sweep = Sweep::from_env("my_crate");
    for n in [4u32, 16, 64, 256, 1024] {
        sweep.stage(&format!("{n} intervals"));
        let (ms, pi) = time_ms(sweep.reps(50), || estimate_pi(std::hint::black_box(n)));
        let error = rel_rms(&[pi], &[std::f64::consts::PI]);
        sweep.entry(
            Entry::new(format!("my_crate/midpoint_{n}"), "midpoint", ms)
                .setting("intervals", n)
                .error("rel_rms", error, "closed_form")
                .threads(1),
        );
    }
    sweep.finish()?;
    Ok(())
}
