//! Interpolating (RBE3) interfaces: a 6-DOF master node whose motion is the weighted average
//! of a node set's, as FE codes define it. It adds no stiffness: the ring stays as free as it
//! was. A force on the master reaches the ring distributed by the same weights, so the
//! interface is a place to load the body and to read its averaged motion, not a joint that
//! holds it.
//!
//! The master's motion is the weighted least-squares rigid motion of the ring,
//! $q_m = \arg\min \sum_s w_s\,|u_s - (u_m + \theta_m \times r_s)|^2 = (R^TDR)^{-1}R^TD\,u_S
//! = A\,u_S$ ($R$ the ring's rigid-motion matrix, $D$ the weights on every DOF of a node);
//! a master load $F_m$ reaches the ring as $f_S = A^TF_m$, doing the same virtual work.

use crate::error::{DofSetName, DofSetProblem};
use faer::Mat;

use super::rigid_interface::rigid_motion_rows;
use crate::{Result, error::ReductionError, fem::FeModel};

/// A node set averaged into a master node.
#[derive(Debug, Clone, PartialEq)]
pub struct AveragingInterface {
    /// The interface's name.
    pub name: String,
    /// The averaged nodes, 1-based.
    pub nodes: Vec<usize>,
    /// The master point, in the body's length unit.
    pub master: [f64; 3],
    /// One weight per node (the same on each of its DOF), positive.
    pub weights: Vec<f64>,
}

impl AveragingInterface {
    /// `nodes` averaged with `weights` (`None`: all 1) into a master at their centroid.
    pub fn at_centroid(
        model: &FeModel,
        name: &str,
        nodes: &[usize],
        weights: Option<Vec<f64>>,
    ) -> Result<Self> {
        let set = || DofSetName::Interface {
            kind: "rbe3",
            name: name.into(),
        };
        if nodes.is_empty() {
            return Err(ReductionError::InvalidDofSet {
                set: set(),
                problem: DofSetProblem::NoNodes,
            }
            .into());
        }
        let weights = weights.unwrap_or_else(|| vec![1.0; nodes.len()]);
        if weights.len() != nodes.len() {
            return Err(ReductionError::InvalidDofSet {
                set: set(),
                problem: DofSetProblem::WeightCount {
                    weights: weights.len(),
                    nodes: nodes.len(),
                },
            }
            .into());
        }
        if let Some((k, w)) = weights
            .iter()
            .enumerate()
            .find(|(_, w)| !(w.is_finite() && **w > 0.0))
        {
            return Err(ReductionError::InvalidDofSet {
                set: set(),
                problem: DofSetProblem::NonPositiveWeight {
                    node: nodes[k],
                    weight: *w,
                },
            }
            .into());
        }
        let mut centre = [0.0; 3];
        for &n in nodes {
            let x = model.position(model.node_index(n)?);
            for d in 0..3 {
                centre[d] += x[d] / nodes.len() as f64;
            }
        }
        Ok(Self {
            name: name.into(),
            nodes: nodes.to_vec(),
            master: centre,
            weights,
        })
    }

    /// $A^T$ row by row: for every DOF of the ring (0-based, in node order), its six
    /// coefficients in the master's motion $q_m = A u_S$ (equally: the load it takes from a
    /// unit master force or moment). Fails with the reason when the ring does not fix a rigid
    /// motion (all its nodes on one line, say).
    pub fn averaging_rows(&self, model: &FeModel) -> Result<Vec<(usize, [f64; 6])>> {
        let rows = rigid_motion_rows(model, &self.nodes, self.master)?;
        let per_node = rows.len() / self.nodes.len();
        // RᵀDR, 6 × 6, scaled so that translations and rotations weigh alike.
        let mut rtdr = nalgebra::Matrix6::<f64>::zeros();
        for (k, (_, r)) in rows.iter().enumerate() {
            let w = self.weights[k / per_node];
            for a in 0..6 {
                for b in 0..6 {
                    rtdr[(a, b)] += w * r[a] * r[b];
                }
            }
        }
        let scale = nalgebra::Matrix6::from_diagonal(&nalgebra::Vector6::from_fn(|a, _| {
            1.0 / rtdr[(a, a)].max(f64::MIN_POSITIVE).sqrt()
        }));
        let scaled = scale * rtdr * scale;
        let eig = scaled.symmetric_eigenvalues();
        let (lo, hi) = eig
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), &e| (l.min(e), h.max(e)));
        // Written so that NaN (a degenerate ring) fails too.
        if lo.is_nan() || lo <= 1e-10 * hi {
            return Err(ReductionError::InvalidDofSet {
                set: DofSetName::Interface {
                    kind: "rbe3",
                    name: (&self.name).into(),
                },
                problem: DofSetProblem::NoRigidMotion {
                    nodes: self.nodes.len(),
                    condition: hi / lo.max(f64::MIN_POSITIVE),
                },
            }
            .into());
        }
        let inverse = scale
            * scaled
                .try_inverse()
                .expect("positive definite: checked above")
            * scale;
        Ok(rows
            .iter()
            .enumerate()
            .map(|(k, (dof, r))| {
                let w = self.weights[k / per_node];
                let row = nalgebra::Vector6::from_row_slice(r);
                let a = inverse * row * w;
                (*dof, [a[0], a[1], a[2], a[3], a[4], a[5]])
            })
            .collect())
    }

    /// $A$ as a dense 6 × n matrix over all the body's DOF.
    pub fn averaging_matrix(&self, model: &FeModel) -> Result<Mat<f64>> {
        let mut a = Mat::<f64>::zeros(6, model.dof_count());
        for (dof, row) in self.averaging_rows(model)? {
            for (q, v) in row.iter().enumerate() {
                a[(q, dof)] = *v;
            }
        }
        Ok(a)
    }
}
