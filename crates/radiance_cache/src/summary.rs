//! A one-line summary of what the cache's last allocation and update did.

use crate::{AllocationStats, RadianceCache, UpdateStats};

/// What a cache's last allocation and update did, in a line a renderer can show: how much
/// of the full grids the view needed, how many caches it lit, and how stale the light is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CacheSummary {
    /// Caches allocated (the view's) and in the full cascades.
    pub allocated: usize,
    pub full_grid: usize,
    /// Caches lit in the last update (at most the budget), and allocated ones never lit yet.
    pub lit: usize,
    pub never_lit: usize,
    /// Frames since the oldest allocated cache was lit.
    pub oldest_age_frames: u64,
    /// Bytes of cache data on the CPU.
    pub memory_bytes: usize,
}

impl std::fmt::Display for CacheSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let share = 100.0 * self.allocated as f64 / self.full_grid.max(1) as f64;
        write!(
            f,
            "{} of {} caches allocated ({share:.1}%), {} lit in the last update, {} never lit, \
             oldest light {} frames old, {} KiB",
            self.allocated,
            self.full_grid,
            self.lit,
            self.never_lit,
            self.oldest_age_frames,
            self.memory_bytes / 1024
        )
    }
}

impl CacheSummary {
    /// The summary of `alloc` and `update` (the last [`RadianceCache::allocate`] and
    /// [`RadianceCache::update`] of `cache`).
    pub fn new(alloc: &AllocationStats, update: &UpdateStats, cache: &RadianceCache) -> Self {
        Self {
            allocated: alloc.allocated,
            full_grid: alloc.full_grid,
            lit: update.lit,
            never_lit: update.never_lit,
            oldest_age_frames: update.oldest_age_frames,
            memory_bytes: cache.memory_bytes(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::CacheSummary;

    #[test]
    fn the_line_gives_the_share_of_the_full_grid() {
        let s = CacheSummary {
            allocated: 3,
            full_grid: 8,
            lit: 2,
            never_lit: 1,
            oldest_age_frames: 4,
            memory_bytes: 5 * 1024,
        };
        let line = s.to_string();
        assert!(line.starts_with("3 of 8 caches allocated (37.5%), 2 lit"), "{line}");
        assert!(line.ends_with("oldest light 4 frames old, 5 KiB"), "{line}");
        let empty = CacheSummary { allocated: 0, full_grid: 0, ..s };
        assert!(empty.to_string().contains("(0.0%)"), "no division by zero");
    }
}
