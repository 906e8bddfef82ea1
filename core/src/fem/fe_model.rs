//! A linear finite-element body: nodes, stiffness and lumped mass.

use faer::Mat;

use super::NodeIndex;
use super::{DofMap, MassProperties, NodeDof};
use crate::{
    Error, Result,
    linalg::{MassMatrix, SparseSymmetric},
};

/// A translational direction of a node (the thesis' ξ, η, ζ of the body frame).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Direction {
    /// ξ, along x.
    X,
    /// η, along y.
    Y,
    /// ζ, along z.
    Z,
}

impl Direction {
    /// All three directions in DOF order.
    pub const ALL: [Direction; 3] = [Direction::X, Direction::Y, Direction::Z];

    /// Offset of this direction inside a node's DOF block.
    pub fn index(self) -> usize {
        match self {
            Direction::X => 0,
            Direction::Y => 1,
            Direction::Z => 2,
        }
    }

    /// `x`, `y` or `z`.
    pub fn name(self) -> &'static str {
        match self {
            Direction::X => "x",
            Direction::Y => "y",
            Direction::Z => "z",
        }
    }
}

/// A body discretised by finite elements, its DOF laid out by a [`DofMap`] (node-major).
/// Units: m, kg, N/m (N m/rad for rotations).
#[derive(Debug, Clone)]
pub struct FeModel {
    /// Body name used in entity paths (`beam`, `slab`, `plank`).
    pub name: String,
    /// The DOF each node carries (2, 3 or 6) and their order.
    pub dofs: DofMap,
    /// Undeformed node positions in m (z = 0 for planar bodies).
    pub nodes: Vec<[f64; 3]>,
    /// Wireframe edges as 0-based node index pairs.
    pub edges: Vec<[usize; 2]>,
    /// Stiffness matrix, N/m, sparse symmetric.
    pub k: SparseSymmetric,
    /// Mass matrix, kg: a diagonal when lumped.
    pub m: MassMatrix,
    /// What is known of the body's zero-energy motions.
    pub rigid_motions: RigidMotions,
}

/// What is known of a body's zero-energy motions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RigidMotions {
    /// A free body: its rigid-body motions follow from the node coordinates
    /// ([`FeModel::rigid_body_modes`]) and are K's null space. Every built-in body.
    FromGeometry,
    /// Not assumed (an imported body restrained before export, or without coordinates):
    /// whether a boundary restrains it is decided by factorising $K_{ii}$, and free-free
    /// modes are computed without handing the solver any rigid motion.
    Unknown,
}

impl FeModel {
    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of DOF.
    pub fn dof_count(&self) -> usize {
        self.dofs.per_node() * self.nodes.len()
    }

    /// 2 for a planar body, 3 for a spatial one.
    pub fn spatial_dim(&self) -> usize {
        self.dofs.spatial_dim()
    }

    /// Checks a 1-based node number and returns its 0-based index: the one place a user's
    /// node number becomes an index.
    pub fn node_index(&self, node: usize) -> Result<NodeIndex> {
        if node == 0 || node > self.node_count() {
            return Err(Error::NodeOutOfRange {
                node,
                count: self.node_count(),
                body: (&self.name).into(),
            });
        }
        NodeIndex::of_number(node).ok_or(Error::NodeOutOfRange {
            node,
            count: self.node_count(),
            body: (&self.name).into(),
        })
    }

    /// The undeformed position of a node, m.
    pub fn position(&self, node: NodeIndex) -> [f64; 3] {
        self.nodes[node.get()]
    }

    /// The DOF index of a 1-based node's translation in a direction.
    pub fn dof(&self, node: usize, dir: Direction) -> Result<usize> {
        self.node_dof(node, NodeDof::Translation(dir))
    }

    /// The DOF index of a 1-based node's DOF (translation or rotation); a node without it is
    /// [`Error::NoSuchDof`].
    pub fn node_dof(&self, node: usize, dof: super::NodeDof) -> Result<usize> {
        let i = self.node_index(node)?.get();
        self.dofs.index(i, dof).ok_or_else(|| Error::NoSuchDof {
            node,
            dof: dof.name(),
            body: (&self.name).into(),
            carried: self.dofs.node_dofs().iter().map(|d| d.name()).collect(),
        })
    }

    /// All DOF of the given 1-based nodes, in the given node order; rejects duplicates.
    pub fn dofs_of_nodes(&self, nodes: &[usize]) -> Result<Vec<usize>> {
        let per = self.dofs.per_node();
        let mut out = Vec::with_capacity(nodes.len() * per);
        for (n, &node) in nodes.iter().enumerate() {
            if nodes[..n].contains(&node) {
                return Err(Error::DuplicateNode { node });
            }
            let i = self.node_index(node)?.get();
            out.extend((0..per).map(|d| i * per + d));
        }
        Ok(out)
    }

    /// `(node, DOF)` of a DOF index.
    pub fn dof_node(&self, dof: usize) -> (NodeIndex, NodeDof) {
        let (node, d) = self.dofs.locate(dof);
        (NodeIndex(node), d)
    }

    /// Position (m) of the node a DOF belongs to, for orderings that need coordinates.
    pub fn dof_position(&self, dof: usize) -> [f64; 3] {
        self.nodes[self.dofs.locate(dof).0]
    }

    /// Every DOF's position (m), in DOF order: what nested dissection cuts by.
    pub fn dof_positions(&self) -> Vec<[f64; 3]> {
        (0..self.dof_count())
            .map(|d| self.dof_position(d))
            .collect()
    }

    /// The body's substructure tree (nested dissection of $K$'s pattern by the DOF positions,
    /// parts of at most `leaf` unknowns left whole).
    pub fn substructure_tree(&self, leaf: usize) -> Option<crate::linalg::SubstructureTree> {
        crate::linalg::SubstructureTree::new(self.k.as_faer(), &self.dof_positions(), leaf)
    }

    /// `node 3 y` (or `node 3 θz`) style label of a DOF.
    pub fn dof_label(&self, dof: usize) -> String {
        let (node, d) = self.dof_node(dof);
        format!("{node} {}", d.name())
    }

    /// The stiffness as a dense matrix (for the small bodies' dense path).
    pub fn k_dense(&self) -> Mat<f64> {
        self.k.to_dense()
    }

    /// The mass as a dense matrix (for the small bodies' dense path).
    pub fn m_dense(&self) -> Mat<f64> {
        self.m.to_dense()
    }

    /// Number of stored stiffness entries (both triangles).
    pub fn stiffness_nnz(&self) -> usize {
        self.k.nnz()
    }

    /// Total mass (kg) as seen by a rigid translation along x.
    pub fn total_mass(&self) -> f64 {
        let n = self.dof_count();
        let mut t = Mat::<f64>::zeros(n, 1);
        for i in 0..self.node_count() {
            if let Some(d) = self.dofs.index(i, NodeDof::Translation(Direction::X)) {
                t[(d, 0)] = 1.0;
            }
        }
        let mt = self.m.mul(t.as_ref());
        (t.transpose() * &mt)[(0, 0)]
    }

    /// Mass centre (m) from the complete mass matrix (see [`MassProperties`]).
    pub fn mass_centre(&self) -> [f64; 3] {
        self.mass_properties().centre
    }

    /// Mass, mass centre and inertia tensor from the complete mass matrix.
    pub fn mass_properties(&self) -> MassProperties {
        MassProperties::of(self)
    }

    /// Rigid-body motions as columns: translations, then small rotations about the origin
    /// (one in the plane, three in space), on every DOF of the map (a rotation DOF takes the
    /// rotation's component).
    pub fn rigid_body_modes(&self) -> Mat<f64> {
        let count = self.dofs.rigid_body_count();
        let per = self.dofs.per_node();
        Mat::from_fn(self.dof_count(), count, |row, k| {
            let (t, w) = self.dofs.rigid_motion(k);
            self.dofs.node_dofs()[row % per].rigid_motion(self.nodes[row / per], t, w)
        })
    }

    /// How far the rigid-body motions $R$ are from K's null space, relative to the data:
    /// $\max|KR| / (\max|K| \max|R|)$. Round-off of an exact assembly leaves ~1e-16; a
    /// matrix written with 11 significant digits (Nastran's 16-column fields) ~1e-11; a body
    /// restrained before export order one.
    pub fn rigid_motion_defect(&self) -> f64 {
        let r = self.rigid_body_modes();
        let kr = self.k.mul(r.as_ref());
        let max = |a: &Mat<f64>| {
            (0..a.ncols())
                .flat_map(|j| (0..a.nrows()).map(move |i| (i, j)))
                .fold(0.0f64, |m, (i, j)| m.max(a[(i, j)].abs()))
        };
        max(&kr) / (self.k.max_abs() * max(&r)).max(f64::MIN_POSITIVE)
    }

    /// The `count` nodes (1-based) where the coordinates' rigid motions are farthest from
    /// K's null space, with their share of [`Self::rigid_motion_defect`]: per node, the
    /// largest $|KR|$ on its DOF over $\max|K|\max|R|$, largest first. Where an FE code
    /// moved nodes after writing the mesh (CalculiX repositions mid-side nodes of distorted
    /// quadratic elements), these are the moved nodes and their neighbours.
    pub fn rigid_motion_residual_nodes(&self, count: usize) -> Vec<(usize, f64)> {
        let r = self.rigid_body_modes();
        let kr = self.k.mul(r.as_ref());
        let mut r_max = 0.0f64;
        for j in 0..r.ncols() {
            for i in 0..r.nrows() {
                r_max = r_max.max(r[(i, j)].abs());
            }
        }
        let scale = (self.k.max_abs() * r_max).max(f64::MIN_POSITIVE);
        let per = self.dofs.per_node().max(1);
        let mut nodes: Vec<(usize, f64)> = (0..self.node_count())
            .map(|node| {
                let worst = (node * per..(node + 1) * per)
                    .flat_map(|i| (0..kr.ncols()).map(move |j| (i, j)))
                    .fold(0.0f64, |m, (i, j)| m.max(kr[(i, j)].abs()));
                (node + 1, worst / scale)
            })
            .collect();
        nodes.sort_by(|a, b| b.1.total_cmp(&a.1));
        nodes.truncate(count);
        nodes
    }

    /// Node positions displaced by a DOF vector `u` scaled by `scale`.
    pub fn displaced(&self, u: &[f64], scale: f64) -> Vec<[f64; 3]> {
        self.nodes
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let mut q = *p;
                let base = i * self.dofs.per_node();
                for (dir, o) in self.dofs.translations() {
                    q[dir.index()] += scale * u[base + o];
                }
                q
            })
            .collect()
    }

    /// Characteristic size (m): the largest extent of the undeformed body.
    pub fn size(&self) -> f64 {
        let mut ext = 0.0f64;
        for d in 0..3 {
            let lo = self
                .nodes
                .iter()
                .map(|p| p[d])
                .fold(f64::INFINITY, f64::min);
            let hi = self
                .nodes
                .iter()
                .map(|p| p[d])
                .fold(f64::NEG_INFINITY, f64::max);
            ext = ext.max(hi - lo);
        }
        ext
    }
}
