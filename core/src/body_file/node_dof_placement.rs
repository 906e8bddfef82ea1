//! Places a matrix entry's (node, component) on the body's node-major DOF, for the formats that
//! name nodes and components themselves (Abaqus matrix output, Nastran DMIG): components 1–3
//! the translations, 4–6 the rotations, nodes the body's 1-based node numbers.

use crate::{
    error::MatrixLineProblem,
    fem::{DofMap, NodeIndex},
};

/// The largest node number a matrix file may name: NASTRAN's grid identifiers and Abaqus'
/// node labels stop below 10⁹. The body's size is the largest node named times its DOF per
/// node, so a larger number would size a matrix no file holds.
pub const MAX_NODE_NUMBER: usize = 999_999_999;

/// The placement of (node, component) pairs on a body whose nodes carry `dofs`.
pub(super) struct NodeDofPlacement {
    per: usize,
    names: Vec<&'static str>,
    /// The largest node placed so far.
    pub largest_node: usize,
}

impl NodeDofPlacement {
    pub fn new(dofs: &DofMap) -> Self {
        Self {
            per: dofs.per_node(),
            names: dofs.node_dofs().iter().map(|d| d.name()).collect(),
            largest_node: 0,
        }
    }

    /// The 0-based DOF of `node` (1-based) and `component` (1–6), or why there is none.
    pub fn index(&mut self, node: usize, component: usize) -> Result<usize, MatrixLineProblem> {
        let Some(index) = NodeIndex::of_number(node) else {
            return Err(MatrixLineProblem::NodeZero);
        };
        if node > MAX_NODE_NUMBER {
            return Err(MatrixLineProblem::NodeNumberTooLarge {
                node,
                largest: MAX_NODE_NUMBER,
            });
        }
        let name = ["x", "y", "z", "θx", "θy", "θz"]
            .get(component.wrapping_sub(1))
            .copied()
            .ok_or_else(|| MatrixLineProblem::NotAComponent {
                node,
                component: component.to_string().into(),
            })?;
        let position = self.names.iter().position(|&n| n == name).ok_or_else(|| {
            MatrixLineProblem::DofNotInBody {
                node,
                dof: name.into(),
                body: self.names.clone(),
            }
        })?;
        self.largest_node = self.largest_node.max(node);
        Ok(index.get() * self.per + position)
    }

    /// Rows of the matrix: every DOF of nodes 1 to the largest placed.
    pub fn size(&self) -> usize {
        self.largest_node * self.per
    }
}
