//! Build settings: the explicit SAH costs and limits, with named presets.

use crate::error::Error;

/// Deepest tree the traversal stack supports.
pub const MAX_DEPTH_LIMIT: u32 = 56;

/// Surface-area-heuristic costs and limits of the kd-tree build.
///
/// Leaves are tested four triangles at a time, so the SAH counts a node of `N` triangles as
/// `B(N) = ceil(N / 4)` packs. The cost of splitting a node with box `V` at a plane into
/// `VL`/`VR` holding `NL`/`NR` triangles is
/// `lambda * (traversal_cost + intersection_cost * (A(VL) B(NL) + A(VR) B(NR)) / A(V))`, with
/// `lambda = 1 - empty_bonus` when one side is empty; a node becomes a leaf when no split is
/// cheaper than `intersection_cost * B(N)` (Wald & Havran 2006, with packs in place of
/// triangles). Only the ratio of the two costs matters: it was swept against trace time on
/// four meshes (`examples/kdrace.rs`; the crate doc's table).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Cost of one traversal step.
    pub traversal_cost: f32,
    /// Cost of testing one pack of up to four triangles.
    pub intersection_cost: f32,
    /// Discount for splits that cut off empty space, in `[0, 1)`.
    pub empty_bonus: f32,
    /// Depth limit; 0 means automatic, `8 + 1.3 log2 N` (pbrt), capped at [`MAX_DEPTH_LIMIT`].
    pub max_depth: u32,
    /// Nodes with at most this many triangles become leaves without trying a split.
    pub leaf_size: u32,
    /// Clip straddling triangles to the child boxes ("perfect splits") instead of only
    /// clipping their bounding boxes: tighter boxes, fewer references, slower build.
    pub perfect_splits: bool,
}

impl Settings {
    /// Fastest build: box clipping only, larger leaves.
    pub const fn low() -> Self {
        Self {
            traversal_cost: 1.0,
            intersection_cost: 0.3,
            empty_bonus: 0.1,
            max_depth: 0,
            leaf_size: 8,
            perfect_splits: false,
        }
    }

    /// Balanced default (fast build, fast traversal).
    pub const DEFAULT: Self = Self {
        traversal_cost: 1.0,
        intersection_cost: 0.4,
        empty_bonus: 0.2,
        max_depth: 0,
        leaf_size: 1,
        perfect_splits: false,
    };

    /// [`Self::DEFAULT`] as a function, like the other presets.
    pub const fn default_preset() -> Self {
        Self::DEFAULT
    }

    /// Better trees at a higher build cost: perfect splits.
    pub const fn high() -> Self {
        Self {
            traversal_cost: 1.0,
            intersection_cost: 0.4,
            empty_bonus: 0.2,
            max_depth: 0,
            leaf_size: 1,
            perfect_splits: true,
        }
    }

    /// The best tree we know how to build (perfect splits, deeper trees).
    pub const fn reference() -> Self {
        Self {
            traversal_cost: 1.0,
            intersection_cost: 0.5,
            empty_bonus: 0.3,
            max_depth: MAX_DEPTH_LIMIT,
            leaf_size: 1,
            perfect_splits: true,
        }
    }

    /// Checks that every value is in range.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |what: String| Err(Error::InvalidSettings(what));
        if !(self.traversal_cost.is_finite() && self.traversal_cost > 0.0) {
            return bad(format!("traversal_cost {} must be finite and > 0", self.traversal_cost));
        }
        if !(self.intersection_cost.is_finite() && self.intersection_cost > 0.0) {
            return bad(format!(
                "intersection_cost {} must be finite and > 0",
                self.intersection_cost
            ));
        }
        if !(0.0..1.0).contains(&self.empty_bonus) {
            return bad(format!("empty_bonus {} must be in [0, 1)", self.empty_bonus));
        }
        if self.max_depth > MAX_DEPTH_LIMIT {
            return bad(format!("max_depth {} exceeds {MAX_DEPTH_LIMIT}", self.max_depth));
        }
        Ok(())
    }

    /// The depth limit used for `n` triangles.
    pub fn depth_limit(&self, n: usize) -> u32 {
        if self.max_depth > 0 {
            return self.max_depth.min(MAX_DEPTH_LIMIT);
        }
        let auto = 8.0 + 1.3 * (n.max(1) as f32).log2();
        (auto.round() as u32).min(MAX_DEPTH_LIMIT)
    }
}

impl Default for Settings {
    fn default() -> Self {
        Self::DEFAULT
    }
}
