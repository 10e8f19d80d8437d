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

/// Nodes per 64-byte cache line.
pub(crate) const LINE: usize = 8;

/// One cache line of nodes (64 bytes, 64-byte aligned).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(64))]
pub(crate) struct Line(pub [Node; LINE]);

const _: () = assert!(std::mem::size_of::<Line>() == 64);

impl Node {
    /// A slot that only fills a cache line (`crate::layout`): never reached, never a leaf of
    /// the tree (real leaves point into the leaf blocks, whose length is below `u32::MAX`).
    pub const PAD: Self = Self { a: 3, b: u32::MAX };

    #[inline]
    pub fn is_pad(self) -> bool {
        self == Self::PAD
    }
}

/// The tree's nodes in 64-byte aligned cache lines, read as one slice.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub(crate) struct Nodes {
    lines: Vec<Line>,
    len: usize,
}

impl Nodes {
    /// The nodes of `v`, in order, in aligned lines.
    pub fn from_slice(v: &[Node]) -> Self {
        let lines = v
            .chunks(LINE)
            .map(|c| Line(std::array::from_fn(|i| c.get(i).copied().unwrap_or(Node::PAD))))
            .collect();
        Self { lines, len: v.len() }
    }
}

impl std::ops::Deref for Nodes {
    type Target = [Node];
    #[inline(always)]
    fn deref(&self) -> &[Node] {
        // SAFETY: a `Line` is exactly `LINE` nodes without padding (`repr(C)` arrays of the
        // `repr(C)` two-`u32` node), and `len <= LINE * lines.len()`.
        unsafe { std::slice::from_raw_parts(self.lines.as_ptr().cast::<Node>(), self.len) }
    }
}
