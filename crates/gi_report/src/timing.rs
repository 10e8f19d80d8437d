//! Timing harness: medians of repeated runs, and interleaved races between two peers so that
//! machine noise cancels in their ratio.

use std::time::Instant;

pub use std::hint::black_box;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}

/// Runs `f` once to warm up and then `reps` times (at least once); returns the median wall time
/// in milliseconds and the last result.
pub fn time_ms<R>(reps: usize, mut f: impl FnMut() -> R) -> (f64, R) {
    let mut last = black_box(f());
    let mut times = Vec::with_capacity(reps.max(1));
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        last = black_box(f());
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    (median(times), last)
}

/// Median nanoseconds per call of `f`, measured in `batches` batches of `calls` calls each
/// (for operations far shorter than the timer's resolution).
pub fn time_ns_per_call<R>(batches: usize, calls: usize, mut f: impl FnMut(usize) -> R) -> f64 {
    let calls = calls.max(1);
    for i in 0..calls.min(1000) {
        black_box(f(i));
    }
    let times = (0..batches.max(1))
        .map(|_| {
            let t = Instant::now();
            for i in 0..calls {
                black_box(f(i));
            }
            t.elapsed().as_secs_f64() * 1e9 / calls as f64
        })
        .collect();
    median(times)
}

/// Races two implementations of the same work: `rounds` rounds, each timing `ours` then
/// `theirs` (order alternating every round), and returns their median times in milliseconds
/// `(ours_ms, theirs_ms)`.
pub fn interleaved(rounds: usize, mut ours: impl FnMut(), mut theirs: impl FnMut()) -> (f64, f64) {
    ours();
    theirs();
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let time = |f: &mut dyn FnMut()| {
        let t = Instant::now();
        f();
        t.elapsed().as_secs_f64() * 1e3
    };
    for round in 0..rounds.max(1) {
        if round % 2 == 0 {
            a.push(time(&mut ours));
            b.push(time(&mut theirs));
        } else {
            b.push(time(&mut theirs));
            a.push(time(&mut ours));
        }
    }
    (median(a), median(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 2.0, 3.0]), 2.5);
    }

    #[test]
    fn slower_work_takes_longer_in_an_interleaved_race() {
        let spin = |n: u64| (0..n).fold(0u64, |a, i| black_box(a.wrapping_add(i * i)));
        let (fast, slow) = interleaved(
            5,
            || {
                black_box(spin(10_000));
            },
            || {
                black_box(spin(2_000_000));
            },
        );
        assert!(slow > fast, "slow {slow} ms vs fast {fast} ms");
    }
}
