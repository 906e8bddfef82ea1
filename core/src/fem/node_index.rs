//! Which node: users number nodes from 1 (body files, the thesis' tables, `--boundary`); the
//! code stores them from 0. A [`NodeIndex`] is a stored, 0-based node, made from a user's
//! number in one place, [`FeModel::node_index`](super::FeModel::node_index), which checks it.

/// A node of a body, 0-based (its row in [`FeModel::nodes`](super::FeModel::nodes)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct NodeIndex(pub usize);

impl NodeIndex {
    /// The node users number `number` (1-based); `None` for 0. Range checks against a body
    /// are [`FeModel::node_index`](super::FeModel::node_index)'s.
    pub const fn of_number(number: usize) -> Option<Self> {
        match number.checked_sub(1) {
            Some(i) => Some(Self(i)),
            None => None,
        }
    }

    /// The 0-based index.
    pub const fn get(self) -> usize {
        self.0
    }

    /// The node's number as users write it (1-based).
    pub const fn number(self) -> usize {
        self.0 + 1
    }
}

impl std::fmt::Display for NodeIndex {
    /// Shown as users number nodes: `node 16` for index 15.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "node {}", self.number())
    }
}
