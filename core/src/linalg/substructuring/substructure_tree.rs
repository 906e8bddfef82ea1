//! The substructure tree of a mesh's unknowns, by geometric nested dissection: a part is cut
//! by a plane across its longest extent into two halves and the separator that couples them
//! (the unknowns of one half joined to the other); each half is cut again until it is small.
//! Numbered halves first (recursively) and separator last, the tree is the elimination order
//! of [`super::nested_dissection`]; kept whole, it is the structure multi-level substructuring
//! (AMLS, Bennighof and Lehoucq 2004) reduces level by level: each leaf a substructure with
//! its separators fixed, each separator the interface of the two subtrees under it.
//!
//! The defining property, checked by the tests on meshes of several sizes: no entry of the
//! matrix couples two nodes of the tree unless one is an ancestor of the other.

use faer::sparse::SparseColMat;

/// Recursion depth beyond which a part is left whole (a mesh this deep has ~2⁶⁴ unknowns).
const MAX_DEPTH: usize = 64;

/// A node of a [`SubstructureTree`]: a leaf substructure or the separator of two subtrees.
#[derive(Debug, Clone, PartialEq)]
pub struct SubstructureNode {
    /// The unknowns of this node (not of its subtree), in ascending position along the cut.
    pub unknowns: Vec<usize>,
    /// The subtrees a separator separates, in the order (two, or one where the part beyond
    /// the cut was all separator); none for a leaf.
    pub children: Vec<usize>,
    /// The separator above (`None` for the root).
    pub parent: Option<usize>,
    /// Depth below the root (0).
    pub level: usize,
}

/// The nodes of a nested dissection in postorder: every node after its subtrees, the root last.
#[derive(Debug, Clone, PartialEq)]
pub struct SubstructureTree {
    nodes: Vec<SubstructureNode>,
    unknowns: usize,
}

impl SubstructureTree {
    /// The tree of `a`'s unknowns given each unknown's position `coords` (m), parts of at
    /// most `leaf` unknowns left whole. Unknowns with the same position (the DOF of one node)
    /// stay together.
    ///
    /// `None` when every unknown has the same position (an imported body without node
    /// coordinates): there is nothing to cut by.
    pub fn new(a: &SparseColMat<usize, f64>, coords: &[[f64; 3]], leaf: usize) -> Option<Self> {
        let n = a.nrows();
        assert_eq!(coords.len(), n, "one position per unknown");
        if coords.windows(2).all(|w| w[0] == w[1]) {
            return None;
        }
        let mut tree = Self {
            nodes: Vec::new(),
            unknowns: n,
        };
        let mut side = vec![0u8; n];
        let root = tree.dissect((0..n).collect(), a, coords, leaf.max(1), &mut side, 0);
        tree.nodes[root].parent = None;
        Some(tree)
    }

    /// The nodes, postorder (children before their separator, the root last).
    pub fn nodes(&self) -> &[SubstructureNode] {
        &self.nodes
    }

    /// The root's index (the last node).
    pub fn root(&self) -> usize {
        self.nodes.len() - 1
    }

    /// The elimination order (new position → old index): the nodes' unknowns in postorder.
    pub fn order(&self) -> Vec<usize> {
        self.nodes
            .iter()
            .flat_map(|node| node.unknowns.iter().copied())
            .collect()
    }

    /// Each unknown's node.
    pub fn node_of(&self) -> Vec<usize> {
        let mut of = vec![usize::MAX; self.unknowns];
        for (j, node) in self.nodes.iter().enumerate() {
            for &i in &node.unknowns {
                of[i] = j;
            }
        }
        of
    }

    /// Whether node `a` is `b` or above it.
    pub fn is_ancestor(&self, a: usize, b: usize) -> bool {
        let mut at = Some(b);
        while let Some(j) = at {
            if j == a {
                return true;
            }
            at = self.nodes[j].parent;
        }
        false
    }

    /// Each node's boundary $B$: the ancestors' unknowns coupled to its subtree through any of
    /// `patterns` (entries of the node's own unknowns' columns, and the children's boundaries),
    /// in the elimination order ([`Self::order`]). With $P$ the node's unknowns, $P \cup B$ is
    /// its front in a multi-level elimination.
    pub fn boundaries(&self, patterns: &[&SparseColMat<usize, f64>]) -> Vec<Vec<usize>> {
        let node_of = self.node_of();
        let mut position = vec![0; self.unknowns];
        for (p, &u) in self.order().iter().enumerate() {
            position[u] = p;
        }
        let mut stamp = vec![usize::MAX; self.unknowns];
        let mut out: Vec<Vec<usize>> = Vec::with_capacity(self.nodes.len());
        for (j, node) in self.nodes.iter().enumerate() {
            let mut boundary = Vec::new();
            let children = node.children.iter().flat_map(|&c| out[c].iter().copied());
            let own = node.unknowns.iter().flat_map(|&u| {
                patterns
                    .iter()
                    .flat_map(move |a| a.symbolic().row_idx_of_col_raw(u).iter().copied())
            });
            for v in own.chain(children) {
                let a = node_of[v];
                if a != j && stamp[v] != j && self.is_ancestor(a, j) {
                    stamp[v] = j;
                    boundary.push(v);
                }
            }
            boundary.sort_unstable_by_key(|&v| position[v]);
            out.push(boundary);
        }
        out
    }

    /// The number of levels (the deepest node's level plus one).
    pub fn levels(&self) -> usize {
        self.nodes.iter().map(|n| n.level + 1).max().unwrap_or(0)
    }

    /// Appends the subtree of `set` (postorder) and returns its root's index.
    fn dissect(
        &mut self,
        mut set: Vec<usize>,
        a: &SparseColMat<usize, f64>,
        coords: &[[f64; 3]],
        leaf: usize,
        side: &mut [u8],
        depth: usize,
    ) -> usize {
        if set.len() <= leaf || depth > MAX_DEPTH {
            return self.push_leaf(set, depth);
        }
        // Longest extent of this part.
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for &i in &set {
            for d in 0..3 {
                lo[d] = lo[d].min(coords[i][d]);
                hi[d] = hi[d].max(coords[i][d]);
            }
        }
        let axis = (0..3)
            .max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y])))
            .expect("three axes");
        set.sort_by(|&x, &y| coords[x][axis].total_cmp(&coords[y][axis]));
        let cut = coords[set[set.len() / 2]][axis];
        // 1: left (< cut), 2: right (≥ cut), then the separator: the right unknowns coupled to
        // the left.
        for &i in &set {
            side[i] = if coords[i][axis] < cut { 1 } else { 2 };
        }
        let mut separator = Vec::new();
        let mut left = Vec::new();
        let mut right = Vec::new();
        for &i in &set {
            if side[i] == 1 {
                left.push(i);
                continue;
            }
            let coupled = a
                .symbolic()
                .row_idx_of_col_raw(i)
                .iter()
                .any(|&r| side[r] == 1);
            if coupled {
                separator.push(i);
            } else {
                right.push(i);
            }
        }
        for &i in &set {
            side[i] = 0;
        }
        if left.is_empty() || right.is_empty() && separator.len() == set.len() {
            return self.push_leaf(set, depth);
        }
        let mut children = vec![self.dissect(left, a, coords, leaf, side, depth + 1)];
        if !right.is_empty() {
            children.push(self.dissect(right, a, coords, leaf, side, depth + 1));
        }
        let j = self.nodes.len();
        for &child in &children {
            self.nodes[child].parent = Some(j);
        }
        self.nodes.push(SubstructureNode {
            unknowns: separator,
            children,
            parent: None,
            level: depth,
        });
        j
    }

    fn push_leaf(&mut self, unknowns: Vec<usize>, depth: usize) -> usize {
        self.nodes.push(SubstructureNode {
            unknowns,
            children: Vec::new(),
            parent: None,
            level: depth,
        });
        self.nodes.len() - 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{SlabParameters, slab};

    fn tree_of(bricks: [usize; 3], leaf: usize) -> (SubstructureTree, crate::fem::FeModel) {
        let model = slab(&SlabParameters::refined(bricks).unwrap());
        let tree = model.substructure_tree(leaf).unwrap();
        (tree, model)
    }

    #[test]
    fn no_entry_couples_two_nodes_unless_one_is_above_the_other() {
        for (bricks, leaf) in [
            ([4, 2, 1], 16),
            ([8, 4, 2], 64),
            ([12, 6, 3], 200),
            ([16, 8, 4], 500),
        ] {
            let (tree, model) = tree_of(bricks, leaf);
            let n = model.dof_count();
            let of = tree.node_of();
            assert!(
                of.iter().all(|&j| j < tree.nodes().len()),
                "{bricks:?}: every unknown placed"
            );
            let mut order = tree.order();
            assert_eq!(order.len(), n);
            order.sort_unstable();
            assert!(order.iter().copied().eq(0..n), "{bricks:?}: a permutation");
            let k = model.k.as_faer();
            for col in 0..n {
                for &row in k.symbolic().row_idx_of_col_raw(col) {
                    let (a, b) = (of[row], of[col]);
                    assert!(
                        tree.is_ancestor(a, b) || tree.is_ancestor(b, a),
                        "{bricks:?}: K({row}, {col}) couples nodes {a} and {b}"
                    );
                }
            }
            // Postorder, the root last and at level 0; children one level below their separator.
            assert_eq!(tree.nodes()[tree.root()].level, 0);
            assert!(tree.nodes()[tree.root()].parent.is_none());
            for (j, node) in tree.nodes().iter().enumerate() {
                for &c in &node.children {
                    assert!(c < j);
                    assert_eq!(tree.nodes()[c].level, node.level + 1);
                    assert_eq!(tree.nodes()[c].parent, Some(j));
                }
                if node.children.is_empty() {
                    assert!(
                        node.unknowns.len() <= leaf,
                        "{bricks:?}: a leaf of {}",
                        node.unknowns.len()
                    );
                }
            }
            assert!(tree.levels() >= 2, "{bricks:?}: cut at least once");
        }
    }
}
