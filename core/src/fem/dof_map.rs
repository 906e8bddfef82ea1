//! Which DOF a node carries and where they sit in the global vector: one map used by every
//! module (partitions, rigid-body motions, drawing, nodal-fixed axes).

use super::Direction;

/// One DOF of a node: a translation (m) or a small rotation (rad) about a global direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NodeDof {
    /// Displacement along the direction, m.
    Translation(Direction),
    /// Rotation about the direction, rad.
    Rotation(Direction),
}

impl std::fmt::Display for NodeDof {
    /// [`NodeDof::name`].
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl NodeDof {
    /// `x` for a translation, `θx` for a rotation.
    pub fn name(self) -> &'static str {
        match self {
            NodeDof::Translation(d) => d.name(),
            NodeDof::Rotation(Direction::X) => "θx",
            NodeDof::Rotation(Direction::Y) => "θy",
            NodeDof::Rotation(Direction::Z) => "θz",
        }
    }

    /// The value this DOF takes in the rigid motion $u = t + \omega \times x$ at position `x`
    /// (m), for translation `t` and rotation `omega` (rad).
    pub fn rigid_motion(self, x: [f64; 3], t: [f64; 3], omega: [f64; 3]) -> f64 {
        match self {
            NodeDof::Translation(d) => {
                let w = omega;
                let cross = [
                    w[1] * x[2] - w[2] * x[1],
                    w[2] * x[0] - w[0] * x[2],
                    w[0] * x[1] - w[1] * x[0],
                ];
                t[d.index()] + cross[d.index()]
            }
            NodeDof::Rotation(d) => omega[d.index()],
        }
    }
}

/// The DOF layout of a body: every node carries the same DOF, node-major (all DOF of node 1,
/// then node 2, …).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DofMap {
    per_node: Vec<NodeDof>,
}

impl DofMap {
    /// 2 DOF per node: x, y (a planar body such as the App. A beam).
    pub fn planar() -> Self {
        Self::new(vec![
            NodeDof::Translation(Direction::X),
            NodeDof::Translation(Direction::Y),
        ])
    }

    /// 3 DOF per node: x, y, z (solids such as the App. B slab).
    pub fn solid() -> Self {
        Self::new(Direction::ALL.map(NodeDof::Translation).to_vec())
    }

    /// 6 DOF per node: x, y, z, θx, θy, θz (3-D beam and shell nodes).
    pub fn frame_3d() -> Self {
        let mut v = Direction::ALL.map(NodeDof::Translation).to_vec();
        v.extend(Direction::ALL.map(NodeDof::Rotation));
        Self::new(v)
    }

    /// A map from the DOF of one node, in their order inside the node's block.
    pub fn new(per_node: Vec<NodeDof>) -> Self {
        Self { per_node }
    }

    /// DOF per node.
    pub fn per_node(&self) -> usize {
        self.per_node.len()
    }

    /// The DOF of one node, in block order.
    pub fn node_dofs(&self) -> &[NodeDof] {
        &self.per_node
    }

    /// 2 when every DOF lies in the x-y plane (x, y translations and a rotation about z),
    /// 3 otherwise.
    pub fn spatial_dim(&self) -> usize {
        let out_of_plane = self.per_node.iter().any(|d| {
            matches!(
                d,
                NodeDof::Translation(Direction::Z)
                    | NodeDof::Rotation(Direction::X)
                    | NodeDof::Rotation(Direction::Y)
            )
        });
        if out_of_plane { 3 } else { 2 }
    }

    /// Rigid-body motions of a free body: 3 in the plane, 6 in space.
    pub fn rigid_body_count(&self) -> usize {
        if self.spatial_dim() == 2 { 3 } else { 6 }
    }

    /// The translation and rotation of rigid motion number `k` (translations first, then
    /// rotations; in the plane: x, y, rotation about z), unit size.
    pub fn rigid_motion(&self, k: usize) -> ([f64; 3], [f64; 3]) {
        let unit = |i: usize| {
            let mut e = [0.0; 3];
            e[i] = 1.0;
            e
        };
        match (self.spatial_dim(), k) {
            (2, 0 | 1) | (3, 0..=2) => (unit(k), [0.0; 3]),
            (2, _) => ([0.0; 3], unit(2)),
            _ => ([0.0; 3], unit(k - 3)),
        }
    }

    /// Offset of a DOF inside a node's block, if the node carries it.
    pub fn offset(&self, dof: NodeDof) -> Option<usize> {
        self.per_node.iter().position(|&d| d == dof)
    }

    /// Global index of DOF `dof` of node `node` (0-based), if nodes carry it.
    pub fn index(&self, node: usize, dof: NodeDof) -> Option<usize> {
        Some(node * self.per_node() + self.offset(dof)?)
    }

    /// `(0-based node, DOF)` of a global index.
    pub fn locate(&self, index: usize) -> (usize, NodeDof) {
        let n = self.per_node();
        (index / n, self.per_node[index % n])
    }

    /// Offsets of the translations inside a node's block, with their directions.
    pub fn translations(&self) -> Vec<(Direction, usize)> {
        self.per_node
            .iter()
            .enumerate()
            .filter_map(|(o, d)| match d {
                NodeDof::Translation(dir) => Some((*dir, o)),
                NodeDof::Rotation(_) => None,
            })
            .collect()
    }
}
