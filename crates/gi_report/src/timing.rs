//! Timing harness: medians of repeated runs with their spread, and interleaved races between two
//! peers so that machine noise cancels in their ratio (with an interval from the pairs).
//!
//! Every timing this module takes is also remembered (the last few hundred) so that
//! [`crate::Sweep::entry`] and [`crate::Sweep::comparison`] can attach the spread and the
//! ratio's interval to the entry or comparison made from it, without the sweep passing them on.

use std::sync::Mutex;
use std::time::Instant;

pub use std::hint::black_box;

fn median_sorted(v: &[f64]) -> f64 {
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}

#[cfg(test)]
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    median_sorted(&v)
}

/// Linear-interpolated quantile `q` in [0, 1] of sorted samples.
fn quantile_sorted(v: &[f64], q: f64) -> f64 {
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    let pos = q * (n - 1) as f64;
    let (i, frac) = (pos.floor() as usize, pos.fract());
    if i + 1 < n { v[i] + frac * (v[i + 1] - v[i]) } else { v[n - 1] }
}

/// The spread of a timing's repeats: min, quartiles, median, max and the number of samples, in
/// the unit of the time it belongs to (ms for an [`crate::Entry`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "sweep", derive(serde::Serialize, serde::Deserialize))]
pub struct Spread {
    pub min: f64,
    /// First quartile (linear interpolation between order statistics).
    pub q1: f64,
    pub median: f64,
    /// Third quartile.
    pub q3: f64,
    pub max: f64,
    /// How many timed repeats (the warm-up run is not one).
    pub samples: usize,
}

impl Spread {
    /// The spread of `samples`; `None` when there are none (NaNs sort last and count).
    pub fn of(samples: &[f64]) -> Option<Self> {
        if samples.is_empty() {
            return None;
        }
        let mut v = samples.to_vec();
        v.sort_by(f64::total_cmp);
        Some(Self {
            min: v[0],
            q1: quantile_sorted(&v, 0.25),
            median: median_sorted(&v),
            q3: quantile_sorted(&v, 0.75),
            max: v[v.len() - 1],
            samples: v.len(),
        })
    }

    /// The same spread in another unit (`k` times every figure).
    pub fn scaled(self, k: f64) -> Self {
        Self {
            min: self.min * k,
            q1: self.q1 * k,
            median: self.median * k,
            q3: self.q3 * k,
            max: self.max * k,
            samples: self.samples,
        }
    }

    /// `(max - min) / median`: the relative width of the whole range.
    pub fn relative_range(&self) -> f64 {
        (self.max - self.min) / self.median
    }
}

/// A distribution-free interval for a race's ratio: the order-statistic confidence interval of
/// the median of the per-round ratios (each round times both peers back to back).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "sweep", derive(serde::Serialize, serde::Deserialize))]
pub struct RatioInterval {
    pub lo: f64,
    pub hi: f64,
    /// Median of the per-round ratios.
    pub median: f64,
    /// The interval's coverage of the true median (0.95 where there are enough rounds; with
    /// few rounds, the whole range and its lower coverage: 0.75 for 3 rounds).
    pub confidence: f64,
    /// Rounds (pairs) the interval comes from.
    pub pairs: usize,
}

impl RatioInterval {
    /// The interval of the median of `ratios` (one per round); `None` when empty.
    pub fn of(ratios: &[f64]) -> Option<Self> {
        let n = ratios.len();
        if n == 0 {
            return None;
        }
        let mut v = ratios.to_vec();
        v.sort_by(f64::total_cmp);
        // P(X <= j) for X ~ Binomial(n, 1/2), accumulated.
        let mut cdf = Vec::with_capacity(n + 1);
        let (mut c, mut acc) = (1.0f64, 0.0f64);
        let half_n = 0.5f64.powi(n as i32);
        for j in 0..=n {
            if j > 0 {
                c = c * (n + 1 - j) as f64 / j as f64;
            }
            acc += c * half_n;
            cdf.push(acc);
        }
        // The largest k (1-based) whose interval [v_(k), v_(n+1-k)] still covers 95%.
        let mut k = 1;
        while k < n.div_ceil(2) && 1.0 - 2.0 * cdf[k] >= 0.95 {
            k += 1;
        }
        let confidence = 1.0 - 2.0 * cdf[k - 1];
        Some(Self {
            lo: v[k - 1],
            hi: v[n - k],
            median: median_sorted(&v),
            confidence: confidence.max(0.0),
            pairs: n,
        })
    }

    /// True when the interval cannot tell the peers apart (it holds 1).
    pub fn includes_one(&self) -> bool {
        self.lo <= 1.0 && self.hi >= 1.0
    }

    /// The interval of the reciprocal ratio.
    pub fn inverted(self) -> Self {
        Self { lo: 1.0 / self.hi, hi: 1.0 / self.lo, median: 1.0 / self.median, ..self }
    }
}

/// An interleaved race's outcome: both peers' spreads and the interval of `theirs / ours`
/// (per round; > 1: ours took less time).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Race {
    pub ours: Spread,
    pub theirs: Spread,
    pub interval: RatioInterval,
}

/// What the harness remembers of its recent timings.
enum Recorded {
    Timing(Spread),
    Race(Race),
}

static RECENT: Mutex<Vec<Recorded>> = Mutex::new(Vec::new());
const REMEMBERED: usize = 512;

fn remember(r: Recorded) {
    if let Ok(mut recent) = RECENT.lock() {
        if recent.len() >= REMEMBERED {
            recent.drain(..REMEMBERED / 2);
        }
        recent.push(r);
    }
}

fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

/// The spread of the most recent timing whose median is `time` in the same unit or after a
/// change of unit (`1e-3`: µs or ns per ms steps), scaled to `time`'s unit.
pub(crate) fn recall_spread(time: f64) -> Option<Spread> {
    let recent = RECENT.lock().ok()?;
    for r in recent.iter().rev() {
        let spreads: &[Spread] = match r {
            Recorded::Timing(s) => std::slice::from_ref(s),
            Recorded::Race(race) => &[race.ours, race.theirs],
        };
        for s in spreads {
            for k in [1.0, 1e-3, 1e-6, 1e3] {
                if close(s.median * k, time) {
                    return Some(s.scaled(k));
                }
            }
        }
    }
    None
}

/// The interval of the most recent race whose ratio of medians (`theirs / ours` in time) is
/// `ratio` (or its reciprocal, when the sweep named the peers the other way round).
pub(crate) fn recall_interval(ratio: f64) -> Option<RatioInterval> {
    let recent = RECENT.lock().ok()?;
    for r in recent.iter().rev() {
        if let Recorded::Race(race) = r {
            let of_medians = race.theirs.median / race.ours.median;
            if close(of_medians, ratio) {
                return Some(race.interval);
            }
            if close(1.0 / of_medians, ratio) {
                return Some(race.interval.inverted());
            }
        }
    }
    None
}

/// Runs `f` once to warm up and then `reps` times (at least once); returns the spread of the
/// wall times in milliseconds and the last result.
pub fn time_spread<R>(reps: usize, mut f: impl FnMut() -> R) -> (Spread, R) {
    let mut last = black_box(f());
    let mut times = Vec::with_capacity(reps.max(1));
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        last = black_box(f());
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let spread = Spread::of(&times).expect("at least one repeat");
    remember(Recorded::Timing(spread));
    (spread, last)
}

/// Runs `f` once to warm up and then `reps` times (at least once); returns the median wall time
/// in milliseconds and the last result. The spread is remembered for [`crate::Sweep::entry`].
pub fn time_ms<R>(reps: usize, f: impl FnMut() -> R) -> (f64, R) {
    let (spread, last) = time_spread(reps, f);
    (spread.median, last)
}

/// Median nanoseconds per call of `f`, measured in `batches` batches of `calls` calls each
/// (for operations far shorter than the timer's resolution). The spread over the batches is
/// remembered for [`crate::Sweep::entry`] (an entry in ms of this median gets it scaled).
pub fn time_ns_per_call<R>(batches: usize, calls: usize, mut f: impl FnMut(usize) -> R) -> f64 {
    let calls = calls.max(1);
    for i in 0..calls.min(1000) {
        black_box(f(i));
    }
    let times: Vec<f64> = (0..batches.max(1))
        .map(|_| {
            let t = Instant::now();
            for i in 0..calls {
                black_box(f(i));
            }
            t.elapsed().as_secs_f64() * 1e9 / calls as f64
        })
        .collect();
    let spread = Spread::of(&times).expect("at least one batch");
    remember(Recorded::Timing(spread));
    spread.median
}

/// Races two implementations of the same work: `rounds` rounds, each timing `ours` then
/// `theirs` (order alternating every round); returns both spreads (ms) and the interval of the
/// per-round ratio `theirs / ours`.
pub fn race(rounds: usize, mut ours: impl FnMut(), mut theirs: impl FnMut()) -> Race {
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
    let ratios: Vec<f64> = a.iter().zip(&b).map(|(o, t)| t / o).collect();
    let race = Race {
        ours: Spread::of(&a).expect("at least one round"),
        theirs: Spread::of(&b).expect("at least one round"),
        interval: RatioInterval::of(&ratios).expect("at least one round"),
    };
    remember(Recorded::Race(race));
    race
}

/// Races two implementations of the same work: `rounds` rounds, each timing `ours` then
/// `theirs` (order alternating every round), and returns their median times in milliseconds
/// `(ours_ms, theirs_ms)`. The race is remembered, so the [`crate::Comparison`] made from the
/// two medians gets the ratio's interval in [`crate::Sweep::comparison`].
pub fn interleaved(rounds: usize, ours: impl FnMut(), theirs: impl FnMut()) -> (f64, f64) {
    let r = race(rounds, ours, theirs);
    (r.ours.median, r.theirs.median)
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
    fn spread_of_known_samples() {
        let s = Spread::of(&[5.0, 1.0, 3.0, 2.0, 4.0]).unwrap();
        assert_eq!((s.min, s.q1, s.median, s.q3, s.max, s.samples), (1.0, 2.0, 3.0, 4.0, 5.0, 5));
        assert_eq!(Spread::of(&[]), None);
        assert_eq!(s.scaled(2.0).q3, 8.0);
    }

    #[test]
    fn ratio_interval_covers_95_percent_once_there_are_enough_rounds() {
        // n = 5: the whole range covers 1 - 2/32 = 0.9375 < 0.95, nothing narrower exists.
        let few = RatioInterval::of(&[1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
        assert_eq!((few.lo, few.hi), (1.0, 5.0));
        assert!((few.confidence - 0.9375).abs() < 1e-12);
        // n = 20: the classical interval is [x_(6), x_(15)], coverage 0.9586.
        let v: Vec<f64> = (1..=20).map(f64::from).collect();
        let i = RatioInterval::of(&v).unwrap();
        assert_eq!((i.lo, i.hi), (6.0, 15.0), "{i:?}");
        assert!((i.confidence - 0.9586).abs() < 1e-3, "{i:?}");
        assert!(i.confidence >= 0.95);
        assert!(!i.includes_one());
        assert!(RatioInterval::of(&[0.9, 1.1, 1.0]).unwrap().includes_one());
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
        let interval = recall_interval(slow / fast).expect("the race is remembered");
        assert!(interval.lo > 1.0, "{interval:?}");
        assert!(recall_interval(fast / slow).unwrap().hi < 1.0);
        assert_eq!(recall_spread(fast).unwrap().samples, 5);
    }
}
