//! Node order: subtrees packed into cache lines.
//!
//! The build emits nodes depth first (siblings adjacent), so a ray stepping down the right
//! side of a subtree jumps to a new cache line at almost every level. Here the nodes are
//! reordered so that each 64-byte line holds a small subtree of sibling pairs (after J. Gil
//! and A. Itai, "How to pack trees", Journal of Algorithms 32(2), 1999, whose subtree
//! clustering minimises the lines a root-to-leaf path touches): a line starts with one pair
//! and takes the pairs below it breadth first until its four pair slots are full; the pairs
//! left over start lines of their own, laid out depth first so that a subtree's lines stay
//! close. The root sits alone in the first slot of the first line, padded with
//! [`Node::PAD`]. A path of `d` levels then touches about `d / 2` lines instead of up to `d`.

use std::collections::VecDeque;

use crate::node::{LINE, Node};

/// Pair slots per line.
const PAIRS: usize = LINE / 2;

/// `nodes` (root first, the children of an interior node adjacent) reordered into lines.
pub(crate) fn treelets(nodes: &[Node]) -> Vec<Node> {
    let mut out = Vec::with_capacity(nodes.len() + nodes.len() / 4 + LINE);
    out.push(nodes[0]);
    out.push(Node::PAD);
    // Pairs that start a line: (old index of the pair's first node, new index of the parent).
    let mut starts: Vec<(u32, usize)> = Vec::new();
    let mut line: VecDeque<(u32, usize)> = VecDeque::new();
    if !nodes[0].is_leaf() {
        line.push_back((nodes[0].first_child(), 0));
    }
    let mut free = PAIRS - 1;
    loop {
        // Fill the current line breadth first from `line`.
        while free > 0
            && let Some((old, parent)) = line.pop_front()
        {
            let at = out.len();
            let p = out[parent];
            out[parent] = Node::inner(p.axis(), p.split(), at as u32);
            for k in 0..2 {
                let n = nodes[old as usize + k];
                out.push(n);
                if !n.is_leaf() {
                    line.push_back((n.first_child(), at + k));
                }
            }
            free -= 1;
        }
        // What did not fit starts lines of its own (depth first: the last pushed comes next).
        starts.extend(line.drain(..).rev());
        while !out.len().is_multiple_of(LINE) {
            out.push(Node::PAD);
        }
        let Some(next) = starts.pop() else { break };
        line.push_back(next);
        free = PAIRS;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A complete tree of `depth` levels below the root, depth first with adjacent siblings.
    fn complete(depth: u32) -> Vec<Node> {
        fn grow(v: &mut Vec<Node>, slot: usize, depth: u32) {
            if depth == 0 {
                v[slot] = Node::leaf(1, slot as u32);
                return;
            }
            let first = v.len();
            v.push(Node::EMPTY_LEAF);
            v.push(Node::EMPTY_LEAF);
            v[slot] = Node::inner((depth % 3) as usize, slot as f32, first as u32);
            grow(v, first, depth - 1);
            grow(v, first + 1, depth - 1);
        }
        let mut v = vec![Node::EMPTY_LEAF];
        grow(&mut v, 0, depth);
        v
    }

    /// The leaves in left-to-right order with their depths and the lines of their paths.
    fn walk(v: &[Node]) -> Vec<(u32, u32, usize)> {
        let mut out = Vec::new();
        let mut stack = vec![(0u32, 0u32, vec![0usize])];
        while let Some((i, d, lines)) = stack.pop() {
            let n = v[i as usize];
            if n.is_leaf() {
                out.push((n.offset(), d, lines.len()));
                continue;
            }
            for k in [1, 0] {
                let c = n.first_child() + k;
                let mut l = lines.clone();
                if *l.last().unwrap() != c as usize / LINE {
                    l.push(c as usize / LINE);
                }
                stack.push((c, d + 1, l));
            }
        }
        out
    }

    #[test]
    fn same_tree_fewer_lines_per_path() {
        for depth in [0, 1, 2, 5, 9] {
            let v = complete(depth);
            let t = treelets(&v);
            assert!(t.len().is_multiple_of(LINE));
            assert_eq!(t.iter().filter(|n| !n.is_pad()).count(), v.len());
            let (a, b) = (walk(&v), walk(&t));
            let same: Vec<_> = a.iter().map(|x| (x.0, x.1)).collect();
            assert_eq!(same, b.iter().map(|x| (x.0, x.1)).collect::<Vec<_>>());
            // Three levels of pairs per line after the root's line (two levels there).
            let worst = b.iter().map(|x| x.2).max().unwrap();
            assert!(worst <= 1 + (depth as usize).div_ceil(2), "depth {depth}: {worst} lines");
        }
    }
}
