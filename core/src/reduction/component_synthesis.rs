//! Component mode synthesis (Craig 1981, the "standard CMS procedure" of Spanos–Tsuha): each
//! component in its own Ritz coordinates, joined by equal displacements at shared nodes.

use super::ReductionError;
use crate::error::{DofSetName, DofSetProblem};
use faer::Mat;

use crate::{
    Error, Result,
    fem::{FeModel, NodeIndex},
};

/// One component of an assembly: its body, a Ritz basis on its DOF (zero rows where it is
/// held) and, per local node, the assembly node it is (0-based).
#[derive(Debug, Clone)]
pub struct Component<'a> {
    /// The component's body.
    pub model: &'a FeModel,
    /// $\Phi_c$, component DOF × component coordinates.
    pub basis: Mat<f64>,
    /// Assembly node of each local node (0-based).
    pub nodes: Vec<usize>,
}

/// An assembled Ritz model: the stacked component coordinates $q = Nw$ with $N$ the null space
/// of the compatibility conditions $\Phi_a[\text{shared}]\,q_a = \Phi_b[\text{shared}]\,q_b$,
/// and $K = N^T\mathrm{diag}(\Phi_c^TK_c\Phi_c)N$, $M$ likewise plus rigid bodies' masses.
#[derive(Debug, Clone)]
pub struct Synthesis {
    /// Assembled stiffness, w × w.
    pub k: Mat<f64>,
    /// Assembled mass, w × w.
    pub m: Mat<f64>,
    /// Per assembly node: (component, local node) owning it first.
    owner: Vec<Option<(usize, usize)>>,
    /// Coordinate offset of each component in q.
    offsets: Vec<usize>,
    /// The component bases.
    bases: Vec<Mat<f64>>,
    /// $N$, q × w.
    null: Mat<f64>,
    /// DOF per node.
    per_node: usize,
}

/// The components' reduced stiffness and mass side by side on the diagonal (`total`
/// coordinates, each component's from its offset).
fn block_diagonal(
    components: &[Component<'_>],
    offsets: &[usize],
    total: usize,
) -> (Mat<f64>, Mat<f64>) {
    let mut kq = Mat::<f64>::zeros(total, total);
    let mut mq = Mat::<f64>::zeros(total, total);
    for (ci, comp) in components.iter().enumerate() {
        let phi = &comp.basis;
        let kc = phi.transpose() * comp.model.k.mul(phi.as_ref());
        let mc = phi.transpose() * comp.model.m.mul(phi.as_ref());
        let o = offsets[ci];
        for i in 0..phi.ncols() {
            for j in 0..phi.ncols() {
                kq[(o + i, o + j)] = kc[(i, j)];
                mq[(o + i, o + j)] = mc[(i, j)];
            }
        }
    }
    (kq, mq)
}

impl Synthesis {
    /// Joins `components` (all with the same DOF per node) at the assembly nodes they share
    /// and adds each rigid body (assembly node, 6 × 6 mass about that node's DOF).
    pub fn new(components: &[Component<'_>], rigid_bodies: &[(usize, Mat<f64>)]) -> Result<Self> {
        let per_node = components
            .first()
            .map(|c| c.model.dofs.per_node())
            .unwrap_or(0);
        let nodes = components
            .iter()
            .flat_map(|c| c.nodes.iter().copied())
            .max()
            .map_or(0, |n| n + 1);
        let mut offsets = Vec::with_capacity(components.len());
        let mut total = 0;
        for (ci, c) in components.iter().enumerate() {
            // The first of its maps whose length is not the component's.
            let shapes = [
                ("DOF per node", c.model.dofs.per_node(), per_node),
                ("nodes mapped", c.nodes.len(), c.model.node_count()),
                ("rows of its basis", c.basis.nrows(), c.model.dof_count()),
            ];
            if let Some(&(what, found, expected)) = shapes.iter().find(|(_, f, e)| f != e) {
                return Err(Error::Reduction(ReductionError::InvalidDofSet {
                    set: DofSetName::Numbered {
                        what: "component",
                        number: ci + 1,
                    },
                    problem: DofSetProblem::Shape {
                        what,
                        found,
                        expected,
                    },
                }));
            }
            offsets.push(total);
            total += c.basis.ncols();
        }
        // Compatibility: every later owner of a node equals its first owner, DOF by DOF.
        let mut owner: Vec<Option<(usize, usize)>> = vec![None; nodes];
        let mut rows: Vec<Vec<f64>> = Vec::new();
        for (ci, c) in components.iter().enumerate() {
            for (local, &global) in c.nodes.iter().enumerate() {
                match owner[global] {
                    None => owner[global] = Some((ci, local)),
                    Some((cj, lj)) => {
                        for d in 0..per_node {
                            let mut row = vec![0.0; total];
                            for q in 0..c.basis.ncols() {
                                row[offsets[ci] + q] += c.basis[(local * per_node + d, q)];
                            }
                            let other = &components[cj].basis;
                            for q in 0..other.ncols() {
                                row[offsets[cj] + q] -= other[(lj * per_node + d, q)];
                            }
                            rows.push(row);
                        }
                    }
                }
            }
        }
        let c = Mat::from_fn(rows.len(), total, |r, q| rows[r][q]);
        let scale = components
            .iter()
            .map(|c| crate::linalg::max_abs(c.basis.as_ref()))
            .fold(0.0f64, f64::max)
            .max(f64::MIN_POSITIVE);
        let null = crate::linalg::null_space(c.as_ref(), 1e-10 * scale)?;
        // Block-diagonal component matrices, then the congruence with N.
        let (kq, mq) = block_diagonal(components, &offsets, total);
        let mut synthesis = Self {
            k: Mat::zeros(0, 0),
            m: Mat::zeros(0, 0),
            owner,
            offsets,
            bases: components.iter().map(|c| c.basis.clone()).collect(),
            null,
            per_node,
        };
        let sym = |a: Mat<f64>| {
            let n = a.nrows();
            Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
        };
        let n = &synthesis.null;
        synthesis.k = sym(n.transpose() * &kq * n);
        let mut m = n.transpose() * &mq * n;
        for (node, mass) in rigid_bodies {
            let t = synthesis.node_rows(*node)?;
            m += t.transpose() * mass * &t;
        }
        synthesis.m = sym(m);
        Ok(synthesis)
    }

    /// Number of assembled coordinates w.
    pub fn size(&self) -> usize {
        self.k.nrows()
    }

    /// The rows mapping w to the displacements of an assembly node's DOF (per_node × w).
    pub fn node_rows(&self, node: usize) -> Result<Mat<f64>> {
        let (ci, local) = self
            .owner
            .get(node)
            .copied()
            .flatten()
            .ok_or(Error::NodeOutOfRange {
                node: NodeIndex(node).number(),
                count: self.owner.len(),
                body: "assembly".into(),
            })?;
        let basis = &self.bases[ci];
        let o = self.offsets[ci];
        let rows = Mat::from_fn(self.per_node, self.null.nrows(), |d, q| {
            if q >= o && q < o + basis.ncols() {
                basis[(local * self.per_node + d, q - o)]
            } else {
                0.0
            }
        });
        Ok(&rows * &self.null)
    }

    /// The row of one assembly DOF (node, local DOF index), 1 × w.
    pub fn dof_row(&self, node: usize, dof: usize) -> Result<Mat<f64>> {
        let rows = self.node_rows(node)?;
        Ok(rows.subrows(dof, 1).to_owned())
    }
}
