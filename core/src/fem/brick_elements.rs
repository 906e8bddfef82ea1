//! The bricks of a mesh with their material: what a body needs, beyond its $K$ and $M$, to
//! form the geometric stiffness of a prestress.

use super::{
    SlabParameters,
    hex8_geometric::{hex8_geometric_stiffness, hex8_stresses},
    slab_bricks,
};
use crate::{
    Result,
    error::MeshError,
    linalg::{SparseAssembly, SparseSymmetric, SparsityPattern},
};

/// Trilinear bricks (node lists in the local order of
/// [`LOCAL_NODES`](super::HEX8_LOCAL_NODES), 0-based) of one isotropic material.
#[derive(Debug, Clone, PartialEq)]
pub struct BrickElements {
    /// The bricks' nodes, 0-based.
    pub bricks: Vec<[usize; 8]>,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
}

impl BrickElements {
    /// The bricks of [`slab`](super::slab) and [`plank`](super::plank) meshed with `p`.
    pub fn of_slab(p: &SlabParameters) -> Self {
        Self {
            bricks: slab_bricks(p),
            youngs_modulus: p.youngs_modulus,
            poisson_ratio: p.poisson_ratio,
        }
    }

    /// The geometric stiffness (N/m) of the stresses of the displacement `u` (3 per node,
    /// node-major, m) of the mesh with node positions `nodes` (m): the sum of each brick's
    /// [`hex8_geometric_stiffness`] at its Gauss-point stresses. A brick naming a node the
    /// mesh does not have, or a `u` of another length, is [`MeshError::ElementsMismatch`].
    pub fn geometric_stiffness(&self, nodes: &[[f64; 3]], u: &[f64]) -> Result<SparseSymmetric> {
        let n = nodes.len();
        if let Some(node) = self.bricks.iter().flatten().find(|&&c| c >= n) {
            return Err(MeshError::ElementsMismatch {
                what: "a brick names node",
                value: node + 1,
                available: n,
            }
            .into());
        }
        if u.len() != 3 * n {
            return Err(MeshError::ElementsMismatch {
                what: "displacement values",
                value: u.len(),
                available: 3 * n,
            }
            .into());
        }
        let pattern =
            SparsityPattern::from_elements(n, 3, self.bricks.iter().map(|c| c.as_slice()));
        let mut assembly = SparseAssembly::new(pattern);
        for conn in &self.bricks {
            let x = conn.map(|c| nodes[c]);
            let ue: [f64; 24] = std::array::from_fn(|k| u[3 * conn[k / 3] + k % 3]);
            let stresses = hex8_stresses(&x, self.youngs_modulus, self.poisson_ratio, &ue);
            let dofs: Vec<usize> = conn
                .iter()
                .flat_map(|&c| [3 * c, 3 * c + 1, 3 * c + 2])
                .collect();
            assembly.add_element(&dofs, hex8_geometric_stiffness(&x, &stresses).as_ref());
        }
        Ok(assembly.finish())
    }
}
