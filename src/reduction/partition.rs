//! The boundary/interior split of Eq. (6.1) and the modes every CMS method builds on.

use faer::{Mat, MatRef};

use crate::{
    Error, Result,
    fem::FeModel,
    linalg::{GeneralizedEigen, InteriorStiffness, generalized_eigen, select},
};

/// DOF sets b (boundary) and i (interior) of Eq. (6.1).
#[derive(Debug, Clone, PartialEq)]
pub struct Partition {
    /// Boundary nodes, 1-based, in the order given.
    pub boundary_nodes: Vec<usize>,
    /// Boundary DOF indices (set b), node by node.
    pub b: Vec<usize>,
    /// Interior DOF indices (set i), ascending.
    pub i: Vec<usize>,
    /// DOF per node of the body.
    pub dim: usize,
}

impl Partition {
    /// Splits `model`'s DOF by the 1-based `boundary_nodes`.
    pub fn new(model: &FeModel, boundary_nodes: &[usize]) -> Result<Self> {
        if boundary_nodes.is_empty() {
            return Err(Error::InvalidBoundary {
                nodes: vec![],
                reason: "at least one boundary node is needed".into(),
            });
        }
        let b = model.dofs_of_nodes(boundary_nodes)?;
        let i: Vec<usize> = (0..model.dof_count()).filter(|d| !b.contains(d)).collect();
        if i.is_empty() {
            return Err(Error::InvalidBoundary {
                nodes: boundary_nodes.to_vec(),
                reason: "every node is a boundary node, nothing is left to reduce".into(),
            });
        }
        Ok(Self {
            boundary_nodes: boundary_nodes.to_vec(),
            b,
            i,
            dim: model.dim,
        })
    }

    /// `a[rows, cols]` for two of the sets.
    pub fn block(&self, a: MatRef<'_, f64>, rows: Set, cols: Set) -> Mat<f64> {
        select(a, self.set(rows), self.set(cols))
    }

    fn set(&self, s: Set) -> &[usize] {
        match s {
            Set::B => &self.b,
            Set::I => &self.i,
        }
    }

    /// Places a boundary block (rows of b) and an interior block (rows of i) into a Ψ with
    /// the body's DOF order.
    pub fn assemble(&self, top: MatRef<'_, f64>, bottom: MatRef<'_, f64>) -> Mat<f64> {
        assert_eq!(top.ncols(), bottom.ncols());
        let n = self.b.len() + self.i.len();
        let mut psi = Mat::zeros(n, top.ncols());
        for c in 0..top.ncols() {
            for (r, &dof) in self.b.iter().enumerate() {
                psi[(dof, c)] = top[(r, c)];
            }
            for (r, &dof) in self.i.iter().enumerate() {
                psi[(dof, c)] = bottom[(r, c)];
            }
        }
        psi
    }
}

/// A DOF set of the partition.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Set {
    /// Boundary.
    B,
    /// Interior.
    I,
}

/// Fixed-interface (fixed-constraint) normal modes, $[\Psi_n, \Lambda_n] =
/// \mathrm{eig}(K_{ii}, M_{ii})$ (Eq. 6.11), mass-normalised, ascending.
pub fn fixed_interface_modes(model: &FeModel, p: &Partition) -> Result<GeneralizedEigen> {
    let k_ii = p.block(model.k.as_ref(), Set::I, Set::I);
    let m_ii = p.block(model.m.as_ref(), Set::I, Set::I);
    generalized_eigen(k_ii.as_ref(), m_ii.as_ref(), "fixed-interface")
}

/// Static constraint modes' interior part $\Psi_s = -K_{ii}^{-1}K_{ib}$ (Eq. 6.3).
pub fn constraint_modes(model: &FeModel, p: &Partition) -> Result<Mat<f64>> {
    let k_ii = p.block(model.k.as_ref(), Set::I, Set::I);
    let k_ib = p.block(model.k.as_ref(), Set::I, Set::B);
    let f = InteriorStiffness::factor(k_ii.as_ref(), &p.boundary_nodes, p.dim)?;
    Ok(-f.solve(k_ib.as_ref()))
}

/// Column descriptions of the boundary columns (one per boundary DOF).
pub(crate) fn boundary_columns(
    model: &FeModel,
    p: &Partition,
    kind: super::ColumnKind,
    prefix: &str,
) -> Vec<super::Column> {
    p.b.iter()
        .map(|&dof| super::Column {
            kind: kind.clone(),
            dof: Some(dof),
            label: format!("{prefix} {}", model.dof_label(dof)),
        })
        .collect()
}

/// Column descriptions of kept normal modes.
pub(crate) fn normal_columns(hz: &[f64]) -> Vec<super::Column> {
    hz.iter()
        .enumerate()
        .map(|(k, &hz)| super::Column {
            kind: super::ColumnKind::Normal { hz },
            dof: None,
            label: format!("normal {} ({hz:.4} Hz)", k + 1),
        })
        .collect()
}
