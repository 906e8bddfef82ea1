//! The loads a body takes through its interfaces: the input matrix $B_1$ of the reduced
//! methods that are built from loads (moment matching, balanced truncation) rather than from
//! unit boundary motions.

use faer::Mat;

use super::{AveragingInterface, MASTER_DOF_NAMES, RigidInterface};
use crate::{Result, fem::FeModel};

/// $B_1$ over all DOF, one labelled column per load.
#[derive(Debug, Clone)]
pub struct InterfaceLoads {
    /// n × p: column j is the nodal force vector of load j (N per unit load).
    pub matrix: Mat<f64>,
    /// One label per column: a DOF's (`node 12 x`) or a master's (`rbe2 bore_a θz`).
    pub labels: Vec<String>,
}

impl InterfaceLoads {
    /// A unit force on each of `dofs` (plain boundary DOF, 0-based), then each rigid
    /// interface's six master loads: a unit master force or moment $F_m$ reaches the ring as
    /// $f_S = R_S F_m$, $R_S$ the ring's rigid-motion matrix ($u_S = R_S q_m$; the virtual
    /// work $f_S^T u_S = F_m^T q_m$ is the master's); then each averaging (RBE3) interface's
    /// six, distributed by its weights, $f_S = A^T F_m$.
    pub fn of(
        model: &FeModel,
        dofs: &[usize],
        interfaces: &[RigidInterface],
        averaging: &[AveragingInterface],
    ) -> Result<Self> {
        let n = model.dof_count();
        let p = dofs.len() + 6 * (interfaces.len() + averaging.len());
        let mut matrix = Mat::<f64>::zeros(n, p);
        let mut labels = Vec::with_capacity(p);
        for (c, &d) in dofs.iter().enumerate() {
            matrix[(d, c)] = 1.0;
            labels.push(model.dof_label(d));
        }
        for (k, interface) in interfaces.iter().enumerate() {
            let first = dofs.len() + 6 * k;
            let rows = interface.rigid_motions(model)?;
            for (dof, row) in rows {
                for (q, w) in row.iter().enumerate() {
                    matrix[(dof, first + q)] = *w;
                }
            }
            labels.extend(
                MASTER_DOF_NAMES
                    .iter()
                    .map(|q| format!("rbe2 {} {q}", interface.name)),
            );
        }
        for (k, interface) in averaging.iter().enumerate() {
            let first = dofs.len() + 6 * (interfaces.len() + k);
            for (dof, row) in interface.averaging_rows(model)? {
                for (q, w) in row.iter().enumerate() {
                    matrix[(dof, first + q)] = *w;
                }
            }
            labels.extend(
                MASTER_DOF_NAMES
                    .iter()
                    .map(|q| format!("rbe3 {} {q}", interface.name)),
            );
        }
        Ok(Self { matrix, labels })
    }

    /// Number of loads.
    pub fn count(&self) -> usize {
        self.labels.len()
    }
}
