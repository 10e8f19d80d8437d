//! The compact 8-byte kd-tree node (Wald's layout).
//!
//! Word `a`: bits 0-1 are the split axis (0, 1, 2) or 3 for a leaf; bits 2-31 are, for an
//! interior node, the index of its first child (the second child follows it, so siblings share
//! a cache line), and for a leaf, the number of triangles. Word `b`: the split position (f32
//! bits) or the leaf's first record in the leaf-triangle array.

/// One kd-tree node, 8 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub(crate) struct Node {
    a: u32,
    b: u32,
}

const _: () = assert!(std::mem::size_of::<Node>() == 8);

/// Largest child index / leaf count the 30-bit field holds.
pub(crate) const MAX_FIELD: u32 = (1 << 30) - 1;

impl Node {
    pub const EMPTY_LEAF: Self = Self { a: 3, b: 0 };

    pub fn inner(axis: usize, split: f32, first_child: u32) -> Self {
        debug_assert!(axis < 3 && first_child <= MAX_FIELD);
        Self { a: (first_child << 2) | axis as u32, b: split.to_bits() }
    }

    pub fn leaf(count: u32, offset: u32) -> Self {
        debug_assert!(count <= MAX_FIELD);
        Self { a: (count << 2) | 3, b: offset }
    }

    #[inline(always)]
    pub fn is_leaf(self) -> bool {
        self.a & 3 == 3
    }

    #[inline(always)]
    pub fn axis(self) -> usize {
        (self.a & 3) as usize
    }

    #[inline(always)]
    pub fn split(self) -> f32 {
        f32::from_bits(self.b)
    }

    #[inline(always)]
    pub fn first_child(self) -> u32 {
        self.a >> 2
    }

    #[inline(always)]
    pub fn count(self) -> u32 {
        self.a >> 2
    }

    #[inline(always)]
    pub fn offset(self) -> u32 {
        self.b
    }

    /// The same node with child indices shifted by `nodes` and leaf offsets by `refs`.
    pub fn shifted(self, nodes: u32, refs: u32) -> Self {
        if self.is_leaf() {
            Self { a: self.a, b: self.b + refs }
        } else {
            Self::inner(self.axis(), self.split(), self.first_child() + nodes)
        }
    }
}
